#!/bin/bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The shape functions against each other (doc/validation.md): the energy
# one wall impact of prm/single_grain_rebound_implicit.prm (to t = 0.45)
# loses on 25, 50, 100 and 200 cells, and the energy the shipped case
# keeps at t = 2, for Material points/Shape functions = linear, uGIMP and
# cpGIMP (a few minutes).
#
# Usage: bash benchmarks/shape_functions.sh [build directory=build]

set -e
build=${1:-build}
grainmpm=$(cd "$build" && pwd)/source/grainmpm
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source benchmarks/common/run_case.sh

echo "Single grain, implicit CFL 2.5: 1 - E(end)/E(0) after one wall impact (t = 0.45), in %, and E(2)/E(0) on 50 cells"
echo
echo "| shape functions | 25 cells | 50 cells | 100 cells | 200 cells | E(2)/E(0) |"
echo "|---|---|---|---|---|---|"
for kernel in linear uGIMP cpGIMP; do
  row="| $kernel |"
  for n in 25 50 100 200; do
    run "${kernel}_$n" single_grain_rebound_implicit "subsection Material points\n  set Shape functions = $kernel\nend\nsubsection Background grid\n  set Number of cells = $n, $n\nend\nsubsection Time stepping\n  set End time = 0.45\nend"
    row="$row $(awk -v e="$(value "${kernel}_$n" "E_total(end)")" 'BEGIN { printf "%.1f", 100 * (1 - e) }') |"
  done
  run "${kernel}_t2" single_grain_rebound_implicit "subsection Material points\n  set Shape functions = $kernel\nend"
  echo "$row $(value "${kernel}_t2" "E_total(end)") |"
done
