#!/usr/bin/env python3
"""Tets and ms per step of surface files made bodies at several tet budgets (max_tets), through
the engine (tacta run, lockstep), for the default budget's figures in docs/SCENES.md.

Each surface is scaled to 10 cm, its top quarter held, soft (E 10 kPa, nu 0.4, as the size sweep
of bench_model_step) and sagging under gravity for --duration s with corotational_fem at its
defaults. Budgets are interleaved per surface so that each sees the same minutes of machine load.
Prints one markdown row per surface and budget: tets, nodes, voxel (m), thin-part voxel (m), and
the model stage of the ticks (report.json tick_breakdown_ms.models, wall ms, p50 and p99) and
the whole tick (tick_ms p50). Usage:
  python3 bench/models/surface_budget.py --tacta build/bin/tacta --budgets 1000,1500,2000,3000 \\
      assets/meshes/Bunny.stl tests/data/meshes/Armadillo_verysimplified.obj
"""
import argparse
import json
import os
import pathlib
import subprocess
import tempfile

SCENE = """name: surface_budget
gravity: [0, -9.81, 0]
clock: {{mode: lockstep, haptic_rate_hz: 1000, render_rate_hz: 60, duration_s: {duration}}}
bodies:
  - name: body
    mesh: {{file: {path}, scale: {scale!r}, max_tets: {budget}}}
    material: {{youngs_modulus: 1.0e4, poisson_ratio: 0.4, density: 1000, rayleigh_mass: 0.1, rayleigh_stiffness: 0.01}}
    model: {model}
    fixed: [{{box: {{min: [-1, {top!r}, -1], max: [1, 1, 1]}}}}]
"""


def bounds(tacta, path):
    info = json.loads(subprocess.run([tacta, "mesh-info", "--json", path], capture_output=True,
                                     text=True, check=True).stdout)
    return info["bounds_min_m"], info["bounds_max_m"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tacta", default="build/bin/tacta")
    parser.add_argument("--budgets", default="1000,1500,2000,3000")
    parser.add_argument("--model", default="corotational_fem")
    parser.add_argument("--duration", type=float, default=1.0)
    parser.add_argument("surfaces", nargs="+")
    args = parser.parse_args()
    print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print("| surface | max_tets | tets (nodes) | voxel / thin parts (m) | models p50 / p99 (ms) | tick p50 (ms) |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        for surface in args.surfaces:
            lo, hi = bounds(args.tacta, surface)
            scale = 0.1 / max(h - l for h, l in zip(hi, lo))
            top = hi[1] * scale - 0.25 * (hi[1] - lo[1]) * scale
            for budget in args.budgets.split(","):
                scene = pathlib.Path(work) / "scene.yaml"
                scene.write_text(SCENE.format(duration=args.duration, path=os.path.abspath(surface),
                                              scale=scale, budget=budget, model=args.model,
                                              top=top))
                out = pathlib.Path(work) / "out"
                subprocess.run([args.tacta, "run", str(scene), "--out", str(out)], check=True,
                               stdout=subprocess.DEVNULL)
                report = json.loads((out / "report.json").read_text())
                body, stage = report["bodies"][0], report["tick_breakdown_ms"]["models"]
                mesh = body["mesh"]
                summary = mesh["summary"]
                tets = summary.split(" tets")[0].split(", ")[-1]
                nodes = summary.split(" nodes")[0].split(", ")[-1]
                print(f"| {pathlib.Path(surface).name} | {budget} | {tets} ({nodes}) | "
                      f"{mesh['voxel_size_m']:.3g} / {mesh['thin_part_size_m']:.3g} | "
                      f"{stage['p50']:.3f} / {stage['p99']:.3f} | {report['tick_ms']['p50']:.3f} |",
                      flush=True)


if __name__ == "__main__":
    main()
