#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The loading-rate sweep. PACKINGS chooses the packings:
# - loose: the 30 disks of prm/slow_compression_*.prm, compressed by the
#   platen from the start over the travel 0.037 (End time = 0.037 / V),
#   frictionless and with Coulomb friction 0.3 (FRICTIONS);
# - dense: the jammed 100 disks (mu = 0.3, P/E = 1.4e-3) of
#   prm/dense_packing_preparation.prm, resumed from its checkpoint at
#   t = 1.4848 (DENSE_CHECKPOINT, or made first, 6 to 24 minutes on two
#   cores) in their own output directories, over the travel DENSE_TRAVEL (default
#   1.11e-3, 0.3 time units at V/c = 1e-4). Friction is the case's.
# Rates are RATES (V / c, c the dilatational wave speed), contact that of
# the case or Contact/Gap check = GAP_CHECK. Per packing, rate and
# friction it runs:
# - the explicit leapfrog (USL) at CFL 0.25: the reference at that rate;
# - the same with Time stepping/Mass scaling = each of MASS_SCALINGS;
# - the implicit case (AMG) at FACTORS times the explicit step, fixed
#   (Time stepping/Maximum CFL number = 0), with Nonlinear
#   solver/Tolerance = TOLERANCE and Time stepping/Theta = THETA if given
#   (else the case's: 1/2);
# - the implicit case from its own step with the steps grown by the
#   controller up to Time stepping/Maximum time step = each of MAXIMA
#   times the explicit step, or, for the entry "default", up to the
#   default Maximum CFL number (the same TOLERANCE and THETA, and
#   Time stepping/Energy error per step = ENERGY_ERROR if given).
# Per run it prints: wall time, steps, rejected steps, steps advanced by
# the explicit fallback, Newton iterations per step, GMRES iterations per
# Newton iteration, residual evaluations per step, the platen work and
# the mean platen force against the reference, the largest deviation of
# the force over tenths of the travel from the reference's (in units of
# the reference's mean force), the energy created (balance residual over
# the platen work), the median inertial number of the platen loading
# over the run (walls.csv) and the median step over the explicit step. Not a test: it prints figures. At 1e-3 the
# runs take seconds to a minute; at 1e-4 the explicit reference takes
# about 3 minutes and the implicit runs at the default tolerance longer;
# 1e-5 takes about 30 minutes per explicit run.
#
# Usage: benchmarks/loading_rate.sh [build directory=build]
# Environment: PACKINGS (default "loose"; "loose dense" for both),
# DENSE_CHECKPOINT, DENSE_TRAVEL, RATES (default "1e-3 1e-4"), FRICTIONS (default "0 0.3"),
# MASS_SCALINGS (default "10 100"), FACTORS (default "30 300"), MAXIMA
# (default none; numbers and "default"), ENERGY_ERROR (default that of the code), GAP_CHECK
# (true or false; default that of the case), TOLERANCE (the implicit runs'
# Newton tolerance; default that of the case), THETA (the implicit runs'
# Theta; default that of the case), STEP_ERROR (the grown runs' Time
# stepping/Step error tolerance; default that of the code),
# STATUS_FROM_LAST (true or false: the implicit runs' Nonlinear
# solver/Contact status from last step; default that of the code),
# LIGHT_FIELD_FRACTION (all runs' Contact/Light field fraction; default
# that of the code), PRECONDITIONER (the implicit runs' Linear
# solver/Preconditioner; default that of the case, automatic),
# MAXIMUM_DISPLACEMENT (the implicit runs' Time stepping/Maximum
# displacement per step, 0 for no bound; default that of the code).
# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

packings=${PACKINGS:-loose}
rates=${RATES:-1e-3 1e-4}
frictions=${FRICTIONS:-0 0.3}
scalings=${MASS_SCALINGS-10 100}
factors=${FACTORS-30 300}
maxima=${MAXIMA:-}

