# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The start of the benchmark scripts that run shipped cases, and their
# shell functions. Source it with the script's arguments ([build
# directory=build]): it goes to the top of the repository and sets
# $grainmpm (the executable) and $work (a scratch directory, removed on
# exit).

set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
build=${1:-build}
grainmpm=$(realpath "$build/source/grainmpm")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run NAME CASE EXTRA: run prm/CASE.prm with the EXTRA parameter text, in
# Test mode unless TEST_MODE=false (Test mode leaves the timings out of
# summary.csv).
run() {
  local name=$1 case=$2 extra=$3
  {
    echo "include $PWD/prm/$case.prm"
    printf '%b\n' "$extra"
    printf 'subsection Output\n  set Output directory = %s\n  set Test mode = %s\n  set Write particles = false\n  set Write grid = false\nend\n' "$work/$name" "${TEST_MODE:-true}"
  } > "$work/$name.prm"
  (cd "$work" && "$grainmpm" "$name.prm" > "$name.out")
}

# shellcheck source=summary.sh
source benchmarks/common/summary.sh

# exact NAME QUANTITY: QUANTITY of the run NAME's summary.csv as written
# (doc/output.md), e.g. exact NAME steps.
exact() {
  summary_value "$work/$1/summary.csv" "$2"
}

# figure NAME QUANTITY: the same to six significant digits, as the screen
# summary prints it, e.g. figure NAME total_energy_end.
figure() {
  summary_value "$work/$1/summary.csv" "$2" "%.6g"
}

# speeds NAME: |v_x| of grain 1 in its first five rebound flights: the
# median over each run of outputs with one sign of v_x, after the first.
speeds() {
  awk -F, 'NR > 1 && $2 == 1 { s = ($6 < 0 ? -1 : 1);
      if (n == 0 || s != sign[n]) { ++n; sign[n] = s; count[n] = 0 }
      speed[n, ++count[n]] = s * $6 }
    END { printed = 0;
      for (k = 2; k <= n && printed < 5; ++k) {
        if (count[k] < 3) continue;
        m = count[k]; for (i = 1; i <= m; ++i) a[i] = speed[k, i];
        for (i = 1; i <= m; ++i) for (j = i + 1; j <= m; ++j) if (a[j] < a[i]) { x = a[i]; a[i] = a[j]; a[j] = x }
        printf "%s%.3f", (printed > 0 ? " " : ""), a[int((m + 1) / 2)]; ++printed } }' "$work/$1/grains.csv"
}
