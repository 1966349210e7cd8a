#!/usr/bin/env python3
"""What tacta.sweep costs per run, and its speed-up on 1 and 2 local workers (docs/BENCHMARKS.md).

The same N runs of one scene (Young's modulus varied so no two are alike), timed as:
  alone      tacta.Simulation(scene, overrides).run(duration) in this process, one after the other
             (the scene load and the run: what a hand-written loop pays)
  serial     tacta.sweep(client="serial"): a child process per run, no Dask
  1 worker   tacta.sweep on a LocalCluster of 1 single-threaded worker (cluster start not counted)
  2 workers  the same on 2 workers
  2 in-worker  2 workers, isolate=False (the run in the worker process: no child process)
Overhead per run = (sweep wall - alone wall) / N. Prints a Markdown table.

    PYTHONPATH=build/python python3 bench/python/sweep_overhead.py --runs 8 --duration 1.0
"""
import argparse
import pathlib
import tempfile
import time

import tacta

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default=str(ROOT / "scenes/liver_palpation.yaml"))
    parser.add_argument("--runs", type=int, default=8)
    parser.add_argument("--duration", type=float, default=1.0, help="s of simulated time a run")
    args = parser.parse_args()
    table = [{"bodies.*.material.youngs_modulus": 10000 + 1000 * i, "output.frames": False,
              "output.vtk": False, "output.trace": False, "output.plots": []} for i in range(args.runs)]

    start = time.perf_counter()
    for p in table:
        tacta.Simulation(args.scene, overrides=p).run(duration=args.duration, realtime=False)
    timings = {"alone": time.perf_counter() - start}

    def timed(label, client, **kw):
        with tempfile.TemporaryDirectory() as folder:
            start = time.perf_counter()
            df = tacta.sweep(args.scene, table, out=pathlib.Path(folder, "runs.csv"), client=client,
                             duration=args.duration, progress=False, **kw)
            timings[label] = time.perf_counter() - start
            assert set(df["status"]) == {"ok"}, df[["status", "error"]]

    timed("serial (child process a run, no Dask)", "serial")
    for workers in (1, 2):
        start = time.perf_counter()
        client = tacta.sweep.local_client(workers)
        client.wait_for_workers(workers)
        started = time.perf_counter() - start
        timed(f"{workers} worker{'s' if workers > 1 else ''}", client)
        if workers == 2:
            timed("2 workers, isolate=False", client, isolate=False)
        cluster = client.cluster
        client.close()
        cluster.close()
        print(f"LocalCluster({workers}) start: {started:.2f} s")
    alone = timings["alone"]
    one = timings["1 worker"]
    print(f"\n{args.runs} runs of {args.duration:g} s of {pathlib.Path(args.scene).name}\n")
    print("| how | wall s | s per run | overhead per run s | speed-up vs 1 worker |")
    print("|---|---|---|---|---|")
    for label, wall in timings.items():
        print(f"| {label} | {wall:.2f} | {wall / args.runs:.3f} | {(wall - alone) / args.runs:+.3f} | "
              f"{one / wall:.2f} |")


if __name__ == "__main__":
    main()
