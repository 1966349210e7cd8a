#!/usr/bin/env python3
"""Sweep elastic models and materials on the liver demo; write a CSV and a plot.

Every (model, Young's modulus) pair runs scenes/liver_palpation.yaml (the stylus palpating the
liver) for --duration s of simulated time, lockstep, and records the peak device force, the
liver's largest displacement, its final energies, faults and the tick time from the report.

    PYTHONPATH=build/python python3 examples/python/sweep_models.py --out runs/sweep
"""
import argparse
import csv
import pathlib
import time

import tacta

ROOT = pathlib.Path(__file__).resolve().parents[2]
MODELS = ["corotational_fem", "tensor_mass", "mass_spring", "hyperelastic"]
YOUNGS_MODULI_PA = [5.0e3, 15.0e3, 30.0e3]  # liver tissue is reported between about 2 and 20 kPa
FIELDS = ["model", "youngs_modulus_Pa", "max_force_N", "max_displacement_m", "kinetic_energy_J",
          "elastic_energy_J", "faults", "tick_p50_ms", "wall_s"]


def run_one(scene, model, youngs_modulus, duration):
    sim = tacta.Simulation(str(scene), overrides={
        "bodies.*.model": model,
        "bodies.*.material.youngs_modulus": youngs_modulus,
    })
    start = time.perf_counter()
    sim.advance_to(duration)
    wall = time.perf_counter() - start
    report = sim.report()
    liver, stylus = report["bodies"][0], report["devices"][0]
    return {
        "model": model,
        "youngs_modulus_Pa": youngs_modulus,
        "max_force_N": stylus["max_force_N"],
        "max_displacement_m": liver["max_displacement_m"],
        "kinetic_energy_J": liver["kinetic_energy_J"],
        "elastic_energy_J": liver["elastic_energy_J"],
        "faults": len(report["faults"]),
        "tick_p50_ms": report["tick_ms"]["p50"],
        "wall_s": wall,
    }


def plot(rows, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    fig, (force_ax, disp_ax) = plt.subplots(1, 2, figsize=(10, 4))
    for model in dict.fromkeys(r["model"] for r in rows):
        mine = [r for r in rows if r["model"] == model]
        e = [r["youngs_modulus_Pa"] / 1e3 for r in mine]
        force_ax.plot(e, [r["max_force_N"] for r in mine], "o-", label=model)
        disp_ax.plot(e, [1000 * r["max_displacement_m"] for r in mine], "o-", label=model)
    force_ax.set_xlabel("Young's modulus (kPa)")
    force_ax.set_ylabel("peak stylus force (N)")
    disp_ax.set_xlabel("Young's modulus (kPa)")
    disp_ax.set_ylabel("largest liver displacement (mm)")
    force_ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default="runs/sweep_models", help="output folder")
    parser.add_argument("--duration", type=float, default=2.0, help="simulated s per run (the first press peaks ~1.2 s)")
    parser.add_argument("--models", nargs="+", default=MODELS)
    parser.add_argument("--moduli", nargs="+", type=float, default=YOUNGS_MODULI_PA, help="Pa")
    parser.add_argument("--scene", default=str(ROOT / "scenes/liver_palpation.yaml"))
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    rows = []
    for model in args.models:
        for youngs_modulus in args.moduli:
            row = run_one(args.scene, model, youngs_modulus, args.duration)
            rows.append(row)
            print(", ".join(f"{k} {row[k]:.4g}" if isinstance(row[k], float) else f"{k} {row[k]}" for k in FIELDS))
    with open(out / "sweep_models.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    print(f"wrote {out / 'sweep_models.csv'}")
    figure = plot(rows, out / "sweep_models.png")
    if figure:
        print(f"wrote {figure}")


if __name__ == "__main__":
    main()
