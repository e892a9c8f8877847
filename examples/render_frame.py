#!/usr/bin/env python3
"""Render one frame of a dismech DEM series (examples/paraview_frames.rs)
to PNG without a screen: the particles coloured by their speed |velocity|,
the walls in black, optionally the contacts as force chains.

    python3 examples/render_frame.py FOLDER [--frame N] [--out frame.png]
                                     [--size 720x640] [--chains]

FOLDER holds particles.pvd and walls.pvd (and contacts.pvd for --chains);
N counts from 0, negative from the end (default -1, the last). Needs VTK's
Python module (Debian: apt-get install python3-vtk9). VTK renders off
screen; a VTK built for X (Debian's) still wants an X server, so on a
machine without a display run it under a virtual one:
xvfb-run -a python3 examples/render_frame.py ...
"""

import argparse
import os
import sys
import xml.etree.ElementTree as ET

import vtk


def pvd_entries(path):
    """(time, file) of each dataset of a .pvd index, in order."""
    root = ET.parse(path).getroot()
    folder = os.path.dirname(path)
    return [(float(d.get("timestep")), os.path.join(folder, d.get("file"))) for d in root.iter("DataSet")]


def read(path):
    reader = vtk.vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder")
    parser.add_argument("--frame", type=int, default=-1)
    parser.add_argument("--out", default="frame.png")
    parser.add_argument("--size", default="720x640")
    parser.add_argument("--chains", action="store_true", help="draw the contacts as force chains")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))

    particles = pvd_entries(os.path.join(args.folder, "particles.pvd"))
    time, particle_file = particles[args.frame]
    index = args.frame % len(particles)
    walls = read(pvd_entries(os.path.join(args.folder, "walls.pvd"))[index][1])
    grains = read(particle_file)

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)

    # Particles: filled outlines coloured by the magnitude of the cell
    # array `velocity`.
    speed = grains.GetCellData().GetArray("velocity")
    top = max(speed.GetMaxNorm(), 1e-12)
    # Viridis (dark blue at rest, yellow fastest), from five of its colours.
    viridis = vtk.vtkColorTransferFunction()
    for x, rgb in ((0.0, (0.267, 0.005, 0.329)), (0.25, (0.229, 0.322, 0.546)),
                   (0.5, (0.128, 0.567, 0.551)), (0.75, (0.369, 0.789, 0.383)),
                   (1.0, (0.993, 0.906, 0.144))):
        viridis.AddRGBPoint(x, *rgb)
    lut = vtk.vtkLookupTable()
    lut.SetNumberOfTableValues(256)
    for k in range(256):
        lut.SetTableValue(k, *viridis.GetColor(k / 255.0), 1.0)
    lut.SetVectorModeToMagnitude()
    lut.SetRange(0.0, top)
    mapper = vtk.vtkDataSetMapper()
    mapper.SetInputData(grains)
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray("velocity")
    mapper.SetLookupTable(lut)
    mapper.SetUseLookupTableScalarRange(True)
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)

    # Their outlines, thin and dark.
    edges = vtk.vtkExtractEdges()
    edges.SetInputData(grains)
    edge_mapper = vtk.vtkPolyDataMapper()
    edge_mapper.SetInputConnection(edges.GetOutputPort())
    edge_mapper.ScalarVisibilityOff()
    edge_actor = vtk.vtkActor()
    edge_actor.SetMapper(edge_mapper)
    edge_actor.GetProperty().SetColor(0.15, 0.15, 0.15)
    edge_actor.GetProperty().SetLineWidth(0.5)
    renderer.AddActor(edge_actor)

    if args.chains:
        contacts = read(pvd_entries(os.path.join(args.folder, "contacts.pvd"))[index][1])
        chain_mapper = vtk.vtkPolyDataMapper()
        chain_mapper.SetInputData(contacts)
        chain_mapper.ScalarVisibilityOff()
        chains = vtk.vtkActor()
        chains.SetMapper(chain_mapper)
        chains.GetProperty().SetColor(0.0, 0.0, 0.0)
        chains.GetProperty().SetLineWidth(1.5)
        renderer.AddActor(chains)

    wall_mapper = vtk.vtkPolyDataMapper()
    wall_mapper.SetInputData(walls)
    wall_mapper.ScalarVisibilityOff()
    wall_actor = vtk.vtkActor()
    wall_actor.SetMapper(wall_mapper)
    wall_actor.GetProperty().SetColor(0.0, 0.0, 0.0)
    wall_actor.GetProperty().SetLineWidth(3.0)
    renderer.AddActor(wall_actor)

    bar = vtk.vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle("|v| (m/s)")
    bar.SetNumberOfLabels(5)
    bar.SetLabelFormat("%.2f")
    bar.SetWidth(0.09)
    bar.SetHeight(0.6)
    bar.SetPosition(0.88, 0.2)
    bar.UnconstrainedFontSizeOn()
    for text in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
        text.SetColor(0.0, 0.0, 0.0)
        text.SetFontSize(16)
        text.BoldOff()
        text.ItalicOff()
        text.ShadowOff()
    renderer.AddActor2D(bar)

    title = vtk.vtkTextActor()
    title.SetInput(f"t = {time:.3f} s, {grains.GetNumberOfCells()} particles")
    title.GetTextProperty().SetColor(0.0, 0.0, 0.0)
    title.GetTextProperty().SetFontSize(18)
    title.SetPosition(12, height - 30)
    renderer.AddActor2D(title)

    # A 2D view of the box and what is in it, with a margin.
    bounds = [0.0] * 6
    box = vtk.vtkAppendFilter()
    box.AddInputData(walls)
    box.AddInputData(grains)
    box.Update()
    box.GetOutput().GetBounds(bounds)
    camera = renderer.GetActiveCamera()
    camera.ParallelProjectionOn()
    aspect = 0.85 * width / height
    half_height = 0.5 * max(bounds[3] - bounds[2], (bounds[1] - bounds[0]) / aspect)
    camera.SetParallelScale(1.16 * half_height)
    # Centred on the box, moved so that the scale bar on the right and the
    # title above do not cover it.
    cx = 0.5 * (bounds[0] + bounds[1]) + 0.1 * half_height * aspect
    cy = 0.5 * (bounds[2] + bounds[3]) + 0.06 * half_height
    camera.SetFocalPoint(cx, cy, 0.0)
    camera.SetPosition(cx, cy, 10.0)
    camera.SetViewUp(0.0, 1.0, 0.0)

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.AddRenderer(renderer)
    window.SetSize(width, height)
    window.Render()
    image = vtk.vtkWindowToImageFilter()
    image.SetInput(window)
    image.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(args.out)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()
    print(f"{args.out}: frame {index} of {len(particles)}, t = {time:.3f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
