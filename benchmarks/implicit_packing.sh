#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# What the implicit scheme costs on a slowly compressed packing, against the
# explicit leapfrog: the 30 disks of prm/slow_compression_implicit.prm
# (platen at 1e-3 of the wave speed) to t = 1, or with PACKING=300 some 300
# disks of half the size in a box twice as wide (256 x 160 cells, 76,000
# points), frictionless and with Coulomb friction 0.3. Runs the explicit
# leapfrog (USL, the shipped prm/slow_compression_explicit.prm) at CFL 0.25
# and, as the reference, at CFL 0.125, and the implicit theta = 1/2 scheme
# (the shipped case: AMG preconditioner, the contact status updated after
# every Newton iteration) at FACTORS times the explicit CFL 0.25 step. Prints per
# run: wall time, steps, rejected steps, Newton iterations per step, GMRES
# iterations per Newton iteration, contact status changes per step, and the
# force the disks put on the platen (walls.csv) averaged over the whole run
# and over its last tenth, each against the reference run. Not a test: it
# prints figures (30 disks with FACTORS="10 30 100": about 15 minutes; 300
# disks with FACTORS="30 100" FRICTIONS=0.3 END_TIME=0.3: about 45 minutes;
# the defaults take hours).
#
# Usage: benchmarks/implicit_packing.sh [build directory=build]
# Environment: PACKING (30 or 300), FACTORS (the implicit steps in units of
# the explicit one; default "10 30 100 300"), FRICTIONS (default "0 0.3"),
# PRECONDITIONER (a Linear solver/Preconditioner; default that of the case),
# END_TIME (default 1), THETA (the implicit runs' theta; default that of
# the case, 1/2).
# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

packing=${PACKING:-30}
factors=${FACTORS:-10 30 100 300}
frictions=${FRICTIONS:-0 0.3}
end_time=${END_TIME:-1}

# The explicit CFL 0.25 step of this case (wave speed of E = 1000,
# nu = 0.3, rho = 1, plane strain) on cells of size h.
if [ "$packing" = 300 ]; then
  h=$(python3 -c "print(1 / 128)")
  # Radii 0.03-0.04 on h = 1/128 (8-10 cells per diameter, as the 30
  # disks); the deposit's top is at y = 0.9175, the platen 0.32 cells
  # above it as in the 30-disk case.
  case_text="subsection Background grid\n  set Upper corner = 2, 1.25\n  set Number of cells = 256, 160\nend\nsubsection Random packing\n  set Number of grains = 300\n  set Minimum radius = 0.03\n  set Maximum radius = 0.04\n  set Upper corner = 2, 1.25\nend\nsubsection Grains\n  subsection Platen\n    set Centre = 1, 0.94\n    set Size = 1.98, 0.04\n  end\nend"
elif [ "$packing" = 30 ]; then
  h=$(python3 -c "print(1 / 64)")
  case_text=""
else
  echo "PACKING must be 30 or 300" >&2
  exit 1
fi
explicit_step=$(python3 -c "
E, nu, rho = 1000., 0.3, 1.
c = (E * (1 - nu) / ((1 + nu) * (1 - 2 * nu) * rho)) ** 0.5
print(0.25 * $h / c)")
end_text="subsection Time stepping\n  set End time = $end_time\nend"
solver_text=""
if [ -n "${PRECONDITIONER:-}" ]; then
  solver_text="subsection Linear solver\n  set Preconditioner = $PRECONDITIONER\nend"
fi
if [ -n "${THETA:-}" ]; then
  solver_text="$solver_text\nsubsection Time stepping\n  set Theta = $THETA\nend"
fi
echo "$packing disks to t = $end_time; implicit runs: ${PRECONDITIONER:-as in the case}"

# platen_force NAME FROM: the dt-weighted mean of the force F_y that the
# disks put on the platen (grain 1; upwards, positive) over t in (FROM, end].
platen_force() {
  python3 - "$work/$1/walls.csv" "$2" <<'PYTHON'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
column = [h.split(" [")[0] for h in rows[0]].index("grain_1_force_y")
start = float(sys.argv[2])
impulse = duration = 0.
for r in rows[1:]:
    t, dt = float(r[1]), float(r[2])
    if t > start + 1e-12:
        impulse += float(r[column]) * dt
        duration += dt
print(f"{impulse / duration:.5g}")
PYTHON
}

late=$(python3 -c "print(0.9 * $end_time)")
ratio() {
  python3 -c "print(f'{$1 / $2:.3f}')"
}

echo "| friction | scheme | dt / explicit | wall time [s] | steps | rejected | Newton/step | GMRES/Newton | status changes/step | mean platen force | / reference | force over the last tenth | / reference |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for friction in $frictions; do
  if [ "$friction" = 0 ]; then
    contact="subsection Contact\n  set Contact model = frictionless\nend"
  else
    contact="subsection Contact\n  set Contact model = Coulomb friction\n  set Friction coefficient = $friction\nend"
  fi
  # The reference first: explicit at half the step.
  run "reference_$friction" slow_compression_explicit \
    "$case_text\n$contact\n$end_text\nsubsection Time stepping\n  set CFL number = 0.125\nend"
  mean_reference=$(platen_force "reference_$friction" 0)
  late_reference=$(platen_force "reference_$friction" "$late")
  for cfl in 0.125 0.25; do
    name="explicit_${friction}_$cfl"
    start=$(date +%s.%N)
    if [ "$cfl" = 0.125 ]; then
      cp -r "$work/reference_$friction" "$work/$name"
      cp "$work/reference_$friction.out" "$work/$name.out"
      seconds="-"
    else
      run "$name" slow_compression_explicit "$case_text\n$contact\n$end_text"
      seconds=$(python3 -c "print(f'{$(date +%s.%N) - $start:.0f}')")
    fi
    steps=$(exact "$name" steps)
    mean=$(platen_force "$name" 0)
    last=$(platen_force "$name" "$late")
    echo "| $friction | explicit USL, CFL $cfl | $(python3 -c "print($cfl / 0.25)") | $seconds | $steps | - | - | - | - | $mean | $(ratio "$mean" "$mean_reference") | $last | $(ratio "$last" "$late_reference") |"
  done
  for factor in $factors; do
    name="implicit_${friction}_$factor"
    step=$(python3 -c "print($factor * $explicit_step)")
    start=$(date +%s.%N)
    if run "$name" slow_compression_implicit \
      "$case_text\n$contact\n$end_text\nsubsection Time stepping\n  set Time step = $step\n  set Maximum CFL number = 0\nend\n$solver_text" 2> "$work/$name.err"; then
      seconds=$(python3 -c "print(f'{$(date +%s.%N) - $start:.0f}')")
      steps=$(exact "$name" steps)
      mean=$(platen_force "$name" 0)
      last=$(platen_force "$name" "$late")
      changes=$(python3 -c "print(f'{$(figure "$name" contact_status_changes) / $steps:.2g}')")
      echo "| $friction | implicit | $factor | $seconds | $steps | $(figure "$name" rejected_steps) | $(figure "$name" newton_iterations_per_step) | $(figure "$name" linear_iterations_per_newton_iteration) | $changes | $mean | $(ratio "$mean" "$mean_reference") | $last | $(ratio "$last" "$late_reference") |"
    else
      echo "| $friction | implicit | $factor | failed: $(tail -c 300 "$work/$name.err" | tr '\n|' '  ') |"
    fi
  done
done
