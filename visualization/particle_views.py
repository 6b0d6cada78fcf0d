# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
"""What fringe_pattern.py and render_grains.py share: the output times of a
particles.pvd, the splat size of the material points, and a top view of
the points drawn as disks of their own size. Needs ParaView (pvbatch)."""


def output_times(reader):
    """The times of a PVDReader's records, as a list (at least one)."""
    times = reader.TimestepValues
    if isinstance(times, (int, float)):
        return [float(times)]
    return list(times) if times else [0.0]


def splat_spacing(data):
    """The median material-point spacing of fetched point data: the square
    (2D, volume is area per unit thickness) or cube (3D) root of the median
    volume."""
    volumes = data.GetPointData().GetArray("volume")
    n = data.GetNumberOfPoints()
    sizes = sorted(volumes.GetValue(i) for i in range(n))
    bounds = data.GetBounds()
    three_d = bounds[5] - bounds[4] > 0.0
    return sizes[n // 2] ** (1.0 / 3.0 if three_d else 0.5)


def particle_view(source, array, lut, spacing, background, time, opacity=1.0):
    """A render view of SOURCE's points as disks of radius 0.75 spacing,
    coloured by the point array ARRAY through LUT, at TIME, with OPACITY."""
    from paraview.simple import CreateRenderView, Show

    view = CreateRenderView()
    view.OrientationAxesVisibility = 0
    view.Background = background
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.CameraParallelProjection = 1
    view.ViewTime = time
    display = Show(source, view)
    display.SetRepresentationType("Point Gaussian")
    display.ShaderPreset = "Plain circle"
    display.GaussianRadius = 0.75 * spacing
    display.ColorArrayName = ["POINTS", array]
    display.LookupTable = lut
    display.Opacity = opacity
    display.SetScalarBarVisibility(view, False)
    return view


def fit_top_view(view, bounds, spacing, aspect, fill):
    """Look down the z axis at the box BOUNDS (grown by one spacing on each
    side), scaled so that it fills the fraction 1/(2 fill) of a view of
    width/height ASPECT."""
    width = bounds[1] - bounds[0] + 2.0 * spacing
    height = bounds[3] - bounds[2] + 2.0 * spacing
    centre = [
        0.5 * (bounds[0] + bounds[1]),
        0.5 * (bounds[2] + bounds[3]),
        0.5 * (bounds[4] + bounds[5]),
    ]
    view.CameraFocalPoint = centre
    view.CameraPosition = [
        centre[0],
        centre[1],
        bounds[5] + 10.0 * max(width, height),
    ]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelScale = fill * max(height, width / aspect)
