"""One run of a sweep, as a worker executes it: plain values in, plain values out.

`run_task(job)` is what the Dask worker calls. By default it runs the simulation in a child
process (`python -m tacta._sweep_task JOB RESULT`), so a plugin that segfaults or a run that
hangs takes down only that child: the worker stays up and answers with a failed row (status
`crashed` with the signal, or `timeout`), which the driver retries once. pybind11 objects do not
pickle, so the Simulation is built here, inside the worker, from the scene path or dict.
"""
import json
import os
import pathlib
import signal
import subprocess
import sys
import tempfile
import time

# Parameter keys that are not scene keys: the model of every body, a device log to replay (as
# `tacta run --replay`), and the run's length.
MODEL_KEY, REPLAY_KEY, DURATION_KEY = "model", "replay", "duration"


def overrides_of(params):
    """The scene overrides (`--set` pairs) that one parameter set stands for."""
    out = {}
    for key, value in params.items():
        if key == MODEL_KEY:
            out["bodies.*.model"] = value
        elif key == REPLAY_KEY:
            # The scene's devices replay the log, keeping their tool and coupling.
            out["devices.*.plugin"] = "replay"
            out["devices.*.params"] = {"log": str(value)}
        elif key != DURATION_KEY:
            out[key] = value
    return out


def figure(report, path):
    """report['a']['b'] for 'a.b'; a list is indexed by position or by its items' `name`."""
    value = report
    for part in path.split("."):
        if isinstance(value, dict) and part in value:
            value = value[part]
        elif isinstance(value, list):
            named = [item for item in value if isinstance(item, dict) and item.get("name") == part]
            if named:
                value = named[0]
            elif part.lstrip("-").isdigit() and -len(value) <= int(part) < len(value):
                value = value[int(part)]
            else:
                raise KeyError(f"report has no '{path}': no item named or numbered '{part}'")
        else:
            known = ", ".join(sorted(value)) if isinstance(value, dict) else type(value).__name__
            raise KeyError(f"report has no '{path}' ('{part}' not among: {known})")
    return value


def simulate(job):
    """Builds the simulation and runs it; returns the report dict (raises what tacta raises)."""
    import tacta  # in the worker or the child, never pickled

    overrides = overrides_of(job["params"])
    if isinstance(job["scene"], dict):
        sim = tacta.Simulation.from_dict(job["scene"], base_dir=job["base_dir"], overrides=overrides)
    else:
        sim = tacta.Simulation(job["scene"], overrides=overrides)
    duration = job["params"].get(DURATION_KEY, job.get("duration"))
    report = sim.run(duration=None if duration is None else float(duration), realtime=False,
                     out_dir=job.get("out_dir") or "")
    report["out_dir"] = job.get("out_dir") or ""  # where figure functions find trace.csv etc.
    return report


def _in_child(job, timeout):
    """(report, None) or (None, (status, error)) from a child process running simulate(job)."""
    with tempfile.TemporaryDirectory(prefix="tacta-sweep-") as folder:
        job_file, result_file = pathlib.Path(folder, "job.json"), pathlib.Path(folder, "result.json")
        job_file.write_text(json.dumps({k: job.get(k) for k in ("scene", "base_dir", "params", "duration", "out_dir")}))
        env = dict(os.environ)
        package_parent = str(pathlib.Path(__file__).resolve().parents[1])
        env["PYTHONPATH"] = os.pathsep.join(p for p in (package_parent, env.get("PYTHONPATH")) if p)
        child = subprocess.Popen([sys.executable, "-m", "tacta._sweep_task", str(job_file), str(result_file)],
                                 stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                 stderr=subprocess.PIPE, env=env, start_new_session=True)
        try:
            _, err = child.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(child.pid, signal.SIGKILL)
            child.communicate()
            return None, ("timeout", f"timeout: no result after {timeout:g} s (run killed)")
        tail = err.decode(errors="replace").strip().splitlines()[-3:]
        if child.returncode < 0:
            name = signal.Signals(-child.returncode).name
            return None, ("crashed", f"crashed: the run died of {name}" +
                          (f" ({' | '.join(tail)})" if tail else ""))
        if not result_file.exists():
            return None, ("crashed", f"crashed: exit code {child.returncode}, no result" +
                          (f" ({' | '.join(tail)})" if tail else ""))
        result = json.loads(result_file.read_text())
    if "error" in result:
        return None, ("error", result["error"])
    return result["report"], None


def run_task(job):
    """The row of one run: {run, attempt, figures..., state_hash, status, error, wall_s, worker}."""
    start = time.perf_counter()
    row = {"run": job["run"], "attempt": job["attempt"]}
    row.update({name: None for name in job["figures"]})
    row.update(state_hash=None, faults=None, status="ok", error="")
    try:
        if job["isolate"]:
            report, failure = _in_child(job, job["timeout"])
        else:
            report, failure = simulate(job), None
    except Exception as e:  # a bad scene or override in-process: the run's own error
        report, failure = None, ("error", f"{type(e).__name__}: {e}")
    if failure:
        row["status"], row["error"] = failure
    else:
        row["state_hash"] = report.get("state_hash")
        faults = report.get("faults") or []
        row["faults"] = len(faults)
        if faults:
            row["status"], row["error"] = "fault", json.dumps(faults[0])
        errors = []
        for name, source in job["figures"].items():
            try:
                row[name] = source(report) if callable(source) else figure(report, source)
            except Exception as e:
                errors.append(f"figure '{name}': {e}")
        if errors:
            row["status"], row["error"] = "error", "; ".join(errors)
    row["wall_s"] = round(time.perf_counter() - start, 4)
    row["worker"] = os.uname().nodename + ":" + str(os.getpid())
    return row


def _child_main(job_file, result_file):
    job = json.loads(pathlib.Path(job_file).read_text())
    try:
        result = {"report": simulate(job)}
    except Exception as e:
        result = {"error": f"{type(e).__name__}: {e}"}
    pathlib.Path(result_file).write_text(json.dumps(result, default=str))


if __name__ == "__main__":
    _child_main(*sys.argv[1:3])
