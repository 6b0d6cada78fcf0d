# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
"""Dark-field isochromatic fringe picture of a grainmpm run (as in Fig. 3 of
Cummins & Brackbill, LA-UR-01-4102).

Reads particles.pvd, takes the particle field fringe_order
N = thickness (sigma_1 - sigma_2) / material fringe value (written for
materials with a 'Material fringe value'), and renders the light intensity
of a dark-field circular polariscope, I = sin^2(pi N), black to white, at one
output time: every material point is drawn as a disk of its own size, so
the picture is a splat of the particles onto the image.

Run it with ParaView's batch interpreter, headless under a virtual display:

  xvfb-run -a pvbatch visualization/fringe_pattern.py \\
      results-five_grains_implicit/particles.pvd --time 50 \\
      --output fringe_implicit.png

For a material without a fringe value, --fringes-per-stress F uses
N = F (sigma_1 - sigma_2) from the field principal_stress_difference.
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="fringe_pattern.py",
        description="Render the dark-field isochromatic fringe picture "
        "I = sin^2(pi N) of a grainmpm particles.pvd to PNG (run with "
        "'xvfb-run -a pvbatch').",
    )
    parser.add_argument("pvd", help="the particles.pvd of a run")
    parser.add_argument(
        "--time",
        type=float,
        default=None,
        help="output time to render (the nearest written one); default: "
        "the last",
    )
    parser.add_argument(
        "--output", default="fringe_pattern.png", help="PNG file to write"
    )
    parser.add_argument(
        "--resolution",
        type=int,
        nargs=2,
        default=[1600, 1000],
        metavar=("WIDTH", "HEIGHT"),
        help="image size in pixels (default 1600 1000)",
    )
    parser.add_argument(
        "--fringes-per-stress",
        type=float,
        default=None,
        help="use N = F (sigma_1 - sigma_2) with this F (thickness / "
        "material fringe value) instead of the field fringe_order",
    )
    parser.add_argument(
        "--light-field",
        action="store_true",
        help="light field, I = cos^2(pi N), instead of dark field",
    )
    return parser.parse_args(argv)


def main(argv):
    arguments = parse_arguments(argv)

    # Import late, so that --help works without ParaView.
    from paraview import servermanager
    from paraview.simple import (
        Calculator,
        GetColorTransferFunction,
        PVDReader,
        SaveScreenshot,
        UpdatePipeline,
    )

    from particle_views import (
        fit_top_view,
        output_times,
        particle_view,
        splat_spacing,
    )

    reader = PVDReader(FileName=arguments.pvd)
    times = output_times(reader)
    time = (
        times[-1]
        if arguments.time is None
        else min(times, key=lambda t: abs(t - arguments.time))
    )
    UpdatePipeline(time=time, proxy=reader)
    fields = reader.PointData.keys()

    if arguments.fringes_per_stress is not None:
        if "principal_stress_difference" not in fields:
            sys.exit("fringe_pattern.py: no field principal_stress_difference "
                     "in " + arguments.pvd)
        order = "%.17g*principal_stress_difference" % arguments.fringes_per_stress
    else:
        if "fringe_order" not in fields:
            sys.exit("fringe_pattern.py: no field fringe_order in "
                     + arguments.pvd)
        order = "fringe_order"
    intensity = Calculator(Input=reader)
    intensity.ResultArrayName = "intensity"
    intensity.Function = "%s(%.17g*%s)^2" % (
        "cos" if arguments.light_field else "sin",
        math.pi,
        order,
    )
    UpdatePipeline(time=time, proxy=intensity)

    data = servermanager.Fetch(intensity)
    n_points = data.GetNumberOfPoints()
    if n_points == 0:
        sys.exit("fringe_pattern.py: no particles at t = %g" % time)
    if arguments.fringes_per_stress is None:
        largest = data.GetPointData().GetArray("fringe_order").GetRange()[1]
        if largest == 0.0:
            sys.exit(
                "fringe_pattern.py: fringe_order is zero everywhere at t = %g: "
                "give the material a 'Material fringe value' (and "
                "'Thickness'), or use --fringes-per-stress" % time
            )

    lut = GetColorTransferFunction("intensity")
    lut.ApplyPreset("Grayscale", True)
    lut.RescaleTransferFunction(0.0, 1.0)
    lut.AutomaticRescaleRangeMode = "Never"
    spacing = splat_spacing(data)
    view = particle_view(
        intensity, "intensity", lut, spacing, [0.0, 0.0, 0.0], time
    )
    view.ViewSize = arguments.resolution
    aspect = float(arguments.resolution[0]) / arguments.resolution[1]
    fit_top_view(view, data.GetBounds(), spacing, aspect, 0.515)
    SaveScreenshot(
        arguments.output, view, ImageResolution=arguments.resolution
    )
    print(
        "fringe_pattern.py: %s at t = %g (%d material points, largest "
        "N = %.3g) -> %s"
        % (
            arguments.pvd,
            time,
            n_points,
            data.GetPointData().GetArray("fringe_order").GetRange()[1]
            if arguments.fringes_per_stress is None
            else arguments.fringes_per_stress
            * data.GetPointData()
            .GetArray("principal_stress_difference")
            .GetRange()[1],
            arguments.output,
        )
    )


if __name__ == "__main__":
    main(sys.argv[1:])
