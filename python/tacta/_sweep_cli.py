"""The sweep as a command: `tacta sweep`, `tacta-sweep` or `python3 -m tacta.sweep` (docs/SWEEPS.md).

    tacta sweep SCENE --grid grid.yaml --out runs.csv [--scheduler ADDRESS] [--workers N]

grid.yaml:
    grid:                     # every combination of these values (scene keys as --set takes them,
      bodies.*.material.youngs_modulus: [5000, 15000]   # model, replay, duration)
      model: [corotational_fem, tensor_mass]
    runs:                     # and/or parameter sets listed one by one
      - {model: vbd}
    figures: [bodies.liver.max_displacement_m, tick_ms.p50]
    duration: 0.5             # s, each run (default the scene's clock.duration_s)
    timeout: 120              # s, a run killed past it (retried once)

Exit 0 when every run ended ok (or with a fault the scene reports), 1 when a run failed (error,
crashed, timeout), 2 for bad input (a grid file that cannot be read, an unknown option).
"""
import argparse
import sys


def _load_grid(path):
    import yaml

    try:
        with open(path, encoding="utf-8") as f:
            spec = yaml.safe_load(f) or {}
    except (OSError, yaml.YAMLError) as e:
        raise SystemExit(f"error: {path}: {e}") from None
    if not isinstance(spec, dict) or not set(spec) <= {"grid", "runs", "figures", "duration", "timeout"}:
        raise SystemExit(f"error: {path}: expected a map of grid, runs, figures, duration, timeout; "
                         f"found {sorted(spec) if isinstance(spec, dict) else type(spec).__name__}")
    axes = spec.get("grid") or {}
    if not isinstance(axes, dict) or any(not isinstance(v, list) for v in axes.values()):
        raise SystemExit(f"error: {path}: grid: expected a map of key: [values]")
    runs = spec.get("runs") or []
    if not isinstance(runs, list) or any(not isinstance(r, dict) for r in runs):
        raise SystemExit(f"error: {path}: runs: expected a list of maps of key: value")
    return spec, runs


def main(argv=None):
    parser = argparse.ArgumentParser(prog="tacta sweep", description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", help="scene file (every worker must be able to read it)")
    parser.add_argument("--grid", required=True, help="YAML file: grid, runs, figures, duration, timeout")
    parser.add_argument("--out", required=True, help="CSV file rows are appended to (a rerun skips its runs)")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler (default: a local cluster)")
    parser.add_argument("--workers", type=int, help="local workers (default: one per core)")
    parser.add_argument("--serial", action="store_true",
                        help="no Dask: run one after the other here (with --only, a Slurm array task)")
    parser.add_argument("--only", type=int, metavar="I",
                        help="run only parameter set I of the table (0-based, grid first, then runs)")
    parser.add_argument("--list", action="store_true", help="print the table's size and exit")
    parser.add_argument("--figure", action="append", default=[], help="report path, added to the file's")
    parser.add_argument("--duration", type=float, help="s, overrides the grid file's")
    parser.add_argument("--timeout", type=float, help="s, overrides the grid file's")
    parser.add_argument("--rerun-failed", action="store_true", help="run again the runs not ok in --out")
    parser.add_argument("--in-worker", action="store_true",
                        help="run each simulation in the worker process (no child process; no timeout)")
    args = parser.parse_args(argv)
    try:
        spec, runs = _load_grid(args.grid)
    except SystemExit as e:
        print(e, file=sys.stderr)
        return 2

    from . import sweep as sweeps

    table = (sweeps.grid(spec["grid"]) if spec.get("grid") else []) + runs
    if args.list:
        print(len(table))
        return 0
    if args.only is not None:
        if not 0 <= args.only < len(table):
            print(f"error: --only {args.only}: the table has {len(table)} parameter sets (0..{len(table) - 1})",
                  file=sys.stderr)
            return 2
        table = [table[args.only]]
    client = "serial" if args.serial else None
    if args.scheduler:
        from distributed import Client
        client = Client(args.scheduler)
    elif args.workers:
        client = sweeps.local_client(args.workers)
    try:
        frame = sweeps.sweep(args.scene, table, list(spec.get("figures") or []) + args.figure,
                             out=args.out, client=client,
                             duration=args.duration if args.duration is not None else spec.get("duration"),
                             timeout=args.timeout if args.timeout is not None else spec.get("timeout"),
                             isolate=not args.in_worker, rerun_failed=args.rerun_failed)
    except ValueError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    finally:
        if client not in (None, "serial"):
            cluster = getattr(client, "cluster", None) if not args.scheduler else None
            client.close()
            if cluster is not None:
                cluster.close()
    counts = frame["status"].value_counts().to_dict()
    print(f"tacta sweep: {len(frame)} runs, " + ", ".join(f"{n} {s}" for s, n in sorted(counts.items()))
          + f"; rows in {args.out}")
    return 0 if set(counts) <= {"ok", "fault"} else 1


if __name__ == "__main__":
    sys.exit(main())
