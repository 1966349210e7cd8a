"""tacta.sweep: one scene over a table of parameter sets, on Dask (docs/SWEEPS.md).

    import tacta.sweep
    table = tacta.sweep.grid({"bodies.*.material.youngs_modulus": [5e3, 15e3],
                              "model": ["corotational_fem", "tensor_mass"]})
    df = tacta.sweep.sweep("scenes/liver_palpation.yaml", table, duration=0.5,
                           figures=["bodies.liver.max_displacement_m", "tick_ms.p50"],
                           out="runs/sweep.csv")

Each parameter set is a dict of scene keys as `--set` takes them, plus `model` (every body's
model), `replay` (a device log the scene's devices replay) and `duration` (s). One row per run:
the parameters, the figures asked for, state_hash, faults, status (ok, fault, error, crashed,
timeout), error, attempt, wall_s, worker. Rows are appended to `out` (CSV) as they arrive; a
rerun with the same `out` skips the runs the file has. As a command:
`python3 -m tacta.sweep SCENE --grid grid.yaml --out runs.csv [--scheduler ADDRESS]`.
"""
import csv
import hashlib
import itertools
import json
import os
import pathlib
import sys
import types

from ._sweep_task import overrides_of, run_task  # noqa: F401  (overrides_of: part of the API)

RETRIED = ("crashed", "timeout")  # failures of the machine, not of the parameters: tried again
FIXED_COLUMNS = ["state_hash", "faults", "status", "error", "attempt", "wall_s", "worker"]


def grid(axes):
    """Every combination of {key: [values]}, as a list of parameter dicts (the first key slowest)."""
    keys = list(axes)
    return [dict(zip(keys, values)) for values in itertools.product(*(axes[k] for k in keys))]


def _plain(value):
    """NumPy and pandas scalars as Python ones, so a parameter set travels as JSON."""
    if hasattr(value, "item") and callable(value.item):
        return value.item()
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    return value


def _table(params):
    if hasattr(params, "to_dict") and hasattr(params, "columns"):  # a pandas DataFrame
        params = params.to_dict(orient="records")
    elif isinstance(params, dict):
        params = grid(params)
    rows = [{str(k): _plain(v) for k, v in dict(p).items()} for p in params]
    if not rows:
        raise ValueError("tacta.sweep: the parameter table is empty")
    return rows


def run_id(scene, params):
    """A stable name for one run: the scene and its parameter set, hashed (12 hex digits)."""
    text = json.dumps([scene if isinstance(scene, dict) else str(scene), params], sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:12]


def _cell(value):
    return json.dumps(value) if isinstance(value, (list, dict)) else value


def _read_done(out, columns):
    """{run: last row} of an earlier sweep's file; refuses a file with other columns."""
    path = pathlib.Path(out)
    if not path.exists() or path.stat().st_size == 0:
        return {}
    with path.open(newline="") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames != columns:
            raise ValueError(f"{out}: its columns {reader.fieldnames} are not this sweep's {columns}; "
                             "give another output file")
        return {row["run"]: row for row in reader}


def _progress(total):
    try:
        from tqdm import tqdm
        return tqdm(total=total, unit="run", desc="tacta.sweep", file=sys.stderr)
    except ImportError:
        return _TextProgress(total)


class _TextProgress:
    def __init__(self, total):
        self.total, self.n = total, 0

    def update(self, n=1):
        self.n += n
        print(f"\rtacta.sweep: {self.n}/{self.total} runs", end="", file=sys.stderr, flush=True)

    def set_postfix_str(self, text):
        pass

    def close(self):
        print(file=sys.stderr)


def local_client(workers=None):
    """A LocalCluster of one single-threaded worker process per core (or `workers`) and its client.
    A worker lost to a crash fails its task at once (allowed-failures 0): the sweep retries it."""
    import logging

    import dask
    from distributed import Client, LocalCluster

    with dask.config.set({"distributed.scheduler.allowed-failures": 0}):
        cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                               processes=True, dashboard_address=":0", silence_logs=logging.ERROR)
        return Client(cluster)


