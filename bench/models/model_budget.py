#!/usr/bin/env python3
"""Largest box a model steps within the 1 ms tick, through the engine (tacta run, lockstep).

Runs scenes/bench/model_budget_box.yaml for each model, thread count and cube size (1 cm cells,
n x n x n, 6 n^3 tets), interleaved so that every model sees the same minutes of machine load,
and prints the median (p50) and p99 of the model stage of the ticks (report.json
tick_breakdown_ms.models, ms of wall time per tick). Usage:
  python3 bench/models/model_budget.py --tacta build/bin/tacta \
      --models 'vbd;corotational_fem;{name: vbd, iterations: 3}' --threads 1,2 --cells 4,6,8,12
(--models is split on ';': a model may be a YAML map of its name and parameters).
"""
import argparse
import json
import pathlib
import subprocess
import tempfile


def run(tacta, scene, model, threads, cells, out):
    size = cells * 0.01
    subprocess.run(
        [tacta, "run", scene, "--out", str(out), "--set", f"threads={threads}",
         "--set", f"bodies.0.model={model}",
         "--set", f"bodies.0.mesh.box_grid.cells=[{cells},{cells},{cells}]",
         "--set", f"bodies.0.mesh.box_grid.size=[{size},{size},{size}]"],
        check=True, stdout=subprocess.DEVNULL)
    report = json.loads((out / "report.json").read_text())
    stage = report["tick_breakdown_ms"]["models"]
    faulted = any(b.get("faults") for b in report["bodies"])
    return stage["p50"], stage["p99"], faulted


def main():
    here = pathlib.Path(__file__).resolve().parents[2]
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tacta", default=str(here / "build/bin/tacta"))
    parser.add_argument("--scene", default=str(here / "scenes/bench/model_budget_box.yaml"))
    parser.add_argument("--models", default="vbd;corotational_fem")
    parser.add_argument("--threads", default="1,2")
    parser.add_argument("--cells", default="4,5,6,7,8,10,12")
    args = parser.parse_args()
    print("| tets | nodes | model | threads | model stage p50 (ms) | p99 (ms) |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        for cells in (int(c) for c in args.cells.split(",")):
            for threads in args.threads.split(","):
                for model in args.models.split(";"):
                    out = pathlib.Path(work) / "".join(
                        c if c.isalnum() else "_" for c in f"{model}_{threads}_{cells}")
                    p50, p99, faulted = run(args.tacta, args.scene, model, threads, cells, out)
                    print(f"| {6 * cells ** 3:,} | {(cells + 1) ** 3:,} | {model} | {threads} | "
                          f"{p50:.3f} | {p99:.3f}{' (fault)' if faulted else ''} |", flush=True)


if __name__ == "__main__":
    main()
