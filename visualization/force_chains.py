# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
"""Force chains of a grainmpm run: the contact network over the grains.

Reads particles.pvd and contacts.pvd of a run (contacts.pvd is written with
Output/Write contacts = true, the default) and draws, one panel per
requested time, the material points in light greys (alternating by grain)
and each contact as a line from the centre of one grain to the centre of
the other (to the contact point for a rigid grain, such as a platen), its
width proportional to the normal contact force (the mean over the output
interval that ends at that time) and its colour showing the force. A 3D
run is seen along z, through faint grains, so that the chains of all
depths show.

  xvfb-run -a pvbatch visualization/force_chains.py \\
      results-compression_of_100_disks/particles.pvd --times 0.5 1 \\
      --output force_chains.png
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="force_chains.py",
        description="Draw the contact forces of a grainmpm run as lines "
        "whose width follows the normal force, over the grains, at chosen "
        "times, to PNG (run with 'xvfb-run -a pvbatch').",
    )
    parser.add_argument("pvd", help="particles.pvd of the run")
    parser.add_argument(
        "--contacts",
        default=None,
        help="contacts.pvd of the run (default: beside particles.pvd)",
    )
    parser.add_argument(
        "--times",
        type=float,
        nargs="+",
        default=None,
        help="output times (the nearest written ones); default: the last",
    )
    parser.add_argument("--output", default="force_chains.png", help="PNG file")
    parser.add_argument(
        "--width",
        type=float,
        default=None,
        help="width of the line of the largest force, in length units "
        "(default: 1/60 of the width of the grains' box)",
    )
    parser.add_argument(
        "--panel-size",
        type=int,
        nargs=2,
        default=[600, 600],
        metavar=("WIDTH", "HEIGHT"),
        help="pixels per panel (default 600 600)",
    )
    return parser.parse_args(argv)


def main(argv):
    arguments = parse_arguments(argv)
    contacts_pvd = arguments.contacts or os.path.join(
        os.path.dirname(os.path.abspath(arguments.pvd)), "contacts.pvd"
    )
    for path in (arguments.pvd, contacts_pvd):
        if not os.path.isfile(path):
            sys.exit(
                "force_chains.py: no file '%s' (contacts.pvd is written with "
                "Output/Write contacts = true)" % path
            )

    from paraview import servermanager
    from paraview.simple import (
        AssignViewToLayout,
        Calculator,
        CellDatatoPointData,
        CreateLayout,
        ExtractSurface,
        GetColorTransferFunction,
        GetScalarBar,
        PVDReader,
        SaveScreenshot,
        Show,
        Text,
        Tube,
        UpdatePipeline,
    )

    from particle_views import (
        fit_top_view,
        output_times,
        particle_view,
        splat_spacing,
    )

    particles = PVDReader(FileName=arguments.pvd)
    contacts = PVDReader(FileName=contacts_pvd)
    times = output_times(particles)
    wanted = arguments.times or [times[-1]]
    panels = [min(times, key=lambda s: abs(s - t)) for t in wanted]

    # The common box, the point spacing and the largest normal force over
    # the panels.
    bounds = [float("inf"), -float("inf")] * 3
    spacing, largest_force, largest_grain = 0.0, 0.0, 1
    for time in panels:
        UpdatePipeline(time=time, proxy=particles)
        data = servermanager.Fetch(particles)
        if data.GetNumberOfPoints() == 0:
            sys.exit("force_chains.py: no particles at t = %g" % time)
        b = data.GetBounds()
        for k in range(3):
            bounds[2 * k] = min(bounds[2 * k], b[2 * k])
            bounds[2 * k + 1] = max(bounds[2 * k + 1], b[2 * k + 1])
        spacing = max(spacing, splat_spacing(data))
        largest_grain = max(
            largest_grain, int(data.GetPointData().GetArray("grain").GetRange()[1])
        )
        UpdatePipeline(time=time, proxy=contacts)
        forces = servermanager.Fetch(contacts).GetCellData().GetArray("normal_force")
        if forces is not None and forces.GetNumberOfTuples() > 0:
            largest_force = max(largest_force, forces.GetRange()[1])
    if largest_force <= 0.0:
        sys.exit("force_chains.py: no contact forces at t = %s" % panels)
    width = arguments.width or (bounds[1] - bounds[0]) / 60.0
    # In 3D the view along z sees the chains through the grains: the
    # material points are drawn faint, or they would hide all but the
    # front layer of chains.
    opacity = 0.08 if bounds[5] - bounds[4] > 2.0 * spacing else 1.0

    # Grains in two light greys, alternating by grain number.
    grey = GetColorTransferFunction("grain")
    grey.InterpretValuesAsCategories = 1
    annotations, colours = [], []
    for g in range(1, largest_grain + 1):
        annotations += [str(g), "grain %d" % g]
        colours += [0.80, 0.80, 0.80] if g % 2 else [0.68, 0.68, 0.70]
    grey.Annotations = annotations
    grey.IndexedColors = colours

    # Lines as tubes of radius (width / 2) N / N_max.
    on_points = CellDatatoPointData(Input=contacts)
    radius = Calculator(Input=on_points)
    radius.ResultArrayName = "tube_radius"
    radius.Function = "max(normal_force, 0) / %.17g * %.17g" % (
        largest_force,
        0.5 * width,
    )
    tubes = Tube(Input=ExtractSurface(Input=radius))
    tubes.Scalars = ["POINTS", "tube_radius"]
    tubes.VaryRadius = "By Absolute Scalar"
    tubes.Radius = 0.5 * width
    tubes.NumberofSides = 12
    force_lut = GetColorTransferFunction("normal_force")
    force_lut.ApplyPreset("Inferno (matplotlib)", True)
    force_lut.RescaleTransferFunction(0.0, largest_force)

    aspect = float(arguments.panel_size[0]) / arguments.panel_size[1]
    layout = CreateLayout("force chains")
    views = []
    for time in panels:
        view = particle_view(
            particles, "grain", grey, spacing, [1.0, 1.0, 1.0], time, opacity
        )
        display = Show(tubes, view)
        display.ColorArrayName = ["POINTS", "normal_force"]
        display.LookupTable = force_lut
        display.SetScalarBarVisibility(view, True)
        bar = GetScalarBar(force_lut, view)
        bar.Title = "normal force"
        bar.ComponentTitle = ""
        bar.TitleColor = [0.0, 0.0, 0.0]
        bar.LabelColor = [0.0, 0.0, 0.0]
        fit_top_view(view, bounds, spacing, aspect, 0.56)
        caption = Text(Text="t = %g" % time)
        caption_display = Show(caption, view)
        caption_display.WindowLocation = "Upper Left Corner"
        caption_display.FontSize = 14
        caption_display.Color = [0.0, 0.0, 0.0]
        views.append(view)

    cell = 0
    for k, view in enumerate(views):
        if k < len(views) - 1:
            cell = layout.SplitHorizontal(cell, 1.0 / (len(views) - k))
            AssignViewToLayout(view=view, layout=layout, hint=cell)
            cell += 1
        else:
            AssignViewToLayout(view=view, layout=layout, hint=cell)
    size = [arguments.panel_size[0] * len(views), arguments.panel_size[1]]
    layout.SetSize(size[0], size[1])
    SaveScreenshot(arguments.output, layout, ImageResolution=size)
    print(
        "force_chains.py: t = %s, largest normal force %.4g -> %s"
        % (", ".join("%g" % t for t in panels), largest_force, arguments.output)
    )


if __name__ == "__main__":
    main(sys.argv[1:])
