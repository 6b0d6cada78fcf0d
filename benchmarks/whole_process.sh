#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The explicit step of the whole grainmpm process against the plain-array
# kernel of the same work (benchmarks/explicit_step/plain_kernel.cc).
#
# The block of build/benchmarks/explicit_step as a .prm case: the cells
# inside [0.25, 0.75]^2 of a CELLS x CELLS grid on the unit square, PER_DIR^2
# points per cell (by default 1024 and 2: 1,048,576 points, 4 per cell), linear elastic (E = 1000, nu = 0.3, rho = 1),
# initial velocity (0.1, 0), gravity (0, -1), free-slip walls, USF, a time
# step of 0.1 h / c, output only at the end. grainmpm runs it for STEPS
# steps on 1 and on 2 MPI ranks with each of the shape functions in KERNELS;
# the step time is the sum of the TimerOutput sections "explicit step"
# (transfer, contact, sorting, the MPI exchanges) and "diagnostics" (the
# energy, wall and contact histories written every step).
# Printed: ns per point per step, its ratio to the plain kernel (goal <= 3.5),
# and the speed-up of 2 ranks over 1 (goal >= 1.7), each of all STEPS steps
# and of the steps after the first: the first step also allocates and first
# touches the transfer cache (room for 3^dim nodes per point) and the slot
# vectors, and builds the slot layout, which the later steps keep while the
# points keep their nodes; the plain kernel allocates before its clock
# starts. "After the first" is (t(STEPS) - t(1)) / (STEPS - 1) from a run of
# STEPS steps and one of 1 step. The speed-up of 2 ranks is also printed
# from the medians of the runs of STEPS steps.
#
# With DIM=3 the same in 3D: the cells inside [0.25, 0.75]^3 of a
# CELLS^3 grid on the unit cube (by default 64 and 2: 262,144 points, 8 per
# cell), gravity (0, -1, 0), against the 3D plain kernel
# (benchmarks/explicit_step/plain_kernel_3d.cc); also printed: the peak
# memory per point (summed over the ranks, from summary.csv).
#
# With PERF=1 (and perf installed) the 2-rank run of the first kernel is
# also recorded with perf: the share of the samples in the MPI library and
# its transport (libmpi, libopen-pal, UCX, ...), which is time spent in or
# waiting on MPI.
#
# Timings on this kind of machine are bimodal (the plain kernel alone takes
# 64 or 81 ns/point/step from one run to the next), so every figure is the
# fastest of REPEAT runs.
#
# Usage: [DIM=2] [KERNELS="linear uGIMP"] [STEPS=20] [REPEAT=3] [CELLS=1024 (3D: 64)]
#        [PER_DIR=2] [PERF=1]
#        bash benchmarks/whole_process.sh [build directory]
# About 8 minutes on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
steps=${STEPS:-20}
repeat=${REPEAT:-3}
dim=${DIM:-2}
if [ "$dim" = 3 ]; then cells=${CELLS:-64}; else cells=${CELLS:-1024}; fi
per_dir=${PER_DIR:-2}
kernels=${KERNELS:-linear uGIMP}
grainmpm=$PWD/$build/source/grainmpm
cmake --build "$build" --target explicit_step > /dev/null
work=$PWD/$build/benchmarks/whole_process
mkdir -p "$work"
mpirun=(mpirun --allow-run-as-root --oversubscribe)

# shellcheck source=common/block_case.sh
source benchmarks/common/block_case.sh
# write_case NAME KERNEL [STEPS]: the block with KERNEL, run into $work/NAME.
write_case() { write_block_case "$work/$1.prm" "$dim" "$cells" "$per_dir" "$2" "${3:-$steps}" "$work/$1"; }

# shellcheck source=common/summary.sh
source benchmarks/common/summary.sh

# step_seconds NAME: seconds of the TimerOutput sections "explicit step" and
# "diagnostics" (energy.csv and the other histories), from the summary.csv
# of the run NAME (doc/output.md).
step_seconds() {
  local summary=$work/$1/summary.csv
  awk "BEGIN { printf \"%.4f\", $(summary_value "$summary" wall_time_explicit_step) + $(summary_value "$summary" wall_time_diagnostics) }"
}
# fastest NAME RANKS: the smallest and the median step_seconds of $repeat
# runs of NAME.
fastest() {
  local times=""
  for run in $(seq 1 "$repeat"); do
    (cd "$work" && "${mpirun[@]}" -np "$2" "$grainmpm" "$1.prm" > "$1-$2.out" 2>&1)
    times="$times $(step_seconds "$1")"
  done
  echo "$times" | tr ' ' '\n' | sed '/^$/d' | sort -g |
    awk '{ t[NR] = $1 } END { m = (NR % 2) ? t[(NR + 1) / 2] : (t[NR / 2] + t[NR / 2 + 1]) / 2; print t[1], m }'
}

