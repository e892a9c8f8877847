#!/usr/bin/env python3
"""Read dismech's VTK XML files back with VTK's own readers and print what
they hold as JSON, for tests/vtk_output.rs to compare with the model.

    python3 tests/vtk_read_back.py FILE.pvd|FILE.vtp|FILE.vtu ...

For a .pvd (a VTK Collection, parsed here: VTK 9.1's Python has no PVD
reader), every dataset it lists is read from the index's folder. Each
dataset gives its points, its cells (point ids and VTK cell type, in VTK's
order: for PolyData vertices, lines, polygons), every point and cell
array (components and values, tuple after tuple) and `cell_size`, the
length, area or volume VTK itself computes for each cell
(vtkCellSizeFilter). Values that are not finite are written as the strings
"inf", "-inf" and "nan" (JSON has no such numbers).

Any error VTK reports while reading (an array too short, a bad header)
makes the script exit with status 1, so that a file VTK cannot read fails
the test.
"""

import json
import math
import os
import sys
import xml.etree.ElementTree as ET

import vtk


class ErrorLog:
    """Collects the errors VTK reports, from the reader and its parser."""

    def __init__(self):
        self.messages = []
        self.window = vtk.vtkStringOutputWindow()
        vtk.vtkOutputWindow.SetInstance(self.window)

    def observe(self, obj):
        obj.AddObserver("ErrorEvent", lambda o, e: self.messages.append(f"{o.GetClassName()}: {e}"))

    def check(self, path):
        text = self.window.GetOutput()
        if self.messages or "ERR" in text or "Error" in text:
            sys.stderr.write(f"VTK reported errors reading {path}:\n{text}\n{self.messages}\n")
            sys.exit(1)


def number(x):
    if math.isfinite(x):
        return x
    if math.isnan(x):
        return "nan"
    return "inf" if x > 0 else "-inf"


def array_values(a):
    components = a.GetNumberOfComponents()
    values = []
    for t in range(a.GetNumberOfTuples()):
        for c in range(components):
            values.append(number(a.GetComponent(t, c)))
    return {"components": components, "type": a.GetDataTypeAsString(), "values": values}


def attributes(data):
    return {data.GetArrayName(k): array_values(data.GetArray(k)) for k in range(data.GetNumberOfArrays())}


def read_dataset(path, log):
    if path.endswith(".vtp"):
        reader = vtk.vtkXMLPolyDataReader()
    elif path.endswith(".vtu"):
        reader = vtk.vtkXMLUnstructuredGridReader()
    else:
        sys.exit(f"not a .vtp or .vtu file: {path}")
    log.observe(reader)
    reader.SetFileName(path)
    reader.Update()
    log.check(path)
    out = reader.GetOutput()
    points = []
    for k in range(out.GetNumberOfPoints()):
        points.extend(out.GetPoint(k))
    cells = []
    types = []
    for k in range(out.GetNumberOfCells()):
        ids = vtk.vtkIdList()
        out.GetCellPoints(k, ids)
        cells.append([ids.GetId(i) for i in range(ids.GetNumberOfIds())])
        types.append(out.GetCellType(k))
    sizes = vtk.vtkCellSizeFilter()
    sizes.SetInputData(out)
    sizes.Update()
    log.check(path)
    measured = []
    for name in ("Length", "Area", "Volume"):
        a = sizes.GetOutput().GetCellData().GetArray(name)
        if a is not None:
            measured.append([a.GetValue(k) for k in range(out.GetNumberOfCells())])
    # Each cell's own measure: the one array of the three that is not zero
    # for it (VTK computes the length of lines, the area of polygons and
    # the volume of 3D cells, and zero for the others).
    cell_size = [number(sum(m[k] for m in measured)) for k in range(out.GetNumberOfCells())]
    return {
        "type": out.GetClassName(),
        "points": points,
        "cells": cells,
        "cell_types": types,
        "cell_size": cell_size,
        "point_data": attributes(out.GetPointData()),
        "cell_data": attributes(out.GetCellData()),
    }


def read_pvd(path, log):
    root = ET.parse(path).getroot()
    if root.get("type") != "Collection":
        sys.exit(f"{path} is not a VTK Collection")
    folder = os.path.dirname(path)
    entries = []
    for d in root.iter("DataSet"):
        file = d.get("file")
        entries.append({
            "timestep": float(d.get("timestep")),
            "file": file,
            "data": read_dataset(os.path.join(folder, file), log),
        })
    return entries


def main(paths):
    log = ErrorLog()
    result = {}
    for path in paths:
        if path.endswith(".pvd"):
            result[path] = {"pvd": read_pvd(path, log)}
        else:
            result[path] = {"data": read_dataset(path, log)}
    json.dump(result, sys.stdout, allow_nan=False)


if __name__ == "__main__":
    main(sys.argv[1:])
