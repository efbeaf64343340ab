#!/usr/bin/python3
"""Headless picture of one step of a run: the wheel surface of fix wheel/cosim (coloured by its
contact pressure), LIGGGHTS' particle dump (spheres of their radius, coloured by speed) and,
optionally, an SCM terrain snapshot from ``wheelsim-post vtk`` (warped by its height), rendered
offscreen with VTK's Python bindings, as ParaView would show them (docs/paraview.md).

Needs Debian's python3-vtk9 and, without a display, xvfb (``apt-get install python3-vtk9 xvfb
xauth``; not wheelsim dependencies, only for pictures): Debian's VTK renders through X only (no
OSMesa or EGL window), so headless runs go through ``xvfb-run``. Example (docs/paraview.md):

    xvfb-run -a /usr/bin/python3 postprocess/paraview_screenshot.py \\
        --wheel WORK/wheel_surface_19500.vtk --particles WORK/particles_19500.vtk \\
        --clip-y 0 --view -30 15 --out docs/images/paraview_coupled.png
"""

import argparse
import re
import sys

import numpy as np

try:
    import vtk
    from vtk.util import numpy_support
except ImportError:
    sys.exit(
        "paraview_screenshot: error: needs VTK's Python bindings (apt-get install python3-vtk9)"
    )


def legacy_reader(path):
    """Reader of a legacy .vtk file (polydata or unstructured grid)."""
    reader = vtk.vtkGenericDataObjectReader()
    reader.SetFileName(path)
    reader.ReadAllScalarsOn()
    reader.ReadAllVectorsOn()
    reader.ReadAllFieldsOn()
    reader.Update()
    if reader.GetOutput() is None or reader.GetOutput().GetNumberOfPoints() == 0:
        sys.exit(f"paraview_screenshot: error: no points in '{path}'")
    return reader


def colour_bar(mapper, title):
    bar = vtk.vtkScalarBarActor()
    bar.SetLookupTable(mapper.GetLookupTable())
    bar.SetTitle(title)
    bar.SetNumberOfLabels(4)
    bar.SetWidth(0.08)
    bar.SetHeight(0.4)
    for prop in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
        prop.SetColor(0.1, 0.1, 0.1)
        prop.SetFontSize(14)
        prop.ItalicOff()
        prop.ShadowOff()
    return bar


_ALIVE = []  # filters whose output ports are in use (a collected filter leaves a dangling port)


def lookup_table(hue, saturation=(1.0, 1.0), value=(1.0, 1.0)):
    """A colour lookup table over the given (start, end) hue, saturation and value ranges."""
    lut = vtk.vtkLookupTable()
    lut.SetHueRange(*hue)
    lut.SetSaturationRange(*saturation)
    lut.SetValueRange(*value)
    lut.Build()
    return lut


def clipped(port, clip_y):
    """The part of ``port``'s data at y >= clip_y (all of it if clip_y is None)."""
    if clip_y is None:
        return port
    plane = vtk.vtkPlane()
    plane.SetOrigin(0.0, clip_y, 0.0)
    plane.SetNormal(0.0, 1.0, 0.0)
    clip = vtk.vtkClipDataSet()
    clip.SetInputConnection(port)
    clip.SetClipFunction(plane)
    _ALIVE.append(clip)
    return clip.GetOutputPort()


def wheel_actor(path, clip_y):
    reader = legacy_reader(path)
    data = reader.GetOutput()
    mapper = vtk.vtkDataSetMapper()
    mapper.SetInputConnection(clipped(reader.GetOutputPort(), clip_y))
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray("contact_pressure")
    high = data.GetCellData().GetArray("contact_pressure").GetRange()[1]
    mapper.SetScalarRange(0.0, max(high, 1.0))
    mapper.SetLookupTable(lookup_table((0.667, 0.0)))
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    title = open(path, encoding="utf-8").read().splitlines()[1]
    match = re.search(r"step (\d+), time (\S+) s", title)
    return actor, colour_bar(mapper, "contact pressure [Pa]"), match


def kept_points(data, clip_y):
    """A polydata of the points of ``data`` at y >= clip_y, with their point arrays."""
    xyz = numpy_support.vtk_to_numpy(data.GetPoints().GetData())
    keep = np.flatnonzero(xyz[:, 1] >= clip_y)
    out = vtk.vtkPolyData()
    points = vtk.vtkPoints()
    points.SetData(numpy_support.numpy_to_vtk(np.ascontiguousarray(xyz[keep]), deep=True))
    out.SetPoints(points)
    arrays = data.GetPointData()
    for i in range(arrays.GetNumberOfArrays()):
        values = numpy_support.vtk_to_numpy(arrays.GetArray(i))
        array = numpy_support.numpy_to_vtk(np.ascontiguousarray(values[keep]), deep=True)
        array.SetName(arrays.GetArrayName(i))
        out.GetPointData().AddArray(array)
    return out


