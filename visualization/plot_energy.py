#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
"""Energy and momentum histories of grainmpm runs, side by side (as in Fig. 2
of Cummins & Brackbill, LA-UR-01-4102).

One column per energy.csv (for example the explicit and the implicit run of
a case); rows: total, kinetic and elastic energy; momentum; the energy
ledger (plastic, friction and boundary work, transfer work and the balance
residual) if the file has it. Energies are divided by the initial total
energy unless --absolute is given (a run that starts at rest is divided by
its largest kinetic plus elastic energy).

  python3 visualization/plot_energy.py \\
      results-single_grain_rebound_explicit/energy.csv \\
      results-single_grain_rebound_implicit/energy.csv \\
      --labels explicit implicit --output energy.png

Needs matplotlib (Debian: python3-matplotlib).
"""

import argparse
import csv
import os
import sys


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="plot_energy.py",
        description="Plot total, kinetic and elastic energy, momentum and "
        "the energy ledger against time from one or several grainmpm "
        "energy.csv files, one column per file, to PNG.",
    )
    parser.add_argument("files", nargs="+", help="energy.csv files")
    parser.add_argument(
        "--labels",
        nargs="+",
        default=None,
        help="column titles, one per file (default: the run directories)",
    )
    parser.add_argument("--output", default="energy.png", help="PNG file")
    parser.add_argument(
        "--absolute",
        action="store_true",
        help="plot energies in the run's units instead of relative to the "
        "initial total energy",
    )
    parser.add_argument(
        "--title", default=None, help="a title above the whole figure"
    )
    return parser.parse_args(argv)


def read_columns(filename):
    """The columns of an energy.csv as lists of floats, keyed by the name
    without its unit."""
    with open(filename, newline="") as file:
        rows = list(csv.reader(file))
    if len(rows) < 2:
        sys.exit("plot_energy.py: %s has no data rows" % filename)
    names = [name.split(" [")[0] for name in rows[0]]
    columns = {name: [] for name in names}
    for row in rows[1:]:
        if len(row) != len(names):
            continue  # a row being written
        for name, value in zip(names, row):
            columns[name].append(float(value))
    for needed in ("time", "kinetic_energy", "elastic_energy", "total_energy"):
        if needed not in columns:
            sys.exit("plot_energy.py: %s has no column %s" % (filename, needed))
    return columns


def main(argv):
    arguments = parse_arguments(argv)
    if arguments.labels is not None and len(arguments.labels) != len(
        arguments.files
    ):
        sys.exit("plot_energy.py: give one label per file")
    labels = arguments.labels or [
        os.path.basename(os.path.dirname(os.path.abspath(f))) for f in arguments.files
    ]

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = [read_columns(f) for f in arguments.files]
    ledger = ["plastic_work", "friction_work", "boundary_work", "transfer_work",
              "leapfrog_work", "hypoelastic_correction", "balance_residual"]
    # (leapfrog_work and hypoelastic_correction: files written since they
    # were added; optional)
    optional = ("leapfrog_work", "hypoelastic_correction")
    with_ledger = all(
        all(name in run for name in ledger if name not in optional) for run in runs
    )
    n_rows = 3 if with_ledger else 2

    figure, axes = plt.subplots(
        n_rows,
        len(runs),
        figsize=(5.0 * len(runs), 3.2 * n_rows),
        squeeze=False,
        sharex="col",
    )
    for column, (run, label) in enumerate(zip(runs, labels)):
        time = run["time"]
        scale = 1.0
        unit = ""
        if not arguments.absolute:
            scale = run["total_energy"][0]
            unit = " / E(0)"
            if not scale > 0.0:
                scale = max(
                    k + e for k, e in zip(run["kinetic_energy"], run["elastic_energy"])
                )
                unit = " / E_max"
            if not scale > 0.0:
                scale = 1.0
                unit = ""

        def scaled(name):
            return [value / scale for value in run[name]]

        top = axes[0][column]
        top.plot(time, scaled("total_energy"), "k-", label="total")
        top.plot(time, scaled("kinetic_energy"), "b-", label="kinetic")
        top.plot(time, scaled("elastic_energy"), "r-", label="elastic")
        if "gravity_potential" in run and any(run["gravity_potential"]):
            top.plot(time, scaled("gravity_potential"), "g-", label="gravity")
        top.set_title(label)
        top.set_ylabel("energy" + unit)
        top.grid(True, alpha=0.3)
        top.legend(loc="best", fontsize="small")

        middle = axes[1][column]
        for axis, name in enumerate(("momentum_x", "momentum_y", "momentum_z")):
            if name in run:
                middle.plot(time, run[name], label=name.replace("_", " "))
        middle.set_ylabel("momentum")
        middle.grid(True, alpha=0.3)
        middle.legend(loc="best", fontsize="small")

        if with_ledger:
            bottom = axes[2][column]
            styles = {
                "plastic_work": "m-",
                "friction_work": "c-",
                "boundary_work": "y-",
                "transfer_work": "b--",
                "leapfrog_work": "r--",
                "hypoelastic_correction": "g:",
                "balance_residual": "k-",
            }
            for name in ledger:
                if name in run and any(run[name]):
                    bottom.plot(
                        time, scaled(name), styles[name],
                        label=name.replace("_", " "),
                    )
            bottom.set_ylabel("ledger" + unit)
            bottom.grid(True, alpha=0.3)
            bottom.legend(loc="best", fontsize="small")
        axes[n_rows - 1][column].set_xlabel("time")

    if arguments.title:
        figure.suptitle(arguments.title)
    figure.tight_layout()
    figure.savefig(arguments.output, dpi=100)
    print("plot_energy.py: %d run(s) -> %s" % (len(runs), arguments.output))


if __name__ == "__main__":
    main(sys.argv[1:])
