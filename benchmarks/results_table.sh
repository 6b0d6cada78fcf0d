#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The figures of doc/results.md, from the shipped cases: the single grain
# between walls (explicit CFL 0.25, implicit CFL 2.5) to t = 2 and the five
# grains (explicit, implicit) to t = 50 us, plus the five-grain frictionless
# control at three time steps and on a grid twice as fine. Prints energies
# relative to E(0), the energy ledger, the spurious elastic energy ratio
# and the rebound speeds, and the single-grain transfer loss of one impact
# on three grids. Not a test: it prints figures (about 1.5
# minutes on one core).
#
# Usage: benchmarks/results_table.sh [build directory=build]
# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

# ledger NAME: the energy ledger of the run as the screen summary prints
# it (the leapfrog term for the explicit scheme only).
ledger() {
  local leapfrog=""
  if [ "$(exact "$1" implicit_scheme)" = 0 ]; then
    leapfrog=", leapfrog = $(figure "$1" leapfrog_work)"
  fi
  echo "plastic work = $(figure "$1" plastic_work), friction work = $(figure "$1" friction_work), boundary work = $(figure "$1" boundary_work), transfers = $(figure "$1" transfer_work)$leapfrog, balance residual = $(figure "$1" balance_residual) (largest $(figure "$1" largest_balance_residual))"
}

echo "| run | E(end)/E(0) | E_el(end)/E(0) | ledger / E(0) | rebound speeds |"
echo "|---|---|---|---|---|"
for case in single_grain_rebound_explicit single_grain_rebound_implicit five_grains_explicit five_grains_implicit; do
  run "$case" "$case" "subsection Output\n  set Output interval = 0.05\nend"
  speed=""
  case $case in single_grain*) speed=$(speeds "$case") ;; esac
  echo "| $case | $(figure "$case" total_energy_end) | $(figure "$case" elastic_energy_end) | $(ledger "$case") | $speed |"
done
explicit_el=$(figure single_grain_rebound_explicit elastic_energy_end)
implicit_el=$(figure single_grain_rebound_implicit elastic_energy_end)
echo
echo "Spurious elastic energy at t = 2, explicit / implicit: $(awk -v a="$explicit_el" -v b="$implicit_el" 'BEGIN { printf "%.0f", a / b }')"
echo
echo "Five grains without friction (implicit):"
echo
echo "| run | E(end)/E(0) | ledger / E(0) |"
echo "|---|---|---|"
frictionless="subsection Contact\n  set Contact model = frictionless\n  set Friction coefficient = 0\nend"
for dt in 0.25 0.5 1; do
  run "mu0_$dt" five_grains_implicit "$frictionless\nsubsection Time stepping\n  set Time step = $dt\nend"
  echo "| dt = $dt us, h = 0.8 mm | $(figure "mu0_$dt" total_energy_end) | $(ledger "mu0_$dt") |"
done
run mu0_fine five_grains_implicit "$frictionless\nsubsection Background grid\n  set Number of cells = 200, 126\nend"
echo "| dt = 0.5 us, h = 0.4 mm | $(figure mu0_fine total_energy_end) | $(ledger mu0_fine) |"
echo
echo "Single grain, implicit CFL 2.5, one wall impact (t = 0.45), against the grid:"
echo
echo "| cells | E(end)/E(0) | ledger / E(0) |"
echo "|---|---|---|"
for n in 25 50 100; do
  run "grain_$n" single_grain_rebound_implicit "subsection Background grid\n  set Number of cells = $n, $n\nend\nsubsection Time stepping\n  set End time = 0.45\nend"
  echo "| $n x $n | $(figure "grain_$n" total_energy_end) | $(ledger "grain_$n") |"
done
