#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# Parallel throughput and memory of the large 2D case (doc/validation.md,
# Parallel runs):
#   prm/ten_thousand_grains.prm: 10,000 disks, about 1,012,000 points;
#   the same grid with 10 rectangular grains of the same total area (about
#   1,013,000 points): memory must not grow with grains x nodes.
# Each case runs STEPS explicit steps on 1 and on 2 MPI ranks, and 2
# implicit steps (theta = 1/2, dt = 1e-3) of the many-grain case on 1 and 2
# ranks. Printed: points x steps per second of the explicit step (TimerOutput
# section "explicit step"), residual evaluations per second of the implicit
# step, and peak resident memory (VmHWM) summed over the ranks.
#
# Usage: bash benchmarks/parallel_scaling.sh [build directory] [STEPS = 40]
# About 5 minutes on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
steps=${2:-40}
grainmpm=$PWD/$build/source/grainmpm
work=$PWD/$build/benchmarks/parallel_scaling
mkdir -p "$work"
mpirun=(mpirun --allow-run-as-root --oversubscribe)

# write_case NAME EXTRA: the many-grain case with EXTRA parameter text.
write_case() {
  {
    echo "include $PWD/prm/ten_thousand_grains.prm"
    printf '%b\n' "$2"
    printf 'subsection Load balancing\n  set Steps between repartitioning = 1000\nend\n'
    printf 'subsection Output\n  set Output directory = %s\n  set Write particles = false\n  set Output interval = 1000\nend\n' "$work/$1"
  } > "$work/$1.prm"
}

explicit="subsection Time stepping\n  set Maximum number of steps = $steps\nend"
write_case many "$explicit"

# Ten rectangles 9.8 x 52.2 side by side: the area of the 10,000 disks.
few="$explicit\nsubsection Random packing\n  set Number of grains = 0\nend\nsubsection Grains"
for g in $(seq 1 10); do
  few="$few\n  subsection Grain $g\n    set Shape = rectangle\n    set Centre = $(awk "BEGIN { print 10 * $g - 5 }"), 26.2\n    set Size = 9.8, 52.2\n    set Material = grain\n  end"
done
write_case few "$few\nend"

write_case implicit "subsection Time stepping\n  set Scheme = implicit theta\n  set Time step = 1e-3\n  set Maximum number of steps = 2\nend"

# shellcheck source=common/summary.sh
source benchmarks/common/summary.sh

# run NAME RANKS: the screen output in NAME-RANKS.out, the run's summary.csv
# (doc/output.md) in NAME-RANKS.csv.
run() {
  (cd "$work" && "${mpirun[@]}" -np "$2" "$grainmpm" "$1.prm" > "$1-$2.out" 2>&1)
  cp "$work/$1/summary.csv" "$work/$1-$2.csv"
}
# timer NAME-RANKS SECTION: wall time of a TimerOutput section on rank 0
# (SECTION with underscores, e.g. explicit_step).
timer() {
  summary_value "$work/$1.csv" "wall_time_$2"
}
points() {
  summary_value "$work/$1.csv" material_points
}
# memory NAME-RANKS: peak resident memory summed over the ranks, in MiB.
memory() {
  summary_value "$work/$1.csv" peak_memory "%.6g"
}

printf '%-14s %5s %10s %6s %14s %16s %12s\n' case ranks points steps "step time [s]" "points*steps/s" "memory [MiB]"
for name in many few; do
  for ranks in 1 2; do
    run $name $ranks
    t=$(timer $name-$ranks explicit_step)
    p=$(points $name-$ranks)
    printf '%-14s %5d %10d %6d %14.3f %16.3e %12.1f\n' \
      "$([ $name = many ] && echo '10,000 grains' || echo '10 grains')" \
      "$ranks" "$p" "$steps" "$t" "$(awk "BEGIN { print $p * $steps / $t }")" \
      "$(memory $name-$ranks)"
  done
done
echo
echo "explicit speed-up 2 ranks vs 1 (10,000 grains): $(awk "BEGIN { printf \"%.2f\", $(timer many-1 explicit_step) / $(timer many-2 explicit_step) }") (goal >= 1.7)"
for ranks in 1 2; do
  echo "memory 10,000 grains / 10 grains, $ranks rank(s): $(awk "BEGIN { printf \"%.3f\", $(memory many-$ranks) / $(memory few-$ranks) }") (goal <= 1.3)"
done
echo
for ranks in 1 2; do
  run implicit $ranks
  evaluations=$(summary_value "$work/implicit-$ranks.csv" residual_evaluations)
  t=$(timer implicit-$ranks implicit_step)
  echo "implicit, $ranks rank(s): $(awk "BEGIN { printf \"%.1f\", $evaluations / $t }") residual evaluations/s ($(awk "BEGIN { printf \"%.1f\", $evaluations }") in $(awk "BEGIN { printf \"%.3g\", $t }") s), peak memory $(memory implicit-$ranks) MiB"
done
