#!/usr/bin/python3
"""Writes scenes/validation/truth_cube_<strain>.yaml from the Truth Cube bead data.

The setup of OpenSurgSim's comparison (docs/REFERENCES.md): an 80 mm cube, E 15.3 kPa,
nu 0.499, rho 980 kg/m^3, no gravity, bottom face held, top face moved down by 4 mm (5 %) or
10 mm (12.5 %), static equilibrium. Coordinates are the data's (metres here), +z down; the cube
is centred on the centroid of the beads at rest. One probe per bead at its rest position.
Usage: scripts/validation/truth_cube_scenes.py  (from the repository root)
"""
import csv
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data", "truth_cube", "uniaxial_positions_5_12.5.csv")
EDGE = 0.08  # m
STRAINS = {"5": 0.004, "12.5": 0.010}  # compression label (%) -> top plate travel, m


def beads():
    rows = [r for r in csv.reader(open(DATA)) if r and not r[0].startswith("#") and r[0] != "i"]
    return [(f"b{r[0]}{r[1]}{r[2]}", [float(v) / 1000.0 for v in r[3:6]]) for r in rows]


def scene(label, travel, rest):
    centre = [sum(p[a] for _, p in rest) / len(rest) for a in range(3)]
    lo = [c - EDGE / 2 for c in centre]
    top, bottom = lo[2], lo[2] + EDGE  # +z is down: the top face has the smallest z
    tol = 1e-6
    lines = [
        f"# The Truth Cube at {label} % compression (Kerdok et al. 2003; tests/data/truth_cube).",
        "# Made by scripts/validation/truth_cube_scenes.py; checked by tests/validation.",
        "# Static equilibrium by implicit steps of 1 s (inertia negligible: each is a Newton step",
        "# of the statics); the top face moves with a stuck plate over the first 5 s.",
        f"name: truth_cube_{label}",
        "gravity: [0, 0, 0]",
        "clock: {mode: lockstep, duration_s: 12}",
        "output: {trace: false, record_interval_s: 1.0}",
        "bodies:",
        "  - name: cube",
        f"    mesh: {{box_grid: {{size: [{EDGE}, {EDGE}, {EDGE}], cells: [8, 8, 8], "
        f"origin: [{lo[0]:.6f}, {lo[1]:.6f}, {lo[2]:.6f}]}}}}",
        "    material: {youngs_modulus: 15.3e3, poisson_ratio: 0.499, density: 980}",
        "    model: {name: corotational_fem, solver: cholesky}",
        "    step_rate_hz: 1",
        f"    fixed: [{{box: {{min: [-1, -1, {bottom - tol:.6f}], max: [1, 1, 1]}}}}]",
        "    prescribed:",
        f"      - region: {{box: {{min: [-1, -1, -1], max: [1, 1, {top + tol:.6f}]}}}}",
        f"        displacement: {{ramp: {{to: [0, 0, {travel}], duration_s: 5}}}}",
        "    probes:",
    ]
    lines += [f"      - {{name: {name}, position: [{p[0]:.5f}, {p[1]:.5f}, {p[2]:.5f}]}}" for name, p in rest]
    return "\n".join(lines) + "\n"


def main():
    rest = beads()
    out_dir = os.path.join(ROOT, "scenes", "validation")
    os.makedirs(out_dir, exist_ok=True)
    for label, travel in STRAINS.items():
        with open(os.path.join(out_dir, f"truth_cube_{label}.yaml"), "w") as f:
            f.write(scene(label, travel, rest))


if __name__ == "__main__":
    main()