# The wave speed of both cases (E = 1000, nu = 0.3, rho = 1, plane strain).
wave_speed=$(python3 -c "
E, nu, rho = 1000., 0.3, 1.
print((E * (1 - nu) / ((1 + nu) * (1 - 2 * nu) * rho)) ** 0.5)")

# compare NAME REFERENCE START: the figures of walls.csv and energy.csv of
# run NAME after time START against those of REFERENCE (the platen is
# grain 1, moving down): steps, rejected steps, Newton iterations per step,
# GMRES iterations per Newton iteration, residual evaluations per step,
# then the platen work and force. A run resumed from a checkpoint holds
# the history before it too; START leaves it out.
compare() {
  python3 - "$work/$1" "$work/$2" "$3" "$explicit_step" <<'PYTHON'
import csv, math, sys

start = float(sys.argv[3])
explicit_step = float(sys.argv[4])

def columns(path):
    # Rows after START (a resumed run repeats the header at the resume).
    rows = [r for r in csv.reader(open(path))]
    names = [h.split(" [")[0] for h in rows[0]]
    rows = [r for r in rows[1:] if r[0] != "step" and float(r[1]) > start]
    return {n: [float(r[i]) for r in rows] for i, n in enumerate(names)}

def before(path):
    # The last row at or before START (the ledger at the checkpoint).
    last = None
    for r in csv.reader(open(path)):
        if r[0] != "step" and r[0][0].isdigit() and float(r[1]) <= start:
            last = r
    return last

def tenths(walls):
    t, dt, f = walls["time"], walls["dt"], walls["grain_1_force_y"]
    length = (t[-1] - start) / 10
    return [sum(f[i] * dt[i] for i in range(len(t))
                if start + k * length < t[i] <= start + (k + 1) * length) / length
            for k in range(10)]

def ledger(directory, name):
    energy = columns(directory + "/energy.csv")
    names = [h.split(" [")[0] for h in next(csv.reader(open(directory + "/energy.csv")))]
    row = before(directory + "/energy.csv")
    offset = float(row[names.index(name)]) if row else 0.
    return energy[name][-1] - offset

walls, reference = columns(sys.argv[1] + "/walls.csv"), columns(sys.argv[2] + "/walls.csv")
energy = columns(sys.argv[1] + "/energy.csv")
steps = len(energy["time"])
newton = sum(energy["newton_iterations"])
gmres = sum(energy["linear_iterations"])
evaluations = sum(energy["residual_evaluations"])
rejected = int(sum(energy["rejected_steps"]))
work = ledger(sys.argv[1], "boundary_work")
reference_work = ledger(sys.argv[2], "boundary_work")
created = ledger(sys.argv[1], "balance_residual") / work if work else float("nan")
mine, theirs = tenths(walls), tenths(reference)
mean, reference_mean = sum(mine) / 10, sum(theirs) / 10
deviation = max(abs(a - b) for a, b in zip(mine, theirs)) / reference_mean
numbers = sorted(x for x in walls["grain_1_inertial_number"] if math.isfinite(x) and x > 0)
median = numbers[len(numbers) // 2] if numbers else float("inf")
step = sorted(walls["dt"])[len(walls["dt"]) // 2] / explicit_step
print(f"{steps} | {rejected} | {newton / steps:.3g} | "
      f"{gmres / newton if newton else 0:.3g} | {evaluations / steps:.3g} | "
      f"{work:.4g} | {work / reference_work:.3f} | {mean:.4g} | "
      f"{mean / reference_mean:.3f} | {deviation:.2f} | {created:.3f} | {median:.1e} | "
      f"{step:.3g}")
PYTHON
}

# row NAME LABEL SECONDS REFERENCE START: one line of the table.
row() {
  local name=$1 label=$2 seconds=$3 reference=$4 start=$5
  local figures
  figures=$(compare "$name" "$reference" "$start")
  # Steps and rejections first, then the fallback steps (summary.csv; the
  # explicit preparation of the dense packing has none), then the rest.
  echo "| $label | $seconds | ${figures%% | *} | $(echo "$figures" | cut -d'|' -f2 | tr -d ' ') | $(exact "$name" explicit_fallback_steps) | $(echo "$figures" | cut -d'|' -f3- | sed 's/^ *//') |"
}

# timed NAME CASE EXTRA: run, and print the wall time in seconds (or
# "failed" and the end of the error).
timed() {
  local start
  start=$(date +%s.%N)
  if run "$1" "$2" "$3" 2> "$work/$1.err"; then
    python3 -c "print(f'{$(date +%s.%N) - $start:.0f}')"
  else
    echo "failed: $(grep -h -m1 'error' "$work/$1.err" "$work/$1.out" 2> /dev/null | cut -c1-160 | tr '|' ' ')"
    return 1
  fi
}

gap_text=""
if [ -n "${GAP_CHECK:-}" ]; then
  gap_text="subsection Contact\n  set Gap check = $GAP_CHECK\nend"
fi
if [ -n "${LIGHT_FIELD_FRACTION:-}" ]; then
  gap_text="$gap_text\nsubsection Contact\n  set Light field fraction = $LIGHT_FIELD_FRACTION\nend"
fi
tolerance_text=""
if [ -n "${TOLERANCE:-}" ]; then
  tolerance_text="subsection Nonlinear solver\n  set Tolerance = $TOLERANCE\nend"
fi
if [ -n "${THETA:-}" ]; then
  tolerance_text="$tolerance_text\nsubsection Time stepping\n  set Theta = $THETA\nend"
fi
if [ -n "${STEP_ERROR:-}" ]; then
  tolerance_text="$tolerance_text\nsubsection Time stepping\n  set Step error tolerance = $STEP_ERROR\nend"
fi
if [ -n "${STATUS_FROM_LAST:-}" ]; then
  tolerance_text="$tolerance_text\nsubsection Nonlinear solver\n  set Contact status from last step = $STATUS_FROM_LAST\nend"
fi
if [ -n "${MAXIMUM_DISPLACEMENT:-}" ]; then
  tolerance_text="$tolerance_text\nsubsection Time stepping\n  set Maximum displacement per step = $MAXIMUM_DISPLACEMENT\nend"
fi

echo "| packing | V/c | friction | run | wall time [s] | steps | rejected | fallback steps | Newton/step | GMRES/Newton | residual evaluations/step | platen work | / reference | mean platen force | / reference | largest deviation over tenths / mean | balance / platen work | median I | median step / explicit step |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"

# The dense packing's checkpoint and its time (from the energy.csv of the
# run that wrote it).
dense_start=0
dense_resume=""
if [[ " $packings " == *" dense "* ]]; then
  if [ -n "${DENSE_CHECKPOINT:-}" ]; then
    dense_resume=$(realpath "$DENSE_CHECKPOINT")
  else
    run dense_preparation dense_packing_preparation ""
    dense_resume=$work/dense_preparation/checkpoint-028000
  fi
  dense_start=$(python3 - "$dense_resume" <<'PYTHON'
import csv, os, sys
checkpoint = sys.argv[1].rstrip("/")
step = int(os.path.basename(checkpoint).split("-")[1])
for row in csv.reader(open(os.path.join(os.path.dirname(checkpoint), "energy.csv"))):
    if row[0] == str(step):
        print(row[1])
        break
PYTHON
)
fi

for packing in $packings; do
  if [ "$packing" = dense ]; then
    explicit_case=dense_packing_preparation
    implicit_case=dense_packing_preparation
    cells=128
    packing_frictions=0.3
    start=$dense_start
    # (At rest at the checkpoint: a mass-scaled run keeps the points'
    # kinetic energy rather than their velocities.)
    resume="subsection Checkpoint\n  set Steps between checkpoints = 0\n  set Resume from = $dense_resume\n  set Scale velocities with the mass = true\nend"
    implicit_text="subsection Time stepping\n  set Scheme = implicit theta\n  set Stress update = USF\nend\nsubsection Linear solver\n  set Preconditioner = ${PRECONDITIONER:-automatic}\nend"
  else
    explicit_case=slow_compression_explicit
    implicit_case=slow_compression_implicit
    cells=64
    packing_frictions=$frictions
    start=0
    resume=""
    implicit_text=""
    if [ -n "${PRECONDITIONER:-}" ]; then
      implicit_text="subsection Linear solver\n  set Preconditioner = $PRECONDITIONER\nend"
    fi
  fi
  explicit_step=$(python3 -c "print(0.25 / $cells / $wave_speed)")
  for rate in $rates; do
    read -r speed end_time <<< "$(python3 -c "
v = $rate * $wave_speed
travel = ${DENSE_TRAVEL:-1.11e-3} if '$packing' == 'dense' else 0.037
print(v, $start + travel / v)")"
    for friction in $packing_frictions; do
      contact=""
      if [ "$packing" = loose ] && [ "$friction" = 0 ]; then
        contact="subsection Contact\n  set Contact model = frictionless\nend"
      elif [ "$packing" = loose ]; then
        contact="subsection Contact\n  set Contact model = Coulomb friction\n  set Friction coefficient = $friction\nend"
      fi
      common="$contact\n$gap_text\n$resume\nsubsection Grains\n  subsection Platen\n    set Prescribed velocity = 0; -$speed\n  end\nend\nsubsection Time stepping\n  set End time = $end_time\nend"
      prefix="$packing | $rate | $friction"
      reference="explicit_${packing}_${rate}_$friction"
      if ! seconds=$(timed "$reference" "$explicit_case" "$common"); then
        echo "| $prefix | explicit | $seconds |"
        continue
      fi
      echo "| $prefix $(row "$reference" "explicit CFL 0.25" "$seconds" "$reference" "$start")"
      for alpha in $scalings; do
        name="scaled_${packing}_${rate}_${friction}_$alpha"
        if seconds=$(timed "$name" "$explicit_case" \
          "$common\nsubsection Time stepping\n  set Mass scaling = $alpha\nend"); then
          echo "| $prefix $(row "$name" "explicit, mass scaling $alpha" "$seconds" "$reference" "$start")"
        else
          echo "| $prefix | explicit, mass scaling $alpha | $seconds |"
        fi
      done
      for factor in $factors; do
        name="implicit_${packing}_${rate}_${friction}_$factor"
        step=$(python3 -c "print($factor * $explicit_step)")
        if seconds=$(timed "$name" "$implicit_case" \
          "$common\n$implicit_text\nsubsection Time stepping\n  set Time step = $step\n  set Maximum CFL number = 0\nend\n$tolerance_text"); then
          echo "| $prefix $(row "$name" "implicit ${factor}x" "$seconds" "$reference" "$start")"
        else
          echo "| $prefix | implicit ${factor}x | $seconds |"
        fi
      done
      for maximum in $maxima; do
        name="grown_${packing}_${rate}_${friction}_$maximum"
        if [ "$maximum" = default ]; then
          growth="subsection Time stepping\n"
          label="implicit, grown by default"
        else
          step=$(python3 -c "print($maximum * $explicit_step)")
          growth="subsection Time stepping\n  set Maximum time step = $step\n"
          label="implicit, grown to ${maximum}x"
        fi
        if [ -n "${ENERGY_ERROR:-}" ]; then
          growth="$growth  set Energy error per step = $ENERGY_ERROR\n"
        fi
        if seconds=$(timed "$name" "$implicit_case" \
          "$common\n$implicit_text\n${growth}end\n$tolerance_text"); then
          echo "| $prefix $(row "$name" "$label" "$seconds" "$reference" "$start")"
        else
          echo "| $prefix | $label | $seconds |"
        fi
      done
    done
  done
done
