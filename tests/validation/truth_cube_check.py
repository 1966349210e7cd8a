#!/usr/bin/python3
"""Runs a Truth Cube scene and compares its probes with the measured bead positions.

Prints the RMS and largest bead error (mm) of the simulation, and of the uniform-compression
guess for scale; exits 1 when the RMS or the largest error is above its limit, 2 on a failed run.
Usage: truth_cube_check.py --tacta BIN --scene SCENE --strain 5|12.5 --out DIR
                           [--set KEY=VALUE ...] --max-rms MM --max-error MM
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

from validation_row import row as validation_row

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "data", "truth_cube", "uniaxial_positions_5_12.5.csv")
COLUMNS = {"5": 6, "12.5": 9}  # first column of the compressed positions (x1 / x2)


def measured(strain):
    out = {}
    for r in csv.reader(open(DATA)):
        if not r or r[0].startswith("#") or r[0] == "i":
            continue
        c = COLUMNS[strain]
        out[f"b{r[0]}{r[1]}{r[2]}"] = ([float(v) / 1000 for v in r[3:6]], [float(v) / 1000 for v in r[c:c + 3]])
    return out


def errors(predicted, beads):
    e = [math.dist(predicted[name], deformed) * 1000 for name, (_, deformed) in beads.items()]
    return math.sqrt(sum(x * x for x in e) / len(e)), max(e)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--tacta", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--strain", required=True, choices=sorted(COLUMNS))
    p.add_argument("--out", required=True)
    p.add_argument("--set", action="append", default=[])
    p.add_argument("--max-rms", type=float, required=True)
    p.add_argument("--max-error", type=float, required=True)
    p.add_argument("--row", help="validation row name (docs/VALIDATION.md, Rows)")
    p.add_argument("--kind", choices=["reference", "regression"], default="regression",
                   help="reference: the limits are the locking-free yardstick; regression: set "
                        "just above what the model reached")
    a = p.parse_args()
    command = [a.tacta, "run", a.scene, "--out", a.out]
    for s in a.set:
        command += ["--set", s]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        print(run.stdout, run.stderr, sep="\n")
        return 2
    report = json.load(open(os.path.join(a.out, "report.json")))
    probes = {p["name"]: p["position"] for p in report["bodies"][0]["probes"]}
    beads = measured(a.strain)
    rms, worst = errors(probes, beads)
    # The uniform-compression guess: the scene's plate travel spread linearly over the height.
    travel = {"5": 0.004, "12.5": 0.010}[a.strain]
    zs = [rest[2] for rest, _ in beads.values()]
    centre = sum(zs) / len(zs)
    bottom = centre + 0.04
    uniform = {n: [r[0], r[1], r[2] + travel * (bottom - r[2]) / 0.08] for n, (r, _) in beads.items()}
    u_rms, u_max = errors(uniform, beads)
    print(f"truth cube {a.strain} %: {' '.join(a.set) or 'scene as written'}: bead error RMS {rms:.3f} mm, "
          f"max {worst:.3f} mm (uniform compression: RMS {u_rms:.3f}, max {u_max:.3f}); "
          f"limits RMS {a.max_rms}, max {a.max_error}")
    if a.row:
        beads_ref = f"Truth Cube beads at {a.strain} % (Kerdok et al. 2003)"
        why = ("the locking-free hexahedra's RMS" if a.kind == "reference"
               else "just above what the model reached")
        validation_row(f"{a.row}.rms", beads_ref, f"RMS <= {a.max_rms} mm ({why})", f"{rms:.3f} mm",
                       rms <= a.max_rms, a.kind)
        validation_row(f"{a.row}.max", beads_ref, f"max <= {a.max_error} mm (just above what the "
                       f"model reached)", f"{worst:.3f} mm",
                       worst <= a.max_error, "regression")
    return 0 if rms <= a.max_rms and worst <= a.max_error else 1


if __name__ == "__main__":
    sys.exit(main())