def particle_actor(path, clip_y):
    reader = legacy_reader(path)
    data = reader.GetOutput()
    points = data.GetPointData()
    if clip_y is not None:  # whole particles: keep those whose centre is at y >= clip_y
        data = kept_points(data, clip_y)
    if points.GetArray("radius") is None:
        sys.exit(f"paraview_screenshot: error: '{path}' has no point array 'radius'")
    speed = vtk.vtkArrayCalculator()
    speed.SetInputData(data)
    velocity = "v" if points.GetArray("v") is not None else None
    if velocity:
        speed.AddVectorArrayName("v")
        speed.SetFunction("mag(v)")
    else:
        speed.AddScalarVariable("vx", "vx")
        speed.AddScalarVariable("vy", "vy")
        speed.AddScalarVariable("vz", "vz")
        speed.SetFunction("sqrt(vx*vx+vy*vy+vz*vz)")
    speed.SetResultArrayName("speed")
    speed.Update()
    # glyphs scaled by the radius, coloured by the speed
    out = speed.GetOutput()
    out.GetPointData().SetActiveScalars("radius")
    sphere = vtk.vtkSphereSource()
    sphere.SetRadius(1.0)
    sphere.SetThetaResolution(10)
    sphere.SetPhiResolution(8)
    glyph = vtk.vtkGlyph3D()
    glyph.SetInputData(out)
    glyph.SetSourceConnection(sphere.GetOutputPort())
    glyph.SetScaleModeToScaleByScalar()
    glyph.SetColorModeToColorByScalar()
    glyph.SetInputArrayToProcess(0, 0, 0, 0, "radius")
    glyph.SetInputArrayToProcess(3, 0, 0, 0, "speed")
    glyph.Update()
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(glyph.GetOutputPort())
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("speed")
    high = out.GetPointData().GetArray("speed").GetRange()[1]
    mapper.SetScalarRange(0.0, max(high, 1e-3))
    mapper.SetLookupTable(lookup_table((0.55, 0.1), (0.35, 0.8), (0.85, 0.95)))
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    bar = colour_bar(mapper, "particle speed [m/s]")
    bar.SetPosition(0.02, 0.08)
    return actor, bar, data.GetNumberOfPoints()


def terrain_actor(path):
    reader = vtk.vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    _ALIVE.append(reader)
    geometry = vtk.vtkImageDataGeometryFilter()
    geometry.SetInputConnection(reader.GetOutputPort())
    warp = vtk.vtkWarpScalar()
    warp.SetInputConnection(geometry.GetOutputPort())
    warp.SetInputArrayToProcess(0, 0, 0, 0, "height")
    warp.SetNormal(0, 0, 1)
    warp.UseNormalOn()
    warp.SetScaleFactor(1.0)
    mapper = vtk.vtkDataSetMapper()
    mapper.SetInputConnection(warp.GetOutputPort())
    mapper.SetScalarModeToUsePointFieldData()
    name = "sinkage" if reader.GetOutput().GetPointData().GetArray("sinkage") else "height"
    mapper.SelectColorArray(name)
    mapper.SetScalarRange(reader.GetOutput().GetPointData().GetArray(name).GetRange())
    mapper.SetLookupTable(lookup_table((0.12, 0.02), (0.3, 0.9), (0.95, 0.45)))
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    return actor


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--wheel", metavar="FILE.vtk", help="fix wheel/cosim VTK")
    parser.add_argument("--particles", metavar="FILE.vtk", help="dump custom/vtk file")
    parser.add_argument("--terrain", metavar="FILE.vti", help="wheelsim-post vtk snapshot")
    parser.add_argument("--out", required=True, metavar="FILE.png", help="picture to write")
    parser.add_argument(
        "--clip-y",
        type=float,
        metavar="Y",
        help="show only y >= Y [m] (a cut through wheel and bed, e.g. 0: the wheel's mid-plane)",
    )
    parser.add_argument("--size", type=int, nargs=2, default=(1200, 700), metavar=("W", "H"))
    parser.add_argument(
        "--view",
        type=float,
        nargs=2,
        default=(-35.0, 25.0),
        metavar=("AZIMUTH", "ELEVATION"),
        help="camera angles [deg] from the -y side (default -35 25)",
    )
    args = parser.parse_args(argv)

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)
    if not (args.wheel or args.particles or args.terrain):
        parser.error("give at least one of --wheel, --particles, --terrain")
    parts, match = [], None
    if args.wheel:
        wheel, wheel_bar, match = wheel_actor(args.wheel, args.clip_y)
        renderer.AddActor(wheel)
        renderer.AddActor2D(wheel_bar)
        wheel_bar.SetPosition(0.9, 0.08)
        parts.append("wheel surface")
    if args.particles:
        particles, bar, count = particle_actor(args.particles, args.clip_y)
        renderer.AddActor(particles)
        renderer.AddActor2D(bar)
        parts.append(f"{count} particles")
    if args.terrain:
        renderer.AddActor(terrain_actor(args.terrain))
        parts.append("SCM terrain (warped by its height, coloured by sinkage)")
    caption = " + ".join(parts)
    if args.clip_y is not None:
        caption += f" (cut: y >= {args.clip_y:g} m)"
    if match:
        caption += f", step {match.group(1)}, t = {float(match.group(2)):.4f} s"
    text = vtk.vtkTextActor()
    text.SetInput(caption)
    text.GetTextProperty().SetColor(0.1, 0.1, 0.1)
    text.GetTextProperty().SetFontSize(18)
    text.SetPosition(20, args.size[1] - 40)
    renderer.AddActor2D(text)

    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(0, 0, 0)
    camera.SetPosition(0, -1, 0)
    camera.SetViewUp(0, 0, 1)
    renderer.ResetCamera()
    camera.Azimuth(args.view[0])
    camera.Elevation(args.view[1])
    renderer.ResetCamera()
    camera.Zoom(1.3)

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*args.size)
    window.AddRenderer(renderer)
    window.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(args.out)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print(f"paraview_screenshot: wrote {args.out} ({caption})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
