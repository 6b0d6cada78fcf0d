#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# The compression of 100 disks by a rigid platen (prm/platen_compression_
# 100_disks.prm) to t = 2: the table of doc/results.md section 3 from
# walls.csv, contacts.csv, grains.csv and energy.csv at t = 1 and 2 (the
# forces on the platen, the floor and the side walls averaged over the
# last 0.1; contacts, sliding contacts, largest and mean normal force; the
# mean coordination number of the disks) and the energy ledger in units of
# the platen work. Not a test: it prints figures (about 16 minutes).
#
# Usage: benchmarks/platen_compression.sh [build directory=build]
# shellcheck source=common/run_case.sh
source "$(dirname "$0")/common/run_case.sh" "$@"

run compression platen_compression_100_disks ""

python3 - "$work/compression" <<'PYTHON'
import csv, sys
out = sys.argv[1]

def rows(name):
    return list(csv.DictReader(open(f"{out}/{name}")))

def column(row, name):
    return float(next(v for k, v in row.items() if k.split(" [")[0] == name))

walls = rows("walls.csv")
def mean_force(name, t0, t1):
    weighted = duration = 0.0
    for row in walls:
        t, dt = column(row, "time"), column(row, "dt")
        if t0 < t <= t1 + 1e-9:
            weighted += column(row, name) * dt
            duration += dt
    return weighted / duration

grains = rows("grains.csv")
contacts = rows("contacts.csv")
print("| | t = 1 | t = 2 |")
print("|---|---|---|")
for label, name in [("platen force", "grain_1_force_y"),
                    ("floor force", "wall_y-_force_y"),
                    ("wall x- force", "wall_x-_force_x"),
                    ("wall x+ force", "wall_x+_force_x")]:
    print(f"| {label} | {mean_force(name, 0.9, 1.0):.4g} | {mean_force(name, 1.9, 2.0):.4g} |")
cells = {}
for t in (1.0, 2.0):
    at = [r for r in contacts if abs(column(r, "time") - t) < 1e-3]
    forces = [column(r, "normal_force") for r in at]
    largest = max(forces)
    disks = [r for r in grains if abs(column(r, "time") - t) < 1e-3 and column(r, "grain") != 1]
    numbers = [column(r, "coordination_number") for r in disks]
    cells[t] = [
        sum(1 for f in forces if f > 1e-6 * largest),
        sum(int(column(r, "sliding")) for r in at),
        f"{largest:.4g} / {sum(forces) / len(forces):.4g}",
        f"{sum(numbers) / len(numbers):.3g} ({sum(1 for z in numbers if z < 2)})",
    ]
for k, label in enumerate(["contacts (above 1e-6 of the largest)", "sliding contacts",
                           "largest / mean normal force",
                           "mean coordination number (disks with fewer than 2)"]):
    print(f"| {label} | {cells[1.0][k]} | {cells[2.0][k]} |")

energy = rows("energy.csv")[-1]
W = column(energy, "boundary_work")
print(f"\nplaten work W = {W:.4g}; in units of W: energy {column(energy, 'total_energy') / W:.3f}, "
      f"kinetic {column(energy, 'kinetic_energy') / W:.2g}, friction work {column(energy, 'friction_work') / W:.3f}, "
      f"transfers {column(energy, 'transfer_work') / W:.4f}, leapfrog {column(energy, 'leapfrog_work') / W:.4f}, "
      f"hypoelastic correction {column(energy, 'hypoelastic_correction') / W:.4f}, "
      f"balance residual {column(energy, 'balance_residual') / W:.4f}")
PYTHON