def sweep(scene, params, figures=(), *, out=None, client=None, duration=None, timeout=None,
          retries=1, isolate=True, base_dir=".", rerun_failed=False, progress=True, outputs=None):
    """Runs `scene` once per parameter set on Dask and returns one row per run (a DataFrame).

    scene: a scene file (a path every worker can read) or a scene dict (`base_dir` for its meshes).
    params: a list of dicts, a DataFrame, or {key: [values]} for their grid (see grid()).
    figures: report paths such as 'bodies.liver.max_displacement_m' or 'tick_ms.p50' (a list item
        by its name or index), or {column: path or function(report) -> value}.
    out: CSV file the rows are appended to as they arrive (each attempt is a line; the DataFrame has
        the last per run); also written as Parquet beside it at the end when pyarrow is present.
    client: any dask.distributed Client; None starts local_client() for this call; "serial" runs
        them one after the other in this process, without Dask.
    timeout: s a run may take before its process is killed (needs isolate).
    retries: how often a crashed or timed-out run is tried again (default once).
    isolate: run each simulation in its own process under the worker (a segfault costs that
        process, not the worker); False runs it in the worker process itself.
    rerun_failed: with an existing `out`, run again the runs whose last status is not ok.
    outputs: a folder; each run writes its outputs (report.json, trace.csv, plots...) into
        outputs/<run>, and report["out_dir"] names it for figure functions.
    """
    if timeout is not None and not isolate:
        raise ValueError("tacta.sweep: timeout needs isolate=True (a run in the worker cannot be killed)")
    if not isinstance(scene, dict):
        scene = str(pathlib.Path(scene).resolve())
    table = _table(params)
    for p in table:
        if "replay" in p:
            p["replay"] = str(pathlib.Path(p["replay"]).resolve())
    figures = {f: f for f in figures} if not isinstance(figures, dict) else dict(figures)
    keys = list(dict.fromkeys(k for p in table for k in p))
    columns = ["run"] + keys + [f for f in figures if f not in keys] + FIXED_COLUMNS
    ids = [run_id(scene, p) for p in table]
    done = _read_done(out, columns) if out else {}
    todo = [i for i, run in enumerate(ids)
            if run not in done or (rerun_failed and done[run]["status"] != "ok")]

    def job(i, attempt):
        return {"run": ids[i], "attempt": attempt, "scene": scene, "base_dir": str(base_dir),
                "params": table[i], "figures": figures, "duration": duration,
                "timeout": timeout, "isolate": isolate,
                "out_dir": str(pathlib.Path(outputs, ids[i]).resolve()) if outputs else None}

    own = client is None and bool(todo)
    if own:
        client = local_client()
    rows = {}
    try:
        with _Appender(out if todo else None, columns) as append:
            _drive(client, todo, job, retries, progress, lambda i, row: (
                row.update({k: table[i].get(k) for k in keys}), append(row),
                rows.__setitem__(ids[i], row)))
    finally:
        if own:
            cluster = client.cluster
            client.close()
            cluster.close()
    frame = _frame(out, ids, rows, columns)
    if out:
        _write_parquet(frame, out)
    return frame


def _drive(client, todo, job, retries, progress, take):
    """Runs every run, hands each row to take(i, row) as it arrives, retries machine failures.

    A run whose process died or timed out is submitted again at once. A run whose worker was lost
    (in-worker runs, a node gone) is tried again after the others, one at a time, so that a run
    that kills its worker takes no other run with it a second time."""
    bar = _progress(len(todo)) if progress and todo else None

    def finish(i, attempt, row):  # the next attempt to make, or None
        take(i, row)
        if row["status"] in RETRIED and attempt <= retries:
            return attempt + 1
        if bar:
            bar.update(1)
        return None

    def result(future, i, attempt):
        try:
            return future.result()
        except Exception as e:  # the worker was lost (KilledWorker), or the task failed in Dask
            return {"run": job(i, attempt)["run"], "attempt": attempt, "status": "crashed",
                    "error": f"worker lost: {type(e).__name__}: {e}"}

    def one(i, attempt):
        if client == "serial":  # no Dask: in this process (a Slurm array task)
            return run_task(job(i, attempt))
        return result(client.submit(run_task, job(i, attempt), pure=False), i, attempt)

    later = [(i, 1) for i in todo] if client == "serial" else []
    try:
        if client != "serial":
            from distributed import as_completed

            pending, index = as_completed(), {}

            def submit(i, attempt):
                future = client.submit(run_task, job(i, attempt), pure=False)
                index[future.key] = (i, attempt)
                pending.add(future)

            for i in todo:
                submit(i, 1)
            for future in pending:
                i, attempt = index.pop(future.key)
                row = result(future, i, attempt)
                again = finish(i, attempt, row)
                if again and row["error"].startswith("worker lost"):
                    later.append((i, again))
                elif again:
                    submit(i, again)
        while later:
            i, attempt = later.pop(0)
            again = finish(i, attempt, one(i, attempt))
            if again:
                later.insert(0, (i, again))
    finally:
        if bar:
            bar.close()


class _Appender:
    """Appends rows to the CSV file (header first when new), flushed row by row."""

    def __init__(self, out, columns):
        self.out, self.columns, self.file = out, columns, None

    def __enter__(self):
        if self.out:
            path = pathlib.Path(self.out)
            path.parent.mkdir(parents=True, exist_ok=True)
            fresh = not path.exists() or path.stat().st_size == 0
            self.file = path.open("a", newline="")
            self.writer = csv.DictWriter(self.file, fieldnames=self.columns)
            if fresh:
                self.writer.writeheader()
        return self

    def __call__(self, row):
        if self.file:
            self.writer.writerow({c: _cell(row.get(c)) for c in self.columns})
            self.file.flush()

    def __exit__(self, *exc):
        if self.file:
            self.file.close()


def _frame(out, ids, rows, columns):
    """One row per run of this table, in its order: the file's last line per run (earlier sweeps'
    rows included), or the rows of this call without a file."""
    import pandas as pd

    if out and pathlib.Path(out).exists():
        text = {c: str for c in ("run", "state_hash", "status", "error", "worker")}
        every = pd.read_csv(out, dtype=text, keep_default_na=False, na_values=[""], float_precision="round_trip")
        last = every.drop_duplicates("run", keep="last").set_index("run")
        return last.reindex(ids).reset_index()[columns]
    return pd.DataFrame([{c: _cell(rows[r].get(c)) for c in columns} for r in ids], columns=columns)


def _write_parquet(frame, out):
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        return
    frame.to_parquet(pathlib.Path(out).with_suffix(".parquet"), index=False)


class _CallableModule(types.ModuleType):
    """tacta.sweep(...) calls sweep(); tacta.sweep.grid, .local_client etc. stay reachable."""

    def __call__(self, *args, **kwargs):
        return sweep(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule

def main(argv=None):
    """The command (tacta-sweep, python3 -m tacta.sweep, tacta sweep): see tacta/_sweep_cli.py."""
    from ._sweep_cli import main as command
    return command(argv)


if __name__ == "__main__":
    sys.exit(main())
