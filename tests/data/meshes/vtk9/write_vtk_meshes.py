#!/usr/bin/env python3
"""Writes the meshes of this folder with VTK's own writers (Debian's python3-vtk9):
   /usr/bin/python3 tests/data/meshes/vtk9/write_vtk_meshes.py [OUT_DIR]
The committed files were written by VTK 9.1.0 (Debian 12). tests/apps/vtk_written_meshes_test.py
runs this again where python3-vtk9 is installed and checks that Tacta reads what the installed
VTK writes as it reads the committed files."""
import os
import sys

import vtk


def sphere_strips():
    """A closed sphere (16 x 10) as triangle strips, with point normals (ignored by Tacta)."""
    s = vtk.vtkSphereSource()
    s.SetThetaResolution(16)
    s.SetPhiResolution(10)
    s.SetRadius(0.05)
    stripper = vtk.vtkStripper()
    stripper.SetInputConnection(s.GetOutputPort())
    stripper.Update()
    return stripper.GetOutput()


def cube_quads():
    """A closed cube of 6 quads (24 points: each face has its own corners), plus one line cell and
    one vertex cell that a body ignores."""
    c = vtk.vtkCubeSource()
    c.SetXLength(0.1)
    c.SetYLength(0.1)
    c.SetZLength(0.1)
    c.Update()
    pd = vtk.vtkPolyData()
    pd.DeepCopy(c.GetOutput())
    lines = vtk.vtkCellArray()
    lines.InsertNextCell(2, [0, 1])
    pd.SetLines(lines)
    verts = vtk.vtkCellArray()
    verts.InsertNextCell(1, [2])
    pd.SetVerts(verts)
    return pd


def cube_tets():
    """The unit cube in 6 tets (an UnstructuredGrid), for the volume readers."""
    points = vtk.vtkPoints()
    for z in (0, 1):
        for y in (0, 1):
            for x in (0, 1):
                points.InsertNextPoint(x, y, z)
    grid = vtk.vtkUnstructuredGrid()
    grid.SetPoints(points)
    for tet in ((0, 1, 3, 7), (0, 1, 7, 5), (0, 2, 7, 3), (0, 2, 6, 7), (0, 4, 5, 7), (0, 4, 7, 6)):
        grid.InsertNextCell(vtk.VTK_TETRA, 4, tet)
    return grid


def xml(writer_class, data, path, mode, compress=True, header64=False, encode=True):
    w = writer_class()
    w.SetInputData(data)
    w.SetFileName(path)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary,
     "appended": w.SetDataModeToAppended}[mode]()
    if not compress:
        w.SetCompressorTypeToNone()
    if header64:
        w.SetHeaderTypeToUInt64()
    w.SetEncodeAppendedData(1 if encode else 0)
    assert w.Write() == 1, path


def legacy(writer_class, data, path, binary, version=None):
    w = writer_class()
    w.SetInputData(data)
    w.SetFileName(path)
    if binary:
        w.SetFileTypeToBinary()
    if version is not None:
        w.SetFileVersion(version)
    assert w.Write() == 1, path


def main(out):
    os.makedirs(out, exist_ok=True)
    p = lambda name: os.path.join(out, name)
    sphere, cube, tets = sphere_strips(), cube_quads(), cube_tets()
    xml(vtk.vtkXMLPolyDataWriter, sphere, p("sphere_strips_default.vtp"), "appended")
    xml(vtk.vtkXMLPolyDataWriter, sphere, p("sphere_strips_raw.vtp"), "appended", encode=False)
    xml(vtk.vtkXMLPolyDataWriter, sphere, p("sphere_strips_binary64.vtp"), "binary", header64=True)
    xml(vtk.vtkXMLPolyDataWriter, sphere, p("sphere_strips_ascii.vtp"), "ascii")
    xml(vtk.vtkXMLPolyDataWriter, cube, p("cube_quads_raw_plain.vtp"), "appended", compress=False,
        encode=False)
    legacy(vtk.vtkPolyDataWriter, sphere, p("sphere_strips_ascii.vtk"), False)
    legacy(vtk.vtkPolyDataWriter, sphere, p("sphere_strips_binary.vtk"), True)
    legacy(vtk.vtkPolyDataWriter, cube, p("cube_quads_binary42.vtk"), True, version=42)
    legacy(vtk.vtkUnstructuredGridWriter, tets, p("cube_tets_binary.vtk"), True)
    xml(vtk.vtkXMLUnstructuredGridWriter, tets, p("cube_tets_raw.vtu"), "appended", encode=False)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__)))
