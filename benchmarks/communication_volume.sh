#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# What an explicit step sends between the ranks, and what it costs: the
# figures behind the weak-scaling estimate of doc/parallel.md.
#
# Every case runs 1 and 1 + STEPS explicit steps on 1 and on 2 MPI ranks,
# with the counting library of benchmarks/mpi_traffic (PMPI, loaded with
# LD_PRELOAD) in every rank; the difference of the two runs is the traffic
# of STEPS steps without the setup. Repartitioning is off in the measured
# steps (Steps between repartitioning = 100000), output only at the end.
# Cases:
#   block2d: the elastic block of whole_process.sh, 1024^2 cells, 1M points,
#            one grain, linear hat functions;
#   block3d: the 3D block, 64^3 cells, 262,144 points;
#   column2d: prm/granular_column_collapse.prm (1000 disks, 51,000 points,
#            one velocity field per grain, contact), from its start;
#   column3d: prm/granular_column_collapse_3d.prm (2000 spheres, 562,622
#            points), from its start (its setup, a ballistic deposition of
#            the spheres, takes some minutes).
# Printed per case and rank count, all per step and from the difference of
# the two runs: the wall time (TimerOutput sections "explicit step" and
# "diagnostics", rank 0), and per rank: point-to-point messages and bytes sent, collective calls and the
# bytes the rank contributes to them, seconds inside MPI calls (waits
# included); and the calls per step of rank 0 of the 2-rank run by MPI
# function.
#
# Usage: [CASES="block2d block3d column2d column3d"] [STEPS=20]
#        bash benchmarks/communication_volume.sh [build directory]
# About 15 minutes on two cores, most of it the 3D column's setup.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
steps=${STEPS:-20}
cases=${CASES:-block2d block3d column2d column3d}
grainmpm=$PWD/$build/source/grainmpm
cmake --build "$build" --target mpi_traffic > /dev/null
traffic=$PWD/$build/benchmarks/libmpi_traffic.so
work=$PWD/$build/benchmarks/communication_volume
mkdir -p "$work"
mpirun=(mpirun --allow-run-as-root --oversubscribe)

# shellcheck source=common/summary.sh
source benchmarks/common/summary.sh
# shellcheck source=common/block_case.sh
source benchmarks/common/block_case.sh

# write_case NAME N_STEPS: the case NAME run for N_STEPS steps into
# $work/NAME-N_STEPS.
write_case() {
  local file=$work/$1-$2.prm out=$work/$1-$2
  case $1 in
    block2d) write_block_case "$file" 2 1024 2 linear "$2" "$out" ;;
    block3d) write_block_case "$file" 3 64 2 linear "$2" "$out" ;;
    column2d | column3d)
      local prm=prm/granular_column_collapse.prm
      [ "$1" = column3d ] && prm=prm/granular_column_collapse_3d.prm
      cat > "$file" <<EOF
include $PWD/$prm
subsection Time stepping
  set Maximum number of steps = $2
end
subsection Load balancing
  set Steps between repartitioning = 100000
end
subsection Output
  set Output directory = $out
  set Output interval  = 1000
  set Write particles  = false
  set Write grid       = false
end
EOF
      ;;
    *) echo "unknown case $1" >&2; exit 1 ;;
  esac
}

# step_seconds SUMMARY: the wall time of the steps (TimerOutput sections
# "explicit step" and "diagnostics") of a run, from its summary.csv.
step_seconds() {
  awk "BEGIN { print $(summary_value "$1" wall_time_explicit_step) + $(summary_value "$1" wall_time_diagnostics) }"
}

# field FILE NAME: the number after NAME in the counting library's line.
field() { awk -v name="$2" '{ for (i = 1; i < NF; ++i) if ($i == name) print $(i + 1) }' "$1"; }

printf 'per rank and step, from the difference of runs of 1 and %d steps\n' $((steps + 1))
printf '%-9s %5s %12s %10s %12s %12s %12s %12s\n' case ranks "ms/step" rank \
  "p2p msgs" "p2p bytes" collectives "coll. bytes" 
printf '%-9s %5s %12s %10s %12s %12s %12s %12s\n' "" "" "" "" "" "" "" "ms in MPI"
for name in $cases; do
  for ranks in 1 2; do
    for n in 1 $((steps + 1)); do
      write_case "$name" "$n"
      rm -f "$work/$name-$n.traffic".*
      (cd "$work" && "${mpirun[@]}" -np "$ranks" -x LD_PRELOAD="$traffic" \
        -x MPI_TRAFFIC_OUTPUT="$work/$name-$n.traffic" \
        "$grainmpm" "$name-$n.prm" > "$work/$name-$n-$ranks.out" 2>&1)
    done
    ms=$(awk -v a="$(step_seconds "$work/$name-1/summary.csv")" \
      -v b="$(step_seconds "$work/$name-$((steps + 1))/summary.csv")" \
      -v s="$steps" 'BEGIN { printf "%.2f", 1e3 * (b - a) / s }')
    for rank in $(seq 0 $((ranks - 1))); do
      a=$work/$name-1.traffic.$rank
      b=$work/$name-$((steps + 1)).traffic.$rank
      per_step() { awk -v a="$(field "$a" "$1")" -v b="$(field "$b" "$1")" -v s="$steps" -v f="$2" 'BEGIN { printf f, (b - a) / s }'; }
      printf '%-9s %5d %12s %10d %12s %12s %12s %12s\n' "$name" "$ranks" "$ms" "$rank" \
        "$(per_step p2p_messages %.1f)" "$(per_step p2p_bytes %.0f)" \
        "$(per_step collectives %.1f)" "$(per_step collective_bytes %.0f)"
      printf '%-9s %5s %12s %10s %12s %12s %12s %12s\n' "" "" "" "" "" "" "" \
        "$(awk -v a="$(field "$a" mpi_seconds)" -v b="$(field "$b" mpi_seconds)" -v s="$steps" 'BEGIN { printf "%.3f", 1e3 * (b - a) / s }')"
    done
  done
  # The calls per step of rank 0 (of the 2-rank run), by function.
  printf 'calls per step, rank 0 of 2:%s\n' "$(awk -v s="$steps" '
    FNR == 2 { for (i = 2; i < NF; i += 2) { if (FILENAME == ARGV[1]) a[$i] = $(i + 1); else b[$i] = $(i + 1) } }
    END { for (f in b) if (b[f] - a[f] > 0) printf " %s %.1f", f, (b[f] - a[f]) / s }' \
    "$work/$name-1.traffic.0" "$work/$name-$((steps + 1)).traffic.0")"
  printf 'points: %s, cells: %s\n\n' "$(summary_value "$work/$name-1/summary.csv" material_points)" \
    "$(grep -m1 -o '[0-9]* cells' "$work/$name-$((steps + 1))-2.out" | cut -d' ' -f1)"
done
echo "(ms/step: wall time of rank 0 per step; all figures are those of the"
echo " last $steps steps, the difference of the two runs)"
