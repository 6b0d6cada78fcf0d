#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# GMRES iterations per Newton step under grid refinement: the one disk of
# prm/slow_compression_one_disk.prm under a slow platen, implicit theta =
# 1/2 at 100 times the explicit CFL 0.25 step of each grid (32, 64, 128
# and 256 cells per side; the step halves with the cell), 20 steps, with
# Linear solver/Preconditioner = probed Jacobi and AMG. Prints wall time,
# Newton iterations per step and GMRES iterations per Newton step, and the
# growth of the latter from N to 2N cells. Not a test: it prints figures
# (about 1 minute).
#
# Usage: benchmarks/preconditioner_refinement.sh [build directory=build]
# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

echo "| preconditioner | cells per side | dt | wall time [s] | Newton/step | GMRES/Newton | growth from N/2 |"
echo "|---|---|---|---|---|---|---|"
for preconditioner in "probed Jacobi" AMG; do
  previous=""
  for cells in 32 64 128 256; do
    step=$(python3 -c "print(100 * 1.0633e-4 * 64 / $cells)")
    end=$(python3 -c "print(20 * $step)")
    name="${preconditioner// /_}_$cells"
    start=$(date +%s.%N)
    run "$name" slow_compression_one_disk \
      "subsection Background grid\n  set Number of cells = $cells, $cells\nend\nsubsection Time stepping\n  set Time step = $step\n  set Maximum CFL number = 0\n  set End time = $end\nend\nsubsection Linear solver\n  set Preconditioner = $preconditioner\nend"
    seconds=$(python3 -c "print(f'{$(date +%s.%N) - $start:.1f}')")
    gmres=$(figure "$name" linear_iterations_per_newton_iteration)
    growth="-"
    [ -n "$previous" ] && growth=$(python3 -c "print(f'{$gmres / $previous:.2f}')")
    echo "| $preconditioner | $cells | $step | $seconds | $(figure "$name" newton_iterations_per_step) | $gmres | $growth |"
    previous=$gmres
  done
done
