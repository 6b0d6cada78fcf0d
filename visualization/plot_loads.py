#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
"""Loads on the walls and rigid grains of grainmpm runs (walls.csv).

Plots, for every walls.csv given, the force that the grains exert on a box
face or a rigid grain (a platen) against time or against the platen's
displacement. walls.csv holds one row per step; the force of a step is the
constraint impulse over the step, so it is noisy from step to step: it is
shown averaged over a moving window (--window, in time units), which keeps
the impulse of every interval.

  python3 visualization/plot_loads.py results-compression/walls.csv \\
      --load grain_1 --component y --versus displacement \\
      --output platen_load.png

--load names the loaded body as in the column names of walls.csv: wall_x-,
wall_y+, ... or grain_N (a rigid grain). --versus displacement takes the
displacement of that rigid grain's centre from the grains.csv beside
walls.csv. Needs matplotlib (Debian: python3-matplotlib).
"""

import argparse
import csv
import os
import sys


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="plot_loads.py",
        description="Plot the force on a box face or rigid grain from one "
        "or several grainmpm walls.csv files against time or the rigid "
        "grain's displacement, to PNG.",
    )
    parser.add_argument("files", nargs="+", help="walls.csv files")
    parser.add_argument(
        "--load",
        default=None,
        help="the loaded body: wall_x-, wall_x+, wall_y-, ... or grain_N "
        "(default: the first rigid grain, else the wall with the largest "
        "load)",
    )
    parser.add_argument(
        "--component",
        default=None,
        choices=["x", "y", "z"],
        help="force component (default: the one with the largest load)",
    )
    parser.add_argument(
        "--versus",
        default="time",
        choices=["time", "displacement"],
        help="abscissa: time, or the displacement of the rigid grain's "
        "centre along the component (from grains.csv)",
    )
    parser.add_argument(
        "--window",
        type=float,
        default=None,
        help="moving average over this much time (default: 1/50 of the run)",
    )
    parser.add_argument(
        "--labels",
        nargs="+",
        default=None,
        help="a name per file (default: the run directories)",
    )
    parser.add_argument("--negate", action="store_true", help="plot -force")
    parser.add_argument("--output", default="loads.png", help="PNG file")
    return parser.parse_args(argv)


def read_columns(filename):
    """Columns of a CSV file as lists of floats, keyed by the name without
    its unit; also the units."""
    with open(filename, newline="") as file:
        rows = list(csv.reader(file))
    if len(rows) < 2:
        sys.exit("plot_loads.py: '%s' has no rows" % filename)
    names = [h.split(" [")[0] for h in rows[0]]
    units = {h.split(" [")[0]: h[h.find("[") + 1 : -1] for h in rows[0] if "[" in h}
    columns = {n: [] for n in names}
    for row in rows[1:]:
        for name, value in zip(names, row):
            columns[name].append(float(value))
    return columns, units


def moving_average(times, steps, values, window):
    """Mean of VALUES over (t - window, t] weighted by the step lengths."""
    averaged, total, start = [], 0.0, 0
    weight = 0.0
    for k in range(len(times)):
        total += values[k] * steps[k]
        weight += steps[k]
        while times[start] <= times[k] - window:
            total -= values[start] * steps[start]
            weight -= steps[start]
            start += 1
        averaged.append(total / weight if weight > 0.0 else 0.0)
    return averaged


def choose(columns, load, component):
    """The column name of the force to plot."""
    forces = [n for n in columns if "_force_" in n]
    if not forces:
        sys.exit("plot_loads.py: walls.csv has no force columns (no closed "
                 "face and no rigid grain)")
    if load is None:
        rigid = [n for n in forces if n.startswith("grain_")]
        candidates = rigid or forces
    else:
        candidates = [n for n in forces if n.startswith(load + "_force_")]
        if not candidates:
            sys.exit("plot_loads.py: no load '%s' in walls.csv (there are: %s)"
                     % (load, ", ".join(sorted({n.rsplit("_force_", 1)[0] for n in forces}))))
    if component is not None:
        candidates = [n for n in candidates if n.endswith("_force_" + component)]
        if not candidates:
            sys.exit("plot_loads.py: no component %s" % component)
    return max(candidates, key=lambda n: sum(abs(v) for v in columns[n]))


def main(argv):
    arguments = parse_arguments(argv)
    if arguments.labels is not None and len(arguments.labels) != len(arguments.files):
        sys.exit("plot_loads.py: give one label per file")
    labels = arguments.labels or [
        os.path.basename(os.path.dirname(os.path.abspath(f))) for f in arguments.files
    ]

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(7.0, 4.5))
    for filename, label in zip(arguments.files, labels):
        columns, units = read_columns(filename)
        name = choose(columns, arguments.load, arguments.component)
        times, steps = columns["time"], columns["dt"]
        window = arguments.window or (times[-1] - times[0]) / 50.0
        force = moving_average(times, steps, columns[name], window)
        if arguments.negate:
            force = [-f for f in force]
        abscissa, abscissa_label = times, "time [%s]" % units.get("time", "T")
        if arguments.versus == "displacement":
            body, component = name.rsplit("_force_", 1)
            if not body.startswith("grain_"):
                sys.exit("plot_loads.py: --versus displacement needs a rigid "
                         "grain (--load grain_N)")
            grains, _ = read_columns(os.path.join(os.path.dirname(filename), "grains.csv"))
            number = float(body.split("_")[1])
            track = [(t, c) for t, g, c in zip(grains["time"], grains["grain"],
                                              grains["centre_" + component]) if g == number]
            if len(track) < 2:
                sys.exit("plot_loads.py: grains.csv has fewer than two rows of %s" % body)
            # The displacement at each row of walls.csv, by linear
            # interpolation between the output times.
            abscissa, j = [], 0
            for t in times:
                while j < len(track) - 2 and track[j + 1][0] < t:
                    j += 1
                (t0, c0), (t1, c1) = track[j], track[j + 1]
                c = c0 + (c1 - c0) * (t - t0) / (t1 - t0) if t1 > t0 else c0
                abscissa.append(abs(c - track[0][1]))
            abscissa_label = "displacement of %s [L]" % body.replace("_", " ")
        axes.plot(abscissa, force, label="%s: %s" % (label, name.replace("_", " ")))
        axes.set_ylabel("force [%s]" % units.get(name, ""))
    axes.set_xlabel(abscissa_label)
    axes.grid(True, alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(arguments.output, dpi=100)
    print("plot_loads.py: %d file(s) -> %s" % (len(arguments.files), arguments.output))


if __name__ == "__main__":
    main(sys.argv[1:])
