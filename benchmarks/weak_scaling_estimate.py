#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
"""Weak-scaling estimate of the explicit step from the figures of
benchmarks/communication_volume.sh (doc/parallel.md explains the model).

Per case, from the measured table: the time of a step on one rank (the
computation, which weak scaling keeps per rank), and on two ranks the
point-to-point messages and bytes the busier rank sends per step to its
one neighbour and the collective calls per step. At P ranks each rank holds
what the whole case holds on one rank (its points and cells, so the
computation stays t_1) in a compact subdomain with 8 (2D) or 26 (3D)
neighbours; the bytes grow from the one cut of the two-rank run to the
2 * dim sides of the subdomain, and every exchange goes to every
neighbour:

  t_comm(P) = messages * neighbours * latency
              + bytes * (boundary / cut) / bandwidth
              + collectives * collective_latency * log2(P)

and the efficiency is t_1 / (t_1 + t_comm(P)). Load imbalance, the
repartitioning and the output are not in it (doc/parallel.md).

Usage: python3 benchmarks/weak_scaling_estimate.py LOG [--latency 2e-6]
       [--bandwidth 5e9] [--collective-latency 3e-6]
LOG is the output of benchmarks/communication_volume.sh.
"""

import argparse
import math
import re
import sys

# The bytes per step grow from the one cut of the two-rank run (through the
# middle of the case, as long as a side of it) to the boundary of a compact
# subdomain of the same cells, 2 * dim sides: an assumption for the
# columns, whose cut follows the Morton curve.
DIMENSION = {"block2d": 2, "block3d": 3, "column2d": 2, "column3d": 3}
NEIGHBOURS = {2: 8, 3: 26}


def parse(log):
    """Rows of the table by case: ranks -> list of per-rank figures."""
    cases = {}
    name = None
    for line in log:
        fields = line.split()
        if len(fields) == 8 and fields[0] in DIMENSION:
            name, ranks = fields[0], int(fields[1])
            row = {
                "ms": float(fields[2]),
                "messages": float(fields[4]),
                "bytes": float(fields[5]),
                "collectives": float(fields[6]),
            }
            cases.setdefault(name, {}).setdefault(ranks, []).append(row)
        match = re.match(r"points: (\d+), cells: (\d+)", line)
        if match and name is not None:
            for rows in cases[name].values():
                for row in rows:
                    row["points"] = int(match.group(1))
    return cases


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("log", help="output of communication_volume.sh")
    parser.add_argument("--latency", type=float, default=2e-6,
                        help="seconds per point-to-point message")
    parser.add_argument("--bandwidth", type=float, default=5e9,
                        help="bytes per second a rank sends")
    parser.add_argument("--collective-latency", type=float, default=3e-6,
                        help="seconds per collective call and tree level")
    parser.add_argument("--ranks", type=int, nargs="+",
                        default=[2, 16, 128, 1000])
    args = parser.parse_args()
    with open(args.log) as f:
        cases = parse(f)
    if not cases:
        sys.exit("no case in " + args.log)

    print(f"latency {args.latency:g} s, bandwidth {args.bandwidth:g} B/s, "
          f"collective {args.collective_latency:g} s x log2(P)")
    print(f"{'case':9} {'points/rank':>11} {'t_1 ms':>8} "
          + " ".join(f"{'P=' + str(p):>16}" for p in args.ranks))
    for name, by_ranks in cases.items():
        dim = DIMENSION[name]
        one, two = by_ranks[1][0], by_ranks[2]
        # The busier of the two ranks.
        sent = max(two, key=lambda row: row["bytes"])
        # Weak scaling keeps the whole case on each rank. In the two-rank
        # run a rank sends across one cut through the case, as long as a
        # side of it; a compact subdomain of the case's cells has 2 dim
        # such sides.
        boundary_over_cut = 2 * dim
        cells = []
        for p in args.ranks:
            comm = (sent["messages"] * NEIGHBOURS[dim] * args.latency
                    + sent["bytes"] * boundary_over_cut / args.bandwidth
                    + sent["collectives"] * args.collective_latency
                    * math.log2(p))
            t1 = one["ms"] * 1e-3
            cells.append(f"{1e3 * comm:6.2f} ms {t1 / (t1 + comm):5.1%}")
        print(f"{name:9} {one['points']:>11} {one['ms']:>8.1f} "
              + " ".join(f"{c:>16}" for c in cells))
    print("(per P: communication per step and the efficiency "
          "t_1 / (t_1 + t_comm))")


if __name__ == "__main__":
    main()
