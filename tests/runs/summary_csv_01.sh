#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# summary.csv, the machine-readable run summary (doc/output.md), on the
# shipped implicit two-disk collision with the settings of
# tests/runs/implicit_failure_policy (CFL 10, at most 3 Newton iterations:
# 9 steps, 1 of them rejected once):
# - its figures agree with energy.csv (step count, end time, the energies
#   and ledger of the last row over energy_reference, the sums of the
#   solver counts and rejected steps) and with the screen summary (the
#   same values, rounded);
# - in test mode it has no wall time or memory rows, otherwise it has them;
# - a summary.csv that cannot be written stops the run with a message
#   naming it, and a summary.csv of an earlier run is not left behind.
# Usage: summary_csv_01.sh GRAINMPM SOURCE_DIR WORK_DIR
set -uo pipefail
grainmpm=$1
source_dir=$2
work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1

# write_case NAME TEST_MODE: the case, writing into results-NAME.
write_case() {
  cat > "$1.prm" <<PRM
include $source_dir/prm/two_disks_implicit.prm
subsection Time stepping
  set End time            = 2.5
  set CFL number          = 10
  set Steps before growth = 2
end
subsection Nonlinear solver
  set Maximum Newton iterations = 3
end
subsection Output
  set Output directory = results-$1
  set Test mode        = $2
  set Output interval  = 0.5
  set Write particles  = false
  set Write grid       = false
end
PRM
}

failed=0
write_case test true
write_case timed false
"$grainmpm" test.prm > test.log 2>&1 || { echo "FAIL: the test-mode run failed"; exit 1; }
"$grainmpm" --quiet timed.prm > timed.log 2>&1 || { echo "FAIL: the run failed"; exit 1; }

python3 - results-test test.log results-timed <<'PYTHON' || failed=1
import csv, re, sys

directory, screen, timed = sys.argv[1:4]

def read_summary(path):
    rows = list(csv.reader(open(path + "/summary.csv")))
    assert rows[0] == ["quantity", "value", "unit"], f"header {rows[0]}"
    names = [r[0] for r in rows[1:]]
    assert len(names) == len(set(names)), "a quantity appears twice"
    return {r[0]: float(r[1]) for r in rows[1:]}, {r[0]: r[2] for r in rows[1:]}

failures = []
def check(what, ok):
    if not ok:
        failures.append(what)

summary, units = read_summary(directory)
energy = list(csv.reader(open(directory + "/energy.csv")))
header = [h.split(" [")[0] for h in energy[0]]
rows = [dict(zip(header, map(float, r))) for r in energy[1:]]
last = rows[-1]
reference = summary["energy_reference"]

def close(a, b, tolerance=1e-9):
    return abs(a - b) <= tolerance * max(abs(a), abs(b), 1e-300)

check("steps = 9 = energy.csv rows after t = 0",
      summary["steps"] == 9 and summary["steps"] == len(rows) - 1 == last["step"])
check("end_time = last time of energy.csv", close(summary["end_time"], last["time"]))
check("energy_reference = initial total energy",
      summary["starts_at_rest"] == 0 and close(reference, rows[0]["total_energy"]))
for name, column in [("total_energy_end", "total_energy"),
                     ("kinetic_energy_end", "kinetic_energy"),
                     ("elastic_energy_end", "elastic_energy"),
                     ("transfer_work", "transfer_work"),
                     ("hypoelastic_correction", "hypoelastic_correction"),
                     ("balance_residual", "balance_residual")]:
    check(f"{name} x energy_reference = last {column} of energy.csv",
          close(summary[name] * reference, last[column]))
check("grid_energy_change = sum of energy.csv's grid_energy_change",
      close(summary["grid_energy_change"] * reference,
            sum(r["grid_energy_change"] for r in rows), 1e-8))
check("total_energy_min = smallest total energy of energy.csv",
      close(summary["total_energy_min"] * reference,
            min(r["total_energy"] for r in rows)))
