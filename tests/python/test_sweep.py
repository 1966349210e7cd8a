# tacta.sweep on a LocalCluster of 2 single-threaded workers: rows against runs made alone, a
# plugin that segfaults (in the run's process and in the worker itself), a run that hangs, a
# resumed sweep and the command. The crash plugin (plugins/crash_model.cpp) comes from ctest.
import csv
import os
import subprocess
import sys

import pytest
import tacta

distributed = pytest.importorskip("distributed")
pytest.importorskip("pandas")
CRASH_DIR = os.environ.get("TACTA_TEST_CRASH_PLUGIN_DIR")
DURATION = 0.05  # s of simulated time a run: 50 ticks of the beam


@pytest.fixture(scope="module")
def client():
    # Workers inherit the environment they start with: the crash plugin's folder goes in first.
    if CRASH_DIR:
        os.environ["TACTA_PLUGIN_PATH"] = CRASH_DIR
    c = tacta.sweep.local_client(2)
    yield c
    cluster = c.cluster
    c.close()
    cluster.close()


@pytest.fixture
def beam(root):
    return str(root / "scenes/examples/beam_under_gravity.yaml")


def lines(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_rows_are_the_runs_made_alone(client, beam, tmp_path):
    table = tacta.sweep.grid({"bodies.*.material.youngs_modulus": [2e5, 8e5],
                              "model": ["corotational_fem", "tensor_mass"]})
    table.append({"bodies.*.material.youngs_modulus": -1.0})  # refused by the scene loader
    out = tmp_path / "runs.csv"
    df = tacta.sweep(beam, table, ["bodies.beam.max_displacement_m", "tick_ms.p50"],
                     out=out, client=client, duration=DURATION)
    assert len(df) == 5 and list(df["status"]) == ["ok"] * 4 + ["error"]
    for row, params in zip(df.itertuples(index=False), table[:4]):
        alone = tacta.Simulation(beam, overrides=tacta.sweep.overrides_of(params)).run(duration=DURATION, realtime=False)
        assert row.state_hash == alone["state_hash"]
        assert row[3] == alone["bodies"][0]["max_displacement_m"]  # the figure column
    assert len(set(df["state_hash"][:4])) == 4  # four different runs, not one repeated
    bad = df.iloc[4]
    assert "youngs_modulus" in bad["error"] and bad["attempt"] == 1  # input errors are not retried
    assert len(lines(out)) == 5 and {r["worker"] for r in lines(out)}  # appended as they came


@pytest.mark.skipif(not CRASH_DIR, reason="TACTA_TEST_CRASH_PLUGIN_DIR not set (ctest sets it)")
@pytest.mark.parametrize("isolate", [True, False], ids=["run_process", "worker_process"])
def test_a_segfaulting_plugin_is_a_failed_row_retried_once(client, beam, tmp_path, isolate):
    crash = {"model": {"name": "test_crash", "fault": "segfault", "after_steps": 5}}
    table = [{"model": "corotational_fem"}, crash, {"model": "tensor_mass"}]
    out = tmp_path / "runs.csv"
    df = tacta.sweep(beam, table, out=out, client=client, duration=DURATION, isolate=isolate)
    assert list(df["status"]) == ["ok", "crashed", "ok"]
    reason = df["error"][1]
    assert ("SIGSEGV" in reason) if isolate else ("worker lost" in reason)
    assert df["attempt"][1] == 2
    tries = [r for r in lines(out) if r["run"] == df["run"][1]]
    assert [(r["attempt"], r["status"]) for r in tries] == [("1", "crashed"), ("2", "crashed")]


@pytest.mark.skipif(not CRASH_DIR, reason="TACTA_TEST_CRASH_PLUGIN_DIR not set (ctest sets it)")
def test_a_run_past_its_timeout_is_killed_and_retried_once(client, beam, tmp_path):
    hang = {"model": {"name": "test_crash", "fault": "hang", "after_steps": 5}}
    df = tacta.sweep(beam, [hang], out=tmp_path / "runs.csv", client=client, duration=DURATION,
                     timeout=4.0, progress=False)
    assert df["status"][0] == "timeout" and df["attempt"][0] == 2
    assert "4 s" in df["error"][0]


def test_a_rerun_skips_the_rows_the_file_has(client, beam, tmp_path):
    out = tmp_path / "runs.csv"
    first = tacta.sweep(beam, {"bodies.*.material.youngs_modulus": [2e5, 4e5]}, out=out, client=client,
                        duration=DURATION)
    more = tacta.sweep(beam, {"bodies.*.material.youngs_modulus": [2e5, 4e5, 6e5]}, out=out, client=client,
                       duration=DURATION)
    assert len(lines(out)) == 3  # only the new run was appended
    assert list(more["status"]) == ["ok"] * 3
    assert list(more["state_hash"][:2]) == list(first["state_hash"])
    assert list(more["worker"][:2]) == list(first["worker"])  # the rows of the first sweep, as they were


def test_the_command_runs_the_grid_file_on_a_scheduler(client, beam, tmp_path, tacta_bin):
    grid = tmp_path / "grid.yaml"
    grid.write_text("grid:\n  bodies.*.material.youngs_modulus: [2.0e+5, 4.0e+5]\n"
                    "figures: [bodies.beam.max_displacement_m]\nduration: 0.05\n")
    out = tmp_path / "runs.csv"
    address = client.scheduler.address
    done = subprocess.run([sys.executable, "-m", "tacta.sweep", beam, "--grid", str(grid), "--out", str(out),
                           "--scheduler", address], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "2 runs, 2 ok" in done.stdout
    # The C++ command line forwards `tacta sweep` to the same module: a rerun finds both rows.
    again = subprocess.run([str(tacta_bin), "sweep", beam, "--grid", str(grid), "--out", str(out),
                            "--scheduler", address], capture_output=True, text=True, timeout=300,
                           env=dict(os.environ, TACTA_PYTHON=sys.executable))
    assert again.returncode == 0, again.stderr
    assert "2 runs, 2 ok" in again.stdout and len(lines(out)) == 2
    grid.write_text("grid: [1, 2]\n")
    bad = subprocess.run([sys.executable, "-m", "tacta.sweep", beam, "--grid", str(grid), "--out", str(out)],
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and "grid: expected a map" in bad.stderr
