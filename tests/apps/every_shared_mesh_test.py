#!/usr/bin/env python3
"""`tacta run` on every mesh of SOFA's share/mesh collection (assets/meshes, tests/data/meshes):
each either runs with the body in one piece per surface shell and nothing falling freely, or is
refused with exit 2 and a message naming the file. Usage: every_shared_mesh_test.py TACTA SRC WORK"""
import json
import pathlib
import re
import subprocess
import sys

tacta, src, work = sys.argv[1], pathlib.Path(sys.argv[2]).resolve(), pathlib.Path(sys.argv[3])
work.mkdir(parents=True, exist_ok=True)
MESHES = {  # file: expected exit code (2: refused, with the reason the message must give)
    "assets/meshes/liver.obj": 0, "assets/meshes/liver-smooth.obj": 0, "assets/meshes/liver.msh": 0,
    "assets/meshes/Bunny.stl": 0, "assets/meshes/Bunny.vtk": 0, "assets/meshes/Armadillo_Tetra_4406.vtu": 0,
    "assets/meshes/sphere.obj": 0, "assets/meshes/stylus.obj": 0, "assets/meshes/cube_low_res.msh": 0,
    "assets/meshes/msh4_cube.msh": 0, "tests/data/meshes/Armadillo_verysimplified.obj": 0,
    "tests/data/meshes/dental_instrument_light.obj": 0, "tests/data/meshes/torus.obj": 0,
    "tests/data/meshes/cylinder.msh": 0, "tests/data/meshes/SimpleBeamHexa.msh": (2, "no tetrahedra"),
}
failures = []
for name, expected in MESHES.items():
    path = src / name
    info = json.loads(subprocess.run([tacta, "mesh-info", "--json", str(path)], capture_output=True, text=True).stdout)
    if "error" in info:
        lo, hi = [0, 0, 0], [1, 1, 1]
    else:
        lo, hi = info["bounds_min_m"], info["bounds_max_m"]
    size = max(h - l for h, l in zip(hi, lo))
    scale = 0.1 / size  # every body about 10 cm across
    top = hi[1] * scale - 0.25 * (hi[1] - lo[1]) * scale  # the top quarter is held
    scene = work / (path.stem + ".yaml")
    scene.write_text(f"""name: {path.stem}
gravity: [0, -9.81, 0]
clock: {{duration_s: 0.03}}
bodies:
  - name: body
    mesh: {{file: {path}, scale: {scale!r}}}
    material: {{youngs_modulus: 1.0e5, poisson_ratio: 0.4, density: 1000, rayleigh_mass: 5}}
    model: corotational_fem
    fixed: [{{box: {{min: [-1, {top!r}, -1], max: [1, 1, 1]}}}}]
""")
    out = work / path.stem
    run = subprocess.run([tacta, "run", str(scene), "--out", str(out)], capture_output=True, text=True)
    want = expected if isinstance(expected, int) else expected[0]
    if run.returncode != want:
        failures.append(f"{name}: exit {run.returncode}, expected {want}: {run.stderr.strip()[:300]}")
        continue
    if want == 2:
        if path.name not in run.stderr or expected[1] not in run.stderr:
            failures.append(f"{name}: refused without naming the file and '{expected[1]}': {run.stderr.strip()[:300]}")
        continue
    body = json.loads((out / "report.json").read_text())["bodies"][0]
    pieces = body["mesh"].get("piece_volumes_m3")
    summary = body["mesh"]["summary"]
    print(f"{name}: {summary}; max displacement {body['max_displacement_m']:.3g} m")
    if "1 piece(s)" not in summary:
        failures.append(f"{name}: not one piece: {summary}")
    # One piece with held nodes: nothing of it can fall freely.
    held = re.search(r"body body \(corotational_fem\): \d+ nodes \((\d+) fixed\)", run.stdout)
    if not held or int(held.group(1)) == 0:
        failures.append(f"{name}: no node held: {run.stdout[:300]}")
for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
