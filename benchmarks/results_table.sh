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

# ledger NAME: the ledger line of the summary, without its label.
ledger() {
  grep -F "energy ledger" "$work/$1.out" | sed 's/.*): //'
}

echo "| run | E(end)/E(0) | E_el(end)/E(0) | ledger / E(0) | rebound speeds |"
echo "|---|---|---|---|---|"
for case in single_grain_rebound_explicit single_grain_rebound_implicit five_grains_explicit five_grains_implicit; do
  run "$case" "$case" "subsection Output\n  set Output interval = 0.05\nend"
  speed=""
  case $case in single_grain*) speed=$(speeds "$case") ;; esac
  echo "| $case | $(value "$case" "E_total(end)") | $(value "$case" "E_el(end)") | $(ledger "$case") | $speed |"
done
explicit_el=$(value single_grain_rebound_explicit "E_el(end)")
implicit_el=$(value single_grain_rebound_implicit "E_el(end)")
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
  echo "| dt = $dt us, h = 0.8 mm | $(value "mu0_$dt" "E_total(end)") | $(ledger "mu0_$dt") |"
done
run mu0_fine five_grains_implicit "$frictionless\nsubsection Background grid\n  set Number of cells = 200, 126\nend"
echo "| dt = 0.5 us, h = 0.4 mm | $(value mu0_fine "E_total(end)") | $(ledger mu0_fine) |"
echo
echo "Single grain, implicit CFL 2.5, one wall impact (t = 0.45), against the grid:"
echo
echo "| cells | E(end)/E(0) | ledger / E(0) |"
echo "|---|---|---|"
for n in 25 50 100; do
  run "grain_$n" single_grain_rebound_implicit "subsection Background grid\n  set Number of cells = $n, $n\nend\nsubsection Time stepping\n  set End time = 0.45\nend"
  echo "| $n x $n | $(value "grain_$n" "E_total(end)") | $(ledger "grain_$n") |"
done
