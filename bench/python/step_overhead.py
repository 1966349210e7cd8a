#!/usr/bin/env python3
"""Cost of stepping from Python against `tacta run` on the same scene (docs/BENCHMARKS.md).

Alternates, --repeats times: `tacta run SCENE --lockstep --duration T` (its report's wall_time_s:
the ticks alone, no process start or scene load) and a fresh tacta.Simulation stepping the same
ticks with step(N) (time.perf_counter around the call). Then the round trip of step(1) (one tick
each call) and step(0) (the binding call alone: no tick, so the GIL is not even released). Prints medians.

    PYTHONPATH=build/python python3 bench/python/step_overhead.py --tacta build/bin/tacta
"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

import tacta

ROOT = pathlib.Path(__file__).resolve().parents[2]


def cli_seconds(tacta_bin, scene, duration):
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([tacta_bin, "run", scene, "--lockstep", "--duration", str(duration), "--quiet", "--out", out,
                        "--set", "output.frames=false", "--set", "output.vtk=false", "--set", "output.plots=[]",
                        "--set", "output.trace=false"], check=True)
        return json.loads(pathlib.Path(out, "report.json").read_text())["wall_time_s"]


def python_seconds(scene, ticks):
    sim = tacta.Simulation(scene, overrides={"output.trace": False})
    start = time.perf_counter()
    sim.step(ticks)
    return time.perf_counter() - start


def round_trip_us(scene, calls, ticks_per_call):
    sim = tacta.Simulation(scene, overrides={"output.trace": False})
    sim.step(10)  # past the first ticks' warm-up
    start = time.perf_counter()
    for _ in range(calls):
        sim.step(ticks_per_call)
    return 1e6 * (time.perf_counter() - start) / calls


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tacta", default=str(ROOT / "build/bin/tacta"))
    parser.add_argument("--scene", default=str(ROOT / "scenes/liver_palpation.yaml"))
    parser.add_argument("--ticks", type=int, default=1000)
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    duration = args.ticks / 1000.0  # the liver demo runs at 1 kHz
    cli, py = [], []
    for _ in range(args.repeats):
        cli.append(cli_seconds(args.tacta, args.scene, duration))
        py.append(python_seconds(args.scene, args.ticks))
    one = [round_trip_us(args.scene, 1000, 1) for _ in range(args.repeats)]
    zero = [round_trip_us(args.scene, 100000, 0) for _ in range(args.repeats)]
    cli_ms, py_ms = 1e3 * statistics.median(cli), 1e3 * statistics.median(py)
    print(f"load {os.getloadavg()[0]:.2f}")
    print(f"tacta run --lockstep, {args.ticks} ticks: median {cli_ms:.1f} ms (min {1e3 * min(cli):.1f})")
    print(f"python step({args.ticks}): median {py_ms:.1f} ms (min {1e3 * min(py):.1f}); ratio {py_ms / cli_ms:.3f}")
    print(f"python step(1) round trip (one tick each): median {statistics.median(one):.1f} us")
    print(f"python step(0) round trip (binding call alone, no tick): median {statistics.median(zero):.2f} us")


if __name__ == "__main__":
    main()
