#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The loading-rate sweep: the 30 disks of prm/slow_compression_*.prm
# compressed by the platen at RATES (V / c, c the dilatational wave speed)
# over the same travel 0.037 (End time = 0.037 / V), frictionless and with
# Coulomb friction 0.3 (FRICTIONS), with the contact of the case or
# Contact/Gap check = GAP_CHECK. Per rate and friction it runs:
# - the explicit leapfrog (USL) at CFL 0.25: the reference at that rate;
# - the same with Time stepping/Mass scaling = each of MASS_SCALINGS;
# - the implicit theta = 1/2 case (AMG) at FACTORS times the explicit
#   step, with Nonlinear solver/Tolerance = TOLERANCE if given.
# Per run it prints: wall time, steps, rejected steps, steps advanced by
# the explicit fallback, Newton iterations per step, GMRES iterations per
# Newton iteration, residual evaluations per step, the platen work and
# the mean platen force against the reference, the largest deviation of
# the force over tenths of the travel from the reference's (in units of
# the reference's mean force), the energy created (balance residual over
# the platen work), and the median inertial number of the platen loading
# over the run (walls.csv). Not a test: it prints figures. At 1e-3 the
# runs take seconds to a minute; at 1e-4 the explicit reference takes
# about 3 minutes and the implicit runs at the default tolerance longer;
# 1e-5 takes about 30 minutes per explicit run.
#
# Usage: benchmarks/loading_rate.sh [build directory=build]
# Environment: RATES (default "1e-3 1e-4"), FRICTIONS (default "0 0.3"),
# MASS_SCALINGS (default "10 100"), FACTORS (default "30 300"), GAP_CHECK
# (true or false; default that of the case), TOLERANCE (the implicit runs'
# Newton tolerance; default that of the case).
# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

rates=${RATES:-1e-3 1e-4}
frictions=${FRICTIONS:-0 0.3}
scalings=${MASS_SCALINGS:-10 100}
factors=${FACTORS:-30 300}

# The wave speed and the explicit CFL 0.25 step of the case (E = 1000,
# nu = 0.3, rho = 1, plane strain, h = 1/64).
read -r wave_speed explicit_step <<< "$(python3 -c "
E, nu, rho = 1000., 0.3, 1.
c = (E * (1 - nu) / ((1 + nu) * (1 - 2 * nu) * rho)) ** 0.5
print(c, 0.25 / 64 / c)")"

