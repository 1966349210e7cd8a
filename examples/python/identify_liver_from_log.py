#!/usr/bin/env python3
"""Young's modulus and Rayleigh damping of the liver from a recorded palpation, on tacta.sweep.

1. A palpation is recorded: the liver demo (scenes/liver_palpation.yaml) with its own material
   (E = 15 kPa, Rayleigh stiffness damping 0.01 s) run by `tacta run --record`, which writes the
   stylus's session log (the device positions, what a real device would log) and trace.csv (the
   force it rendered: the "measured" force).
2. The log is replayed (`replay: LOG`) over a grid of (E, rayleigh_stiffness) on Dask; each run's
   force trace is compared with the measured one (RMS difference, N).
3. The grid is refined around its best point (the same number of points between its two
   neighbours, each axis), --refinements times. The error surface is plotted.

    PYTHONPATH=build/python python3 examples/python/identify_liver_from_log.py --out runs/identify_liver

Writes identify_liver_from_log.csv (every run: E, damping, RMS error, status) and
identify_liver_from_log.png (the error surface of the first grid, the refined points, the truth).
"""
import argparse
import csv
import math
import os
import pathlib
import subprocess

import tacta

ROOT = pathlib.Path(__file__).resolve().parents[2]
E_KEY, DAMPING_KEY = "bodies.*.material.youngs_modulus", "bodies.*.material.rayleigh_stiffness"
TRUE_E, TRUE_DAMPING = 15000.0, 0.01  # Pa, s: the scene's own values


def force_trace(folder):
    with open(pathlib.Path(folder, "trace.csv"), newline="") as f:
        return [float(row["force_N"]) for row in csv.DictReader(f)]


def log_grid(low, high, n):
    return [low * (high / low) ** (i / (n - 1)) for i in range(n)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="runs/identify_liver")
    parser.add_argument("--duration", type=float, default=2.0, help="s of palpation (the first press)")
    parser.add_argument("--cells", type=int, default=5, help="grid points along each axis")
    parser.add_argument("--refinements", type=int, default=4)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--tacta", default=os.environ.get("TACTA_BIN", str(ROOT / "build/bin/tacta")))
    args = parser.parse_args()
    out = pathlib.Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    scene = str(ROOT / "scenes/liver_palpation.yaml")
    quiet = ["--set", "output.frames=false", "--set", "output.vtk=false", "--set", "output.plots=[]"]

    log = out / "palpation_log.csv"
    subprocess.run([args.tacta, "run", scene, "--lockstep", "--duration", str(args.duration), "--quiet",
                    "--record", str(log), "--out", str(out / "recorded")] + quiet, check=True)
    measured = force_trace(out / "recorded")

    def rms_error(report):
        run = force_trace(report["out_dir"])
        n = min(len(run), len(measured))
        return math.sqrt(sum((a - b) ** 2 for a, b in zip(run[:n], measured[:n])) / n)

    fixed = {"replay": str(log), "output.frames": False, "output.vtk": False, "output.plots": []}
    client = tacta.sweep.local_client(args.workers)
    rows = []
    try:
        es, ds = log_grid(3000, 60000, args.cells), log_grid(0.001, 0.1, args.cells)
        for level in range(args.refinements + 1):
            table = [dict(fixed, **{E_KEY: e, DAMPING_KEY: d}) for e in es for d in ds]
            df = tacta.sweep(scene, table, {"rms_force_error_N": rms_error}, client=client,
                             duration=args.duration, outputs=out / "runs", out=out / "sweep.csv",
                             progress=False)
            df["level"] = level
            rows.append(df)
            best = df.loc[df["rms_force_error_N"].idxmin()]
            print(f"level {level}: {len(df)} runs, best E = {best[E_KEY]:.0f} Pa, "
                  f"damping = {best[DAMPING_KEY]:.4g} s, RMS force error {best['rms_force_error_N']:.3g} N")
            # Refine: the same number of points between the best point's two neighbours.
            e_step, d_step = es[1] / es[0], ds[1] / ds[0]
            es = log_grid(best[E_KEY] / e_step, best[E_KEY] * e_step, args.cells)
            ds = log_grid(best[DAMPING_KEY] / d_step, best[DAMPING_KEY] * d_step, args.cells)
    finally:
        cluster = client.cluster
        client.close()
        cluster.close()

    import pandas as pd
    every = pd.concat(rows, ignore_index=True)
    table = every[["level", E_KEY, DAMPING_KEY, "rms_force_error_N", "status", "state_hash"]]
    table.columns = ["level", "youngs_modulus_Pa", "rayleigh_stiffness_s", "rms_force_error_N", "status",
                     "state_hash"]
    table.to_csv(out / "identify_liver_from_log.csv", index=False)
    best = table.loc[table["rms_force_error_N"].idxmin()]
    print(f"identified: E = {best['youngs_modulus_Pa']:.0f} Pa (true {TRUE_E:.0f}), rayleigh_stiffness = "
          f"{best['rayleigh_stiffness_s']:.4g} s (true {TRUE_DAMPING:g}); {len(table)} runs")
    plot(table, out / "identify_liver_from_log.png")


def plot(table, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not installed: no plot")
        return
    first = table[table["level"] == 0]
    es = sorted(set(first["youngs_modulus_Pa"]))
    ds = sorted(set(first["rayleigh_stiffness_s"]))
    grid = first.pivot(index="rayleigh_stiffness_s", columns="youngs_modulus_Pa", values="rms_force_error_N")
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    mesh = ax.pcolormesh(es, ds, grid.values, shading="nearest", cmap="viridis",
                         norm=matplotlib.colors.LogNorm())
    fig.colorbar(mesh, ax=ax, label="RMS force error (N)")
    later = table[table["level"] > 0]
    ax.scatter(later["youngs_modulus_Pa"], later["rayleigh_stiffness_s"], s=8, c="white", label="refined")
    ax.scatter([TRUE_E], [TRUE_DAMPING], marker="+", s=120, c="red", label="recorded with")
    best = table.loc[table["rms_force_error_N"].idxmin()]
    ax.scatter([best["youngs_modulus_Pa"]], [best["rayleigh_stiffness_s"]], marker="x", s=80, c="orange",
               label="identified")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("Young's modulus (Pa)")
    ax.set_ylabel("Rayleigh stiffness damping (s)")
    ax.set_title("Liver palpation replayed: force error over the grid")
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
