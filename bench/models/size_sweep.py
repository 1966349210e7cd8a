#!/usr/bin/env python3
"""Size sweep: ms per step against body size x engine threads x model (docs/BENCHMARKS.md).

Runs bench_model_step's Sweep/ cases (a clamped box of ~500 to ~50k tets, each model at its
plugin defaults, given the engine's parallel_for on a JobPool of 1, 2 and `auto` threads) with
repetitions in random interleaving, then writes into --out:

  sweep.json   Google Benchmark's own output
  sweep.csv    model, tets, nodes, threads, wall and CPU ms per step (medians), p99 of the
               stepping thread's CPU per step
  sweep.md     the same as a markdown table (one row per size, one column per model x threads),
               with the machine (lscpu model), the load average and the command
  sweep.png    tets against ms per step (log-log), one colour per model, one line style per
               thread count, the 1 ms haptic tick drawn

  python3 bench/models/size_sweep.py --out runs/size_sweep
  python3 bench/models/size_sweep.py --models corotational_fem,baseline_corotational_fem \\
      --baseline-dir /path/to/old/build/lib/tacta/plugins --sizes 2058,10368
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
from collections import defaultdict

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
NAME = re.compile(r"^Sweep/(?P<model>[^/]+)/tets:(?P<tets>\d+)/threads:(?P<threads>\d+)")


def cpu_model():
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True, check=True).stdout
        for line in out.splitlines():
            if line.startswith("Model name:"):
                return line.split(":", 1)[1].strip()
    except (OSError, subprocess.CalledProcessError):
        pass
    return "unknown"


def load_average():
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def run_bench(args, json_path):
    # Google Benchmark's regex (POSIX extended): no \d, no escapes.
    models = "|".join(args.models.split(",")) if args.models else "[^/]+"
    sizes = "|".join(args.sizes.split(",")) if args.sizes else "[0-9]+"
    command = [
        args.bench,
        f"--benchmark_filter=^Sweep/({models})/tets:({sizes})/",
        f"--benchmark_repetitions={args.repetitions}",
        f"--benchmark_min_time={args.min_time}",
        "--benchmark_enable_random_interleaving=true",
        "--benchmark_report_aggregates_only=true",
        "--benchmark_format=json",
        f"--benchmark_out={json_path}",
        "--benchmark_out_format=json",
    ]
    env = dict(os.environ)
    if args.baseline_dir:
        env["TACTA_BASELINE_PLUGIN_DIR"] = os.path.abspath(args.baseline_dir)
    print(" ".join(command), file=sys.stderr)
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)
    return command


def read_rows(json_path):
    with open(json_path) as f:
        data = json.load(f)
    rows = {}
    # The medians of the repetitions; with one repetition, the run itself.
    medians = {b["run_name"] for b in data["benchmarks"] if b.get("aggregate_name") == "median"}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") != "median" and (
            b["run_name"] in medians or b.get("run_type") != "iteration"
        ):
            continue
        m = NAME.match(b["run_name"])
        if not m:
            continue
        scale = {"ms": 1.0, "us": 1e-3, "ns": 1e-6, "s": 1e3}[b.get("time_unit", "ms")]
        key = (m["model"], int(m["tets"]), int(m["threads"]))
        rows[key] = {
            "model": m["model"],
            "tets": int(m["tets"]),
            "nodes": int(b.get("nodes", 0)),
            "threads": int(m["threads"]),
            "wall_ms": b["real_time"] * scale,
            "cpu_ms": b["cpu_time"] * scale,
            "cpu_p99_ms": b.get("cpu_p99_ms", float("nan")),
            "wall_p10_ms": b.get("wall_p10_ms", float("nan")),
            "fault": int(b.get("fault", 0)),
        }
    return data.get("context", {}), [rows[k] for k in sorted(rows)]


def write_csv(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow(r)


def write_markdown(rows, path, command, load_before, load_after):
    columns = sorted({(r["model"], r["threads"]) for r in rows})
    by_size = defaultdict(dict)
    nodes = {}
    for r in rows:
        by_size[r["tets"]][(r["model"], r["threads"])] = r
        nodes[r["tets"]] = r["nodes"]
    lines = [
        f"Machine: \"{cpu_model()}\" (`lscpu`), {os.cpu_count()} CPUs; load average "
        f"{load_before} before, {load_after} after.",
        "",
        "```",
        " ".join(command),
        "```",
        "",
        "Wall ms per step, median (CPU ms of the stepping thread in brackets); **bold**: within "
        "the 1 ms tick.",
        "",
        "| tets (nodes) | " + " | ".join(f"{m} x{t}" for m, t in columns) + " |",
        "|---" * (len(columns) + 1) + "|",
    ]
    for tets in sorted(by_size):
        cells = []
        for c in columns:
            r = by_size[tets].get(c)
            if r is None:
                cells.append("")
                continue
            text = f"{r['wall_ms']:.3g} ({r['cpu_ms']:.3g})"
            if r["wall_ms"] < 1.0:
                text = f"**{text}**"
            if r["fault"]:
                text += " fault"
            cells.append(text)
        lines.append(f"| {tets:,} ({nodes[tets]:,}) | " + " | ".join(cells) + " |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def plot(rows, path, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = ["-", "--", ":", "-."]
    markers = ["o", "s", "^", "D"]
    models = sorted({r["model"] for r in rows})
    thread_counts = sorted({r["threads"] for r in rows})
    fig, ax = plt.subplots(figsize=(8, 5.5))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for mi, model in enumerate(models):
        for ti, threads in enumerate(thread_counts):
            pts = sorted((r["tets"], r["wall_ms"]) for r in rows
                         if r["model"] == model and r["threads"] == threads)
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts],
                    linestyle=styles[ti % len(styles)], marker=markers[ti % len(markers)],
                    color=colours[mi % len(colours)], label=f"{model}, {threads} thread"
                    + ("s" if threads > 1 else ""))
    ax.axhline(1.0, color="red", linewidth=1.5, label="1 ms (the haptic tick)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("tets")
    ax.set_ylabel("ms per step (wall, median)")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--bench", default=os.path.join(ROOT, "build", "bin", "bench_model_step"))
    p.add_argument("--out", default=os.path.join(ROOT, "runs", "size_sweep"))
    p.add_argument("--models", default="", help="comma-separated labels (default: all built)")
    p.add_argument("--sizes", default="", help="comma-separated tet counts (default: all)")
    p.add_argument("--baseline-dir", default="",
                   help="plugins of an earlier build: adds the baseline_<model> cases")
    p.add_argument("--repetitions", type=int, default=3)
    p.add_argument("--min-time", default="0.1")
    p.add_argument("--from-json", default="", help="only tabulate and plot this sweep.json")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    json_path = os.path.join(args.out, "sweep.json")
    load_before = load_average()
    if args.from_json:
        json_path, command = args.from_json, ["(from", args.from_json + ")"]
    else:
        command = run_bench(args, json_path)
    load_after = load_average()
    context, rows = read_rows(json_path)
    if not rows:
        sys.exit("no Sweep/ results (is the plugin built?)")
    write_csv(rows, os.path.join(args.out, "sweep.csv"))
    write_markdown(rows, os.path.join(args.out, "sweep.md"), command, load_before, load_after)
    plot(rows, os.path.join(args.out, "sweep.png"),
         f"Step time against size: {cpu_model()}, {context.get('num_cpus', os.cpu_count())} CPUs, "
         f"load {load_before}")
    print(open(os.path.join(args.out, "sweep.md")).read())


if __name__ == "__main__":
    main()
