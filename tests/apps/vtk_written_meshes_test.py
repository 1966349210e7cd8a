#!/usr/bin/env python3
"""Meshes written by the installed VTK (python3-vtk9) read by `tacta mesh-info` as the committed
ones of tests/data/meshes/vtk9 are, and as VTK itself measures them (triangle count after
vtkTriangleFilter, enclosed volume by vtkMassProperties). Skipped (exit 77) without python3-vtk9.
Usage: vtk_written_meshes_test.py TACTA_BINARY SOURCE_DIR WORK_DIR"""
import importlib.util
import json
import os
import subprocess
import sys

try:
    import vtk
except ImportError:
    print("skipped: python3-vtk9 is not installed")
    sys.exit(77)

tacta, src, work = sys.argv[1:4]
committed = os.path.join(src, "tests/data/meshes/vtk9")
spec = importlib.util.spec_from_file_location("write_vtk_meshes", os.path.join(committed, "write_vtk_meshes.py"))
writer = importlib.util.module_from_spec(spec)
spec.loader.exec_module(writer)
os.makedirs(work, exist_ok=True)
writer.main(work)
print("VTK", vtk.vtkVersion.GetVTKVersion())


def info(path):
    out = subprocess.run([tacta, "mesh-info", "--json", path], capture_output=True, text=True)
    if out.returncode != 0:
        raise SystemExit(f"FAIL: tacta mesh-info {path} exited {out.returncode}: {out.stderr}")
    return json.loads(out.stdout)


def vtk_measure(path):
    reader = vtk.vtkXMLPolyDataReader() if path.endswith(".vtp") else vtk.vtkPolyDataReader()
    reader.SetFileName(path)
    clean = vtk.vtkCleanPolyData()  # welds the cube's per-face corners, as Tacta does
    clean.SetInputConnection(reader.GetOutputPort())
    tri = vtk.vtkTriangleFilter()
    tri.SetInputConnection(clean.GetOutputPort())
    tri.PassVertsOff()
    tri.PassLinesOff()
    mass = vtk.vtkMassProperties()
    mass.SetInputConnection(tri.GetOutputPort())
    mass.Update()
    return tri.GetOutput().GetNumberOfPolys(), mass.GetVolume()


failures = 0
for name in sorted(os.listdir(work)):
    fresh, old = info(os.path.join(work, name)), info(os.path.join(committed, name))
    keys = ["kind", "vertices", "nodes", "tets", "triangles", "closed"]
    for key in keys:
        if fresh.get(key) != old.get(key):
            print(f"FAIL {name}: {key} {fresh.get(key)} (installed VTK) != {old.get(key)} (committed)")
            failures += 1
    if fresh["kind"] == "surface":
        triangles, volume = vtk_measure(os.path.join(work, name))
        if fresh["triangles"] != triangles or abs(fresh["enclosed_volume_m3"] - volume) > 1e-6 * volume:
            print(f"FAIL {name}: {fresh['triangles']} triangles, {fresh['enclosed_volume_m3']} m^3; "
                  f"VTK: {triangles}, {volume} m^3")
            failures += 1
    print(f"{name}: {fresh['kind']}, {fresh.get('triangles')} triangles, {fresh.get('tets', '-')} tets")
sys.exit(1 if failures else 0)
