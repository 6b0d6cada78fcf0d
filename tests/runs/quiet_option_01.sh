#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The progress lines and --quiet, on the shipped two-disk collision: a run
# prints one progress line per output with the wall time and an estimate
# of the time to the end; with --quiet (before or after the file name) it
# prints no header and no progress line, but the final summary. The summary
# is the same with and without --quiet, with six significant digits (the
# progress line's one-digit wall time used to stay set on the output, so
# that the summary said "E_total(end) / E_total(0) = 0.9"). --quiet also
# silences the Newton lines of Nonlinear solver/Verbose (the implicit
# two-disk case, two steps).
# Usage: quiet_option_01.sh GRAINMPM SOURCE_DIR WORK_DIR
set -uo pipefail
grainmpm=$1
source_dir=$2
work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
cat > case.prm <<PRM
include $source_dir/prm/two_disks_explicit.prm
subsection Output
  set Output directory = results
  set Write particles  = false
  set Write grid       = false
end
PRM
failed=0
"$grainmpm" case.prm > loud.log 2>&1 || { echo "FAIL: the run failed"; exit 1; }
lines=$(grep -c '^step .* wall .* s  to end ~.* s$' loud.log)
# Outputs every 0.1 to t = 3.5: 35 lines with the timing (t = 0 has none).
if [ "$lines" -ne 35 ]; then
  echo "FAIL: $lines progress lines with wall time and estimate, expected 35"
  failed=1
fi
for where in before after; do
  if [ $where = before ]; then
    "$grainmpm" --quiet case.prm > quiet.log 2>&1 || failed=1
  else
    "$grainmpm" case.prm -q > quiet.log 2>&1 || failed=1
  fi
  if grep -q '^step\|^grainmpm' quiet.log; then
    echo "FAIL: --quiet ($where the file) printed a header or progress line"
    failed=1
  fi
  if ! grep -q '^finished: ' quiet.log; then
    echo "FAIL: --quiet ($where the file) printed no summary"
    failed=1
  fi
done
summary() {
  sed -n '/^finished: /,/momentum(end)/p' "$1"
}
if ! diff <(summary loud.log) <(summary quiet.log); then
  echo "FAIL: the summary differs with and without --quiet"
  failed=1
fi
if ! grep -q '^finished: 3500 steps to t = 3.5$' loud.log ||
  ! grep -Eq '^  E_(total|kin|el)\(end\) / E_total\(0\) = 0\.[0-9]{6}$' loud.log; then
  echo "FAIL: the summary is not printed with six significant digits:"
  summary loud.log
  failed=1
fi
cat > implicit.prm <<PRM
include $source_dir/prm/two_disks_implicit.prm
subsection Time stepping
  set End time = 0.2
end
subsection Nonlinear solver
  set Verbose = true
end
subsection Output
  set Output directory = results-implicit
  set Write particles  = false
  set Write grid       = false
end
PRM
"$grainmpm" implicit.prm > verbose.log 2>&1 || failed=1
"$grainmpm" --quiet implicit.prm > verbose-quiet.log 2>&1 || failed=1
# The Verbose lines: "  Newton   1: |R|/F = ..." and "  Newton converged
# in ..." (not the summary's "  Newton iterations per step").
newton_lines='^  Newton +([0-9]+:|converged|failed|did not)'
if ! grep -Eq "$newton_lines" verbose.log; then
  echo "FAIL: Verbose printed no Newton line without --quiet"
  failed=1
fi
if grep -Eq "$newton_lines" verbose-quiet.log; then
  echo "FAIL: --quiet printed the Newton lines of Verbose"
  failed=1
fi
[ $failed -eq 0 ] && echo "PASS: 35 progress lines; --quiet prints the summary only (no Verbose lines either); the summary has six digits either way"
exit $failed