plain=$(for run in $(seq 1 "$repeat"); do
  "$PWD/$build/benchmarks/explicit_step" "$cells" "$per_dir" "$steps" "$([ "$dim" = 3 ] && echo plain3d || echo plain)"
done | awk '/plain-array kernel:/ { if (best == "" || $3 < best) best = $3 } END { print best }')
printf '%dD, %d^%d cells, %d^%d points per cell; plain-array kernel (linear, USF, one core): %.1f ns/point/step\n\n' "$dim" "$cells" "$dim" "$per_dir" "$dim" "$plain"
printf 'fastest of %d runs each; "all": the %d steps, "after 1st": the steps after the first\n' "$repeat" "$steps"
printf '%-8s %5s %10s %8s %12s %8s %10s %10s %12s\n' kernel ranks "all ns" "/ plain" "after 1st" "/ plain" speed-up "(after)" bytes/point
for kernel in $kernels; do
  write_case "$kernel" "$kernel"
  write_case "$kernel-first" "$kernel" 1
  n_points=""
  for ranks in 1 2; do
    read -r t_all t_median <<< "$(fastest "$kernel" "$ranks")"
    read -r t_first _ <<< "$(fastest "$kernel-first" "$ranks")"
    n_points=$(summary_value "$work/$kernel/summary.csv" material_points)
    all=$(awk -v t="$t_all" -v n="$n_points" -v s="$steps" 'BEGIN { printf "%.1f", 1e9 * t / (n * s) }')
    after=$(awk -v t="$t_all" -v f="$t_first" -v n="$n_points" -v s="$steps" 'BEGIN { printf "%.1f", 1e9 * (t - f) / (n * (s - 1)) }')
    # Peak memory (summed over the ranks) per point, of the last run.
    memory=$(awk "BEGIN { printf \"%.0f\", 1048576 * $(summary_value "$work/$kernel/summary.csv" peak_memory) / $n_points }")
    if [ "$ranks" = 1 ]; then one=$all; one_after=$after; one_median=$t_median; one_memory=$memory; else two=$all; two_after=$after; two_median=$t_median; two_memory=$memory; fi
  done
  printf '%-8s %5d %10.1f %8.2f %12.1f %8.2f %10s %10s %12s\n' "$kernel" 1 "$one" "$(awk "BEGIN { print $one / $plain }")" "$one_after" "$(awk "BEGIN { print $one_after / $plain }")" - - "$one_memory"
  printf '%-8s %5d %10.1f %8.2f %12.1f %8.2f %10.2f %10.2f %12s\n' "$kernel" 2 "$two" "$(awk "BEGIN { print $two / $plain }")" "$two_after" "$(awk "BEGIN { print $two_after / $plain }")" "$(awk "BEGIN { print $one / $two }")" "$(awk "BEGIN { print $one_after / $two_after }")" "$two_memory"
  printf '%-8s speed-up of 2 ranks over 1 from the medians of the %d runs of %d steps: %.2f\n' "$kernel" "$repeat" "$steps" "$(awk "BEGIN { print $one_median / $two_median }")"
done
echo "(ns/point/step of 2 ranks: wall time x 1 / points, so the ratio to the"
echo " one-core plain kernel falls with the speed-up; goals: 1 rank <= 3.5,"
echo " speed-up >= 1.7)"

if [ "${PERF:-0}" = 1 ] && command -v perf > /dev/null; then
  # Sampled on 2 ranks for 1 and for 101 steps: the difference of the sample
  # counts is that of 100 steps, without the setup.
  kernel=${kernels%% *}
  # samples FILE: "total MPI kernel" sample counts, MPI = the MPI library and
  # its transport (libmpi, Open MPI's mca_* components, open-pal, PMIx,
  # libevent, UCX), kernel = the operating system.
  samples() {
    perf report -i "$1" --sort dso -n --stdio 2> /dev/null |
      awk '/^ +[0-9.]+%/ { t += $2;
        if ($3 ~ /libmpi|mca_|open-pal|open-rte|pmix|libevent|ucx|libuc[pts]/) m += $2;
        if ($3 ~ /kernel/) k += $2 }
        END { print t + 0, m + 0, k + 0 }'
  }
  for n in 1 101; do
    sed -i "s/Maximum number of steps = .*/Maximum number of steps = $n/" "$work/$kernel.prm"
    rm -f "$work"/perf.$n.*
    (cd "$work" && "${mpirun[@]}" -np 2 sh -c \
      'exec perf record -q -F 999 -o perf.$2.$OMPI_COMM_WORLD_RANK "$0" "$1"' \
      "$grainmpm" "$kernel.prm" "$n" > "$work/perf-$n.out" 2>&1) || true
  done
  for rank in 0 1; do
    read -r t1 m1 k1 <<< "$(samples "$work/perf.1.$rank")"
    read -r t2 m2 k2 <<< "$(samples "$work/perf.101.$rank")"
    awk -v k0="$kernel" -v r=$rank -v t=$((t2 - t1)) -v m=$((m2 - m1)) -v k=$((k2 - k1)) 'BEGIN {
      printf "perf, %s, rank %d, 100 steps: %.1f %% of the samples in MPI and its transport, %.1f %% in the operating system\n", k0, r, 100 * m / t, 100 * k / t }'
  done
fi
