#!/usr/bin/env python3
"""Identify a beam's Young's modulus from a measured tip deflection.

The "measurement" is SOFA's cantilever validation reference (docs/REFERENCES.md): a
0.02 x 0.02 x 0.2 m beam, rho 1100 kg/m^3, nu 0.45, clamped at z = 0 and sagging under gravity,
with a static tip deflection of 0.03237 m (Euler-Bernoulli) + 0.00038 m (shear) = 0.03275 m for
E = 2 MPa. We search the E for which Tacta's static corotational FEM sags by that much: SciPy's
brentq when SciPy is there, else bisection on log E. The fit is plotted (PNG) when matplotlib is
there, and always written as CSV. Linear tetrahedra are too stiff in bending on a coarse grid
(locking, worse at nu = 0.45), so the E identified is below 2 MPa and rises toward it as the grid is refined.

    PYTHONPATH=build/python python3 examples/python/identify_youngs_modulus.py --out runs/identify
"""
import argparse
import csv
import math
import pathlib

import tacta

MEASURED_TIP_DEFLECTION_M = 0.03237 + 0.00038  # SOFA cantilever reference, E = 2e6 Pa
TRUE_E_PA = 2.0e6


def beam(youngs_modulus, cells_along):
    # SOFA's grid is 4 x 4 x 29 cells; a coarser run keeps that aspect (at least one cell across).
    across = max(1, round(cells_along * 4 / 29))
    return {
        "name": "identify_beam",
        "gravity": [0, -9.81, 0],
        "clock": {"mode": "lockstep", "haptic_rate_hz": 100, "render_rate_hz": 10, "duration_s": 0.05},
        "bodies": [{
            "name": "beam",
            "mesh": {"beam_grid": {"size": [0.02, 0.02, 0.2], "cells": [across, across, cells_along], "origin": [0, 0, 0]}},
            "material": {"youngs_modulus": youngs_modulus, "poisson_ratio": 0.45, "density": 1100},
            "model": {"name": "corotational_fem", "solve": "static"},
            "fixed": [{"box": {"min": [-1, -1, -0.001], "max": [1, 1, 0.001]}}],
        }],
    }


def tip_deflection(youngs_modulus, cells_along):
    """Static tip sag (m) of the beam: the mean drop of the nodes at z = L."""
    sim = tacta.Simulation.from_dict(beam(youngs_modulus, cells_along))
    sim.step(2)  # a static solve every tick: the second confirms the first
    body = sim.bodies["beam"]
    tip = body.rest_positions[:, 2] > 0.2 - 1e-6
    return float((body.rest_positions[tip, 1] - body.positions[tip, 1]).mean())


def solve(residual, low, high, tolerance):
    """The root of residual(log E) in [low, high]: SciPy's brentq, or bisection without SciPy."""
    try:
        from scipy.optimize import brentq
        return brentq(residual, low, high, xtol=tolerance), "scipy.optimize.brentq"
    except ImportError:
        f_low = residual(low)
        while high - low > tolerance:
            mid = 0.5 * (low + high)
            f_mid = residual(mid)
            if (f_mid > 0) == (f_low > 0):
                low, f_low = mid, f_mid
            else:
                high = mid
        return 0.5 * (low + high), "bisection"


def write_fit(out, trials, identified, cells_along):
    curve = sorted(trials.items())
    with open(out / "identify_youngs_modulus.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["youngs_modulus_Pa", "tip_deflection_m"])
        writer.writerows(curve)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return out / "identify_youngs_modulus.csv"
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogx([e for e, _ in curve], [1000 * d for _, d in curve], "o-", label=f"Tacta, {cells_along} cells")
    ax.axhline(1000 * MEASURED_TIP_DEFLECTION_M, color="k", ls="--", label="measured (SOFA reference)")
    ax.axvline(identified, color="C3", ls=":", label=f"identified E = {identified / 1e6:.3f} MPa")
    ax.set_xlabel("Young's modulus (Pa)")
    ax.set_ylabel("static tip deflection (mm)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "identify_youngs_modulus.png", dpi=100)
    return out / "identify_youngs_modulus.png"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default="runs/identify_youngs_modulus", help="output folder")
    parser.add_argument("--cells", type=int, default=29, help="cells along the beam (SOFA's 29 by default; 5 for a quick run)")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    trials = {}

    def residual(log_e):
        e = math.exp(log_e)
        trials[e] = tip_deflection(e, args.cells)
        return trials[e] - MEASURED_TIP_DEFLECTION_M

    log_e, method = solve(residual, math.log(2e5), math.log(2e7), tolerance=1e-4)
    identified = math.exp(log_e)
    for e in (5e5, 1e6, 4e6, 8e6):  # a few more points for the plot
        trials.setdefault(e, tip_deflection(e, args.cells))
    written = write_fit(out, trials, identified, args.cells)
    print(f"identified E = {identified:.6g} Pa with {method} ({len(trials)} simulations); "
          f"the reference beam has E = {TRUE_E_PA:.3g} Pa (ratio {identified / TRUE_E_PA:.3f})")
    print(f"wrote {written}")


if __name__ == "__main__":
    main()
