#!/usr/bin/python3
"""Models that agree (issue 11): runs `tacta compare SCENE --reference REF` and checks each
model's displacement over the reference's against its band in docs/VALIDATION.md (0.75 to 1.25,
or the measured band of a model that cannot agree, with the reason written there).

--measure max: the compare table's max displacement ratio; probe: the probe node's displacement at
the end over the reference's. Every run must end without a fault. Exit 1 on a failed check, 2 on
a failed run.
Usage: model_agreement_check.py --tacta BIN --scene SCENE --out DIR --reference MODEL
       --expect MODEL=LOW:HIGH ... [--measure max|probe] [--compare-arg ARG ...]
"""
import argparse
import json
import os
import subprocess
import sys

from validation_row import row as validation_row


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--tacta", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--reference", required=True)
    p.add_argument("--expect", action="append", default=[], help="MODEL=LOW:HIGH")
    p.add_argument("--measure", choices=["max", "probe"], default="max")
    p.add_argument("--compare-arg", action="append", default=[], help="passed to tacta compare")
    a = p.parse_args()
    bands = {}
    for item in a.expect:
        model, band = item.rsplit("=", 1)
        low, high = (float(v) for v in band.split(":"))
        bands[model] = (low, high)
    models = [a.reference] + list(bands)
    command = [a.tacta, "compare", a.scene, "--models", ",".join(models), "--reference",
               a.reference, "--out", a.out] + a.compare_arg
    run = subprocess.run(command, capture_output=True, text=True)
    table = os.path.join(a.out, "compare.json")
    if run.returncode == 2 or not os.path.exists(table):
        print(" ".join(command), run.stdout, run.stderr, sep="\n")
        return 2
    rows = {row["model"]: row for row in json.load(open(table))["models"]}
    key = "max_displacement_m" if a.measure == "max" else "probe_displacement_m"
    failed = False
    scene = os.path.splitext(os.path.basename(a.scene))[0]
    reference = rows[a.reference][key]
    for model, (low, high) in bands.items():
        row = rows[model]
        ratio = row[key] / reference
        ok = low <= ratio <= high and not row["faults"]
        failed |= not ok
        print(f"{model:48s} {a.measure} displacement ratio {ratio:.3f} (band {low} to {high}), "
              f"faults {row['faults']}: {'ok' if ok else 'FAILED'}")
        # 0.75 to 1.25 is issue 11's agreement target against the FEM; any other band is the
        # measured ratio of a model that cannot agree, kept as a regression guard.
        agrees = (low, high) == (0.75, 1.25)
        validation_row(f"models_agree.{scene}.{model.replace('=', '-')}",
                       f"{a.reference} {a.measure} displacement {1000 * reference:.2f} mm",
                       f"ratio {low} to {high}" + ("" if agrees else " (measured +-10 %)"),
                       f"ratio {ratio:.3f}" + (f", faults {row['faults']}" if row["faults"] else ""),
                       ok, "reference" if agrees else "regression")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
