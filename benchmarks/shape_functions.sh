#!/bin/bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The shape functions and the mass matrix of the implicit scheme against
# each other (doc/validation.md): the energy one wall impact of
# prm/single_grain_rebound_implicit.prm (to t = 0.45) loses on 25, 50, 100
# and 200 cells, the energy the shipped single grain keeps at t = 2 and the
# shipped implicit two disks at t = 3.5, and the Newton and GMRES
# iterations of the single grain, for Material points/Shape functions =
# linear, uGIMP, cpGIMP and Time stepping/Mass matrix = lumped, blended
# (Consistent mass fraction 0.95; about ten minutes).
#
# Usage: bash benchmarks/shape_functions.sh [build directory=build]

# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

echo "Implicit theta = 1/2, CFL 2.5. Impact: 1 - E(end)/E(0) in % after one wall impact of the single grain (t = 0.45)"
echo "on 25 to 200 cells; E(2)/E(0) of the shipped single grain (50 cells), E(end)/E(0) of the shipped two disks (20 cells);"
echo "Newton iterations per step and GMRES iterations per Newton iteration of the single grain."
echo
echo "| shape functions | mass matrix | 25 cells | 50 cells | 100 cells | 200 cells | single grain E(2)/E(0) | two disks E(end)/E(0) | Newton / step | GMRES / Newton |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for setting in "linear lumped" "uGIMP lumped" "linear blended" "uGIMP blended" "cpGIMP blended"; do
  read -r kernel mass <<< "$setting"
  choice="subsection Material points\n  set Shape functions = $kernel\nend\nsubsection Time stepping\n  set Mass matrix = $mass\nend"
  row="| $kernel | $mass |"
  for n in 25 50 100 200; do
    run "${kernel}_${mass}_$n" single_grain_rebound_implicit "$choice\nsubsection Background grid\n  set Number of cells = $n, $n\nend\nsubsection Time stepping\n  set End time = 0.45\nend"
    row="$row $(awk -v e="$(figure "${kernel}_${mass}_$n" total_energy_end)" 'BEGIN { printf "%.1f", 100 * (1 - e) }') |"
  done
  run "${kernel}_${mass}_t2" single_grain_rebound_implicit "$choice"
  run "${kernel}_${mass}_disks" two_disks_implicit "$choice"
  echo "$row $(figure "${kernel}_${mass}_t2" total_energy_end) | $(figure "${kernel}_${mass}_disks" total_energy_end) | $(figure "${kernel}_${mass}_t2" newton_iterations_per_step) | $(figure "${kernel}_${mass}_t2" linear_iterations_per_newton_iteration) |"
done