for name in ["newton_iterations", "linear_iterations"]:
    check(f"{name} = sum of energy.csv's column",
          summary[name] == sum(r[name] for r in rows))
check("newton_iterations_max = largest of energy.csv",
      summary["newton_iterations_max"] == max(r["newton_iterations"] for r in rows))
check("rejected_steps = 1 = sum of energy.csv's rejected_steps",
      summary["rejected_steps"] == 1 == sum(r["rejected_steps"] for r in rows))
check("newton_iterations_per_step = newton_iterations / steps",
      close(summary["newton_iterations_per_step"],
            summary["newton_iterations"] / summary["steps"], 1e-15))
check("units", units["end_time"] == "T" and units["total_energy_end"] == "E_ref"
      and units["energy_reference"] == "M L^2/T^2 per L")

# The screen prints the same values, rounded.
text = open(screen).read()
def rounded(printed, name):
    """Whether the screen's number is summary.csv's value, rounded."""
    value = summary[name]
    return any(printed == f"{value:.{k}g}" for k in range(1, 18)) or \
        (printed == "0" and abs(value) < 1e-12)
number = r"(-?[0-9.]+(?:e[-+][0-9]+)?)"
for pattern, names in [
        (r"finished: # steps to t = #", ["steps", "end_time"]),
        (r"E_total\(end\) / E_total\(0\) = #", ["total_energy_end"]),
        (r"min, max E_total / E_total\(0\) = #, #", ["total_energy_min", "total_energy_max"]),
        (r"E_el\(end\) / E_total\(0\) = #", ["elastic_energy_end"]),
        (r"transfers = #, hypoelastic correction = #, balance residual = # \(largest #\)",
         ["transfer_work", "hypoelastic_correction", "balance_residual",
          "largest_balance_residual"]),
        (r"Newton iterations per step \(mean, max\): #, #",
         ["newton_iterations_per_step", "newton_iterations_max"]),
        (r"linear iterations per Newton iteration: #", ["linear_iterations_per_newton_iteration"]),
        (r"residual evaluations per step: +#", ["residual_evaluations_per_step"]),
        (r"rejected steps: +#", ["rejected_steps"]),
        (r"smallest time step tried: +#", ["smallest_time_step_tried"]),
        (r"sum m\|v\|\(0\) = #", ["momentum_change_relative"])]:
    match = re.search(pattern.replace("#", number), text)
    check(f"the screen has '{pattern}' with the values of summary.csv",
          match is not None and
          all(rounded(p, n) for p, n in zip(match.groups(), names)))

measured = ["wall_time", "peak_memory", "peak_memory_largest_rank"]
check("no wall time or memory in test mode",
      not any(k.startswith("wall_time") or k.startswith("peak_memory") for k in summary))
timed_summary, timed_units = read_summary(timed)
check("wall time, step time and memory outside test mode",
      all(timed_summary.get(k, 0) > 0 for k in measured + ["wall_time_implicit_step"])
      and timed_units["wall_time"] == "s" and timed_units["peak_memory"] == "MiB")
check("the other rows are those of test mode",
      {k: v for k, v in timed_summary.items() if k not in measured and not k.startswith("wall_time")} == summary)

for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
PYTHON

# A summary.csv that cannot be written (its temporary file is a
# directory), and one of an earlier run in the directory.
echo "quantity,value,unit" > results-test/summary.csv
mkdir results-test/summary.csv.tmp
if "$grainmpm" test.prm > blocked.log 2>&1; then
  echo "FAIL: the run did not stop when summary.csv could not be written"
  failed=1
elif ! grep -q "Output/Output directory: could not write 'results-test/summary.csv'" blocked.log; then
  echo "FAIL: the message does not name summary.csv:"
  tail -3 blocked.log
  failed=1
fi
if [ -e results-test/summary.csv ]; then
  echo "FAIL: the summary.csv of the earlier run is still there"
  failed=1
fi

[ $failed -eq 0 ] && echo "PASS: summary.csv agrees with energy.csv and the screen"
exit $failed
