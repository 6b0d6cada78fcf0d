#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# What the implicit scheme costs on a slowly compressed packing: the 30
# disks of prm/slow_compression_implicit.prm (platen at 1e-3 of the wave
# speed) to t = 1, frictionless and with Coulomb friction 0.3, explicit
# (USL, CFL 0.25: the shipped prm/slow_compression_explicit.prm) and
# implicit theta = 1/2 at 10, 30, 100 and 300 times the explicit step.
# Prints per run: wall time, steps, rejected steps, Newton iterations per
# step, GMRES iterations per Newton iteration, contact status changes per
# step, and the platen force averaged over t in [0.9, 1] (the rigid platen's
# force in walls.csv) against that of the explicit run. Not a test: it
# prints figures (about 25 minutes on one core).
#
# Usage: benchmarks/implicit_packing.sh [build directory=build]
# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

# Environment: PRECONDITIONER (probed Jacobi or AMG), FACTORS (the implicit
# steps in units of the explicit one), FRICTIONS.
preconditioner=${PRECONDITIONER:-probed Jacobi}
factors=${FACTORS:-10 30 100 300}
frictions=${FRICTIONS:-0 0.3}
echo "implicit runs: Linear solver/Preconditioner = $preconditioner"

# The explicit CFL 0.25 step of this case (h = 1/64, wave speed of E = 1000,
# nu = 0.3, rho = 1, plane strain).
explicit_step=$(python3 -c "
E, nu, rho = 1000., 0.3, 1.
c = (E * (1 - nu) / ((1 + nu) * (1 - 2 * nu) * rho)) ** 0.5
print(0.25 / 64 / c)")

# platen_force NAME: the dt-weighted mean of the force F_y that the disks
# put on the platen (grain 1; upwards, positive) over t in (0.9, 1].
platen_force() {
  python3 - "$work/$1/walls.csv" <<'PYTHON'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
column = [h.split(" [")[0] for h in rows[0]].index("grain_1_force_y")
impulse = duration = 0.
for r in rows[1:]:
    t, dt = float(r[1]), float(r[2])
    if t > 0.9 + 1e-12:
        impulse += float(r[column]) * dt
        duration += dt
print(f"{impulse / duration:.5g}")
PYTHON
}

echo "| friction | scheme | dt / explicit | wall time [s] | steps | rejected | Newton/step | GMRES/Newton | status changes/step | platen force (0.9-1) | / explicit |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for friction in $frictions; do
  if [ "$friction" = 0 ]; then
    contact="subsection Contact\n  set Contact model = frictionless\nend"
  else
    contact="subsection Contact\n  set Contact model = Coulomb friction\n  set Friction coefficient = $friction\nend"
  fi
  start=$(date +%s.%N)
  run "explicit_$friction" slow_compression_explicit "$contact"
  seconds=$(python3 -c "print(f'{$(date +%s.%N) - $start:.0f}')")
  reference=$(platen_force "explicit_$friction")
  steps=$(grep -o 'finished: [0-9]*' "$work/explicit_$friction.out" | sed 's/finished: //')
  echo "| $friction | explicit USL | 1 | $seconds | $steps | - | - | - | - | $reference | 1 |"
  for factor in $factors; do
    name="implicit_${friction}_$factor"
    step=$(python3 -c "print($factor * $explicit_step)")
    start=$(date +%s.%N)
    if run "$name" slow_compression_implicit \
      "$contact\nsubsection Time stepping\n  set Time step = $step\nend\nsubsection Linear solver\n  set Preconditioner = $preconditioner\nend" 2> "$work/$name.err"; then
      seconds=$(python3 -c "print(f'{$(date +%s.%N) - $start:.0f}')")
      steps=$(grep -o 'finished: [0-9]*' "$work/$name.out" | sed 's/finished: //')
      force=$(platen_force "$name")
      changes=$(python3 -c "print(f'{$(value "$name" "contact status changes") / $steps:.2g}')")
      echo "| $friction | implicit | $factor | $seconds | $steps | $(value "$name" "rejected steps") | $(value "$name" "Newton iterations per step") | $(value "$name" "linear iterations per Newton") | $changes | $force | $(python3 -c "print(f'{$force / $reference:.3f}')") |"
    else
      echo "| $friction | implicit | $factor | failed: $(tail -c 300 "$work/$name.err" | tr '\n|' '  ') |"
    fi
  done
done
