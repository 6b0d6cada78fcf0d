# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
"""Grain positions of a grainmpm run at chosen times, side by side (as in
Fig. 1 of Cummins & Brackbill, LA-UR-01-4102).

Reads particles.pvd and draws every material point as a disk of its own
size, coloured by its grain, one panel per requested time, all panels on
the same scale (the box spanned by the particles over the chosen times).
Several runs can be given (for example explicit and implicit): then there
is one row of panels per run.

  xvfb-run -a pvbatch visualization/render_grains.py \\
      results-single_grain_rebound_explicit/particles.pvd \\
      results-single_grain_rebound_implicit/particles.pvd \\
      --times 0 2 --output grains.png
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

# Qualitative colours for grains 1, 2, ... (cycled).
PALETTE = [
    (0.122, 0.467, 0.706),
    (1.000, 0.498, 0.055),
    (0.173, 0.627, 0.173),
    (0.839, 0.153, 0.157),
    (0.580, 0.404, 0.741),
    (0.549, 0.337, 0.294),
    (0.890, 0.467, 0.761),
    (0.498, 0.498, 0.498),
    (0.737, 0.741, 0.133),
    (0.090, 0.745, 0.812),
]


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="render_grains.py",
        description="Render the material points of one or several grainmpm "
        "runs coloured by grain at chosen times, one panel per time and one "
        "row per run, to PNG (run with 'xvfb-run -a pvbatch').",
    )
    parser.add_argument("pvd", nargs="+", help="particles.pvd of each run")
    parser.add_argument(
        "--times",
        type=float,
        nargs="+",
        default=None,
        help="output times (the nearest written ones); default: first and "
        "last",
    )
    parser.add_argument("--output", default="grains.png", help="PNG file")
    parser.add_argument(
        "--labels",
        nargs="+",
        default=None,
        help="a name per run, written on its panels (default: the run "
        "directories)",
    )
    parser.add_argument(
        "--panel-size",
        type=int,
        nargs=2,
        default=[500, 500],
        metavar=("WIDTH", "HEIGHT"),
        help="pixels per panel (default 500 500)",
    )
    return parser.parse_args(argv)


def main(argv):
    arguments = parse_arguments(argv)

    from paraview import servermanager
    from paraview.simple import (
        AssignViewToLayout,
        CreateLayout,
        GetColorTransferFunction,
        PVDReader,
        SaveScreenshot,
        Show,
        Text,
        UpdatePipeline,
    )

    from particle_views import (
        fit_top_view,
        output_times,
        particle_view,
        splat_spacing,
    )

    if arguments.labels is not None and len(arguments.labels) != len(
        arguments.pvd
    ):
        sys.exit("render_grains.py: give one label per run")
    labels = arguments.labels or [
        os.path.basename(os.path.dirname(os.path.abspath(p))) for p in arguments.pvd
    ]
    readers = []
    for pvd in arguments.pvd:
        reader = PVDReader(FileName=pvd)
        readers.append((reader, output_times(reader)))

    # The panels: (run, time) pairs, and the common box.
    panels = []
    bounds = [float("inf"), -float("inf")] * 3
    largest_grain = 1
    spacing = 0.0
    for reader, times in readers:
        wanted = arguments.times or [times[0], times[-1]]
        row = []
        for t in wanted:
            time = min(times, key=lambda s: abs(s - t))
            UpdatePipeline(time=time, proxy=reader)
            data = servermanager.Fetch(reader)
            if data.GetNumberOfPoints() == 0:
                sys.exit("render_grains.py: no particles at t = %g" % time)
            b = data.GetBounds()
            for k in range(3):
                bounds[2 * k] = min(bounds[2 * k], b[2 * k])
                bounds[2 * k + 1] = max(bounds[2 * k + 1], b[2 * k + 1])
            grains = data.GetPointData().GetArray("grain")
            largest_grain = max(largest_grain, int(grains.GetRange()[1]))
            spacing = max(spacing, splat_spacing(data))
            row.append(time)
        panels.append(row)

    lut = GetColorTransferFunction("grain")
    lut.InterpretValuesAsCategories = 1
    annotations, colours = [], []
    for g in range(1, largest_grain + 1):
        annotations += [str(g), "grain %d" % g]
        colours += list(PALETTE[(g - 1) % len(PALETTE)])
    lut.Annotations = annotations
    lut.IndexedColors = colours

    aspect = float(arguments.panel_size[0]) / arguments.panel_size[1]

    layout = CreateLayout("grains")
    n_rows, n_columns = len(panels), len(panels[0])
    views = []
    for r, ((reader, _), row) in enumerate(zip(readers, panels)):
        for c, time in enumerate(row):
            view = particle_view(
                reader, "grain", lut, spacing, [1.0, 1.0, 1.0], time
            )
            fit_top_view(view, bounds, spacing, aspect, 0.56)
            caption = Text(Text="%s, t = %g" % (labels[r], time))
            caption_display = Show(caption, view)
            caption_display.WindowLocation = "Upper Left Corner"
            caption_display.FontSize = 14
            caption_display.Color = [0.0, 0.0, 0.0]
            views.append((r, c, view))

    # Split the layout into a grid of n_rows x n_columns cells.
    # (Split returns the first child's index; the second is the next.)
    def split(cell, count, direction):
        cells = [cell]
        for k in range(count - 1):
            fraction = 1.0 / (count - k)
            if direction == "v":
                first = layout.SplitVertical(cells[-1], fraction)
            else:
                first = layout.SplitHorizontal(cells[-1], fraction)
            cells[-1] = first
            cells.append(first + 1)
        return cells

    rows = split(0, n_rows, "v")
    for r, row_cell in enumerate(rows):
        columns = split(row_cell, n_columns, "h")
        for c, cell in enumerate(columns):
            view = [v for (rr, cc, v) in views if rr == r and cc == c][0]
            AssignViewToLayout(view=view, layout=layout, hint=cell)

    size = [arguments.panel_size[0] * n_columns, arguments.panel_size[1] * n_rows]
    layout.SetSize(size[0], size[1])
    SaveScreenshot(arguments.output, layout, ImageResolution=size)
    print(
        "render_grains.py: %d run(s) at t = %s -> %s"
        % (
            len(panels),
            ", ".join("%g" % t for t in panels[0]),
            arguments.output,
        )
    )


if __name__ == "__main__":
    main(sys.argv[1:])
