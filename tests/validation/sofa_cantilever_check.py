#!/usr/bin/python3
"""Runs SOFA's cantilever setup (scenes/validation/sofa_cantilever.yaml) with the direct solve and
with each model given, and compares the tip (probe tip_centre, y, after 100 steps of 0.01 s).

Checks: the direct solve's sag lies within [--min-fraction, --max-fraction] of the analytic static
sag (Euler-Bernoulli 0.03237 m plus Timoshenko shear 0.00038 m; linear tets lock in bending, see
docs/VALIDATION.md), and every other model's tip is within --tolerance (relative) of the direct
solve's. Exit 1 on a failed check, 2 on a failed run.
Usage: sofa_cantilever_check.py --tacta BIN --scene SCENE --out DIR [--model YAML ...]
"""
import argparse
import json
import os
import re
import subprocess
import sys

from validation_row import row as validation_row

ANALYTIC_SAG = 0.03237 + 0.00038  # m
DIRECT = "{name: corotational_fem, solver: cholesky}"


def tip_sag(tacta, scene, out, model):
    run = subprocess.run([tacta, "run", scene, "--out", out, "--set", f"bodies.0.model={model}"],
                         capture_output=True, text=True)
    if run.returncode == 2 or not os.path.exists(os.path.join(out, "report.json")):
        print(run.stdout, run.stderr, sep="\n")
        sys.exit(2)
    report = json.load(open(os.path.join(out, "report.json")))
    probe = next(p for p in report["bodies"][0]["probes"] if p["name"] == "tip_centre")
    return -probe["displacement"][1], run.returncode


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--tacta", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--model", action="append", default=[])
    p.add_argument("--tolerance", type=float, default=0.005)
    p.add_argument("--min-fraction", type=float, default=0.70)
    p.add_argument("--max-fraction", type=float, default=0.80)
    a = p.parse_args()
    ok = True
    reference, code = tip_sag(a.tacta, a.scene, os.path.join(a.out, "direct"), DIRECT)
    fraction = reference / ANALYTIC_SAG
    print(f"direct solve ({DIRECT}): tip sag {reference:.6f} m = {100 * fraction:.1f}% of the analytic static "
          f"{ANALYTIC_SAG:.5f} m (band {a.min_fraction}-{a.max_fraction})")
    passed = code == 0 and a.min_fraction <= fraction <= a.max_fraction
    validation_row("sofa_cantilever.direct_vs_analytic",
                   f"analytic static tip sag {ANALYTIC_SAG:.5f} m (Euler-Bernoulli + Timoshenko shear)",
                   f"{100 * a.min_fraction:.0f} to {100 * a.max_fraction:.0f} % of it (linear tets lock)",
                   f"{reference:.6f} m = {100 * fraction:.1f} %", passed, "regression")
    ok = ok and passed
    for i, model in enumerate(a.model):
        sag, code = tip_sag(a.tacta, a.scene, os.path.join(a.out, f"model_{i}"), model)
        off = abs(sag - reference) / reference
        print(f"{model}: tip sag {sag:.6f} m, {100 * off:.3f}% from the direct solve (limit {100 * a.tolerance}%)"
              f"{'' if code == 0 else ', the run faulted'}")
        passed = code == 0 and off <= a.tolerance
        label = re.sub(r"[^A-Za-z0-9_.+-]+", "_", re.sub(r"\w+:\s*", "", model)).strip("_")
        validation_row(f"sofa_cantilever.{label}_vs_direct", f"direct solve tip sag {reference:.6f} m",
                       f"<= {100 * a.tolerance:g} %", f"{sag:.6f} m ({100 * off:.3f} %)"
                       f"{'' if code == 0 else ', faulted'}", passed)
        ok = ok and passed
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
