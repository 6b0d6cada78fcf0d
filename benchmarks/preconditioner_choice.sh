#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# What `Linear solver/Preconditioner = automatic` (the default) costs
# against its two parts, probed Jacobi and sparse Cholesky, on the shipped
# implicit cases: the single grain between walls
# (prm/single_grain_rebound_implicit.prm) at its CFL 2.5 and at CFL 10, the
# two-disk collision (prm/two_disks_implicit.prm, CFL 2.5), the five grains
# (prm/five_grains_implicit.prm, steps grown from CFL 1.4) and the slow
# compression of 30 disks (prm/slow_compression_implicit.prm, steps grown
# from CFL 7.5). Per run: the wall time of the implicit steps (TimerOutput
# section "implicit step"), steps, rejected steps, Newton iterations per
# step, GMRES iterations per Newton iteration, residual evaluations per
# step, and the result the case is about (E_total(end)/E0, or the boundary
# work over E_max for the compression). Runs one after the other; the wall
# times are only comparable on an otherwise idle machine. Not a test: it
# prints figures (about 5 minutes).
#
# Usage: benchmarks/preconditioner_choice.sh [build directory=build]
# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

echo "| case | CFL | preconditioner | implicit steps wall time (s) | steps | rejected | Newton/step | GMRES/Newton | residual evaluations/step | result |"
echo "|---|---|---|---|---|---|---|---|---|---|"
# case_rows CASE LABEL EXTRA CFL RESULT QUANTITY: the three runs of
# prm/CASE.prm with the parameter text EXTRA; the last column is RESULT and
# the summary quantity QUANTITY.
count=0
case_rows() {
  local case=$1 label=$2 extra=$3 cfl=$4 result=$5 quantity=$6 preconditioner name
  for preconditioner in "probed Jacobi" "sparse Cholesky" "automatic"; do
    name="run_$((++count))"
    TEST_MODE=false run "$name" "$case" \
      "${extra}subsection Linear solver\n  set Preconditioner = $preconditioner\nend"
    echo "| $label | $cfl | $preconditioner | $(figure "$name" wall_time_implicit_step) | $(exact "$name" steps) | $(exact "$name" rejected_steps) | $(figure "$name" newton_iterations_per_step) | $(figure "$name" linear_iterations_per_newton_iteration) | $(figure "$name" residual_evaluations_per_step) | $result $(figure "$name" "$quantity") |"
  done
}
case_rows single_grain_rebound_implicit "single grain" "" 2.5 "E(2)/E0" total_energy_end
case_rows single_grain_rebound_implicit "single grain" \
  "subsection Time stepping\n  set CFL number = 10\nend\n" 10 "E(2)/E0" total_energy_end
case_rows two_disks_implicit "two disks" "" 2.5 "E(3.5)/E0" total_energy_end
case_rows five_grains_implicit "five grains" "" "1.4, grown" "E(50)/E0" total_energy_end
case_rows slow_compression_implicit "30 disks, slow platen" "" "7.5, grown" \
  "boundary work / E_max" boundary_work