# compare NAME REFERENCE: the figures of walls.csv and energy.csv of run
# NAME against those of REFERENCE (the platen is grain 1, moving down).
compare() {
  python3 - "$work/$1" "$work/$2" <<'PYTHON'
import csv, math, sys

def columns(path):
    rows = list(csv.reader(open(path)))
    names = [h.split(" [")[0] for h in rows[0]]
    return {n: [float(r[i]) for r in rows[1:]] for i, n in enumerate(names)}

def tenths(walls):
    t, dt, f = walls["time"], walls["dt"], walls["grain_1_force_y"]
    end = t[-1]
    return [sum(f[i] * dt[i] for i in range(len(t))
                if k * end / 10 < t[i] <= (k + 1) * end / 10) / (end / 10)
            for k in range(10)]

walls, reference = columns(sys.argv[1] + "/walls.csv"), columns(sys.argv[2] + "/walls.csv")
energy = columns(sys.argv[1] + "/energy.csv")
reference_energy = columns(sys.argv[2] + "/energy.csv")
work = energy["boundary_work"][-1]
reference_work = reference_energy["boundary_work"][-1]
mine, theirs = tenths(walls), tenths(reference)
mean, reference_mean = sum(mine) / 10, sum(theirs) / 10
deviation = max(abs(a - b) for a, b in zip(mine, theirs)) / reference_mean
created = energy["balance_residual"][-1] / work if work else float("nan")
numbers = sorted(x for x in walls["grain_1_inertial_number"] if math.isfinite(x) and x > 0)
median = numbers[len(numbers) // 2] if numbers else float("inf")
print(f"{work:.4g} | {work / reference_work:.3f} | {mean:.4g} | "
      f"{mean / reference_mean:.3f} | {deviation:.2f} | {created:.3f} | {median:.1e}")
PYTHON
}

# row NAME LABEL SECONDS REFERENCE: one line of the table.
row() {
  local name=$1 label=$2 seconds=$3 reference=$4
  local fallback newton gmres evaluations
  fallback=$(exact "$name" explicit_fallback_steps)
  newton=$(figure "$name" newton_iterations_per_step)
  gmres=$(figure "$name" linear_iterations_per_newton_iteration)
  evaluations=$(figure "$name" residual_evaluations_per_step)
  echo "| $label | $seconds | $(exact "$name" steps) | $(exact "$name" rejected_steps) | $fallback | $newton | $gmres | $evaluations | $(compare "$name" "$reference") |"
}

# timed NAME CASE EXTRA: run, and print the wall time in seconds (or
# "failed" and the end of the error).
timed() {
  local start
  start=$(date +%s.%N)
  if run "$1" "$2" "$3" 2> "$work/$1.err"; then
    python3 -c "print(f'{$(date +%s.%N) - $start:.0f}')"
  else
    echo "failed: $(tail -c 200 "$work/$1.err" | tr '\n|' '  ')"
    return 1
  fi
}

gap_text=""
if [ -n "${GAP_CHECK:-}" ]; then
  gap_text="subsection Contact\n  set Gap check = $GAP_CHECK\nend"
fi
tolerance_text=""
if [ -n "${TOLERANCE:-}" ]; then
  tolerance_text="subsection Nonlinear solver\n  set Tolerance = $TOLERANCE\nend"
fi

echo "| V/c | friction | run | wall time [s] | steps | rejected | fallback steps | Newton/step | GMRES/Newton | residual evaluations/step | platen work | / reference | mean platen force | / reference | largest deviation over tenths / mean | balance / platen work | median I |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for rate in $rates; do
  read -r speed end_time <<< "$(python3 -c "v = $rate * $wave_speed; print(v, 0.037 / v)")"
  for friction in $frictions; do
    if [ "$friction" = 0 ]; then
      contact="subsection Contact\n  set Contact model = frictionless\nend"
    else
      contact="subsection Contact\n  set Contact model = Coulomb friction\n  set Friction coefficient = $friction\nend"
    fi
    common="$contact\n$gap_text\nsubsection Grains\n  subsection Platen\n    set Prescribed velocity = 0; -$speed\n  end\nend\nsubsection Time stepping\n  set End time = $end_time\nend"
    reference="explicit_${rate}_$friction"
    if ! seconds=$(timed "$reference" slow_compression_explicit "$common"); then
      echo "| $rate | $friction | explicit | $seconds |"
      continue
    fi
    echo "| $rate | $friction $(row "$reference" "explicit CFL 0.25" "$seconds" "$reference")"
    for alpha in $scalings; do
      name="scaled_${rate}_${friction}_$alpha"
      if seconds=$(timed "$name" slow_compression_explicit \
        "$common\nsubsection Time stepping\n  set Mass scaling = $alpha\nend"); then
        echo "| $rate | $friction $(row "$name" "explicit, mass scaling $alpha" "$seconds" "$reference")"
      else
        echo "| $rate | $friction | explicit, mass scaling $alpha | $seconds |"
      fi
    done
    for factor in $factors; do
      name="implicit_${rate}_${friction}_$factor"
      step=$(python3 -c "print($factor * $explicit_step)")
      if seconds=$(timed "$name" slow_compression_implicit \
        "$common\nsubsection Time stepping\n  set Time step = $step\nend\n$tolerance_text"); then
        echo "| $rate | $friction $(row "$name" "implicit ${factor}x" "$seconds" "$reference")"
      else
        echo "| $rate | $friction | implicit ${factor}x | $seconds |"
      fi
    done
  done
done
