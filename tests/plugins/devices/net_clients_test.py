#!/usr/bin/env python3
"""The net device's two shipped clients end to end, each in its own process against `tacta run`
in another: a recorded session (tacta run --record) replayed as if it were hardware by the C
example (tacta_net_replay) and by the pure-Python one (replay_session.py). Each run must take
every datagram, touch the liver, end with the client's BYE (no fault, exit 0) and report its link.
Also the Python client's passivity filter alone: its exact ledger against a random hand.

    net_clients_test.py SOURCE_DIR BUILD_DIR WORK_DIR
"""
import json
import math
import os
import random
import shutil
import subprocess
import sys
import time


def wait_for(path, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if os.path.exists(path):
            return True
        time.sleep(0.01)
    return False


def replay(source, build, work, name, client):
    out = os.path.join(work, name)
    port_file = os.path.join(work, name + ".port")
    run = subprocess.Popen([os.path.join(build, "bin", "tacta"), "run",
                            os.path.join(source, "scenes/examples/teleoperated_palpation.yaml"), "--out", out,
                            "--set", "devices.0.params.port=0", "--set", "devices.0.params.port_file=" + port_file,
                            "--set", "clock.duration_s=3.0", "--set", "output.plots=[]",
                            "--set", "devices.0.params.watchdog=2.0",  # s: a loaded CI machine stalls Python
                            "--set", "clock.haptic_priority=0"])  # an ASan tick at SCHED_FIFO starves the client
    try:
        assert wait_for(port_file, 30), "the net device wrote no port file"
        port = open(port_file).read().strip()
        replayed = subprocess.run(client + [port], capture_output=True, text=True, timeout=60)
        assert replayed.returncode == 0, replayed.stderr
        print(name + ": " + replayed.stdout.strip())
        assert run.wait(timeout=60) == 0, "tacta run failed"
    finally:
        if run.poll() is None:
            run.kill()
    report = json.load(open(os.path.join(out, "report.json")))
    device = report["devices"][0]
    link = device["link"]
    print(name + ": " + json.dumps(link))
    rows = sum(1 for _ in open(os.path.join(work, "session.csv"))) - 1
    assert link["packets_in"] >= rows, link  # loopback: every STATE (plus HELLOs and the BYE)
    assert link["dropped"] == 0 and link["watchdog_trips"] == 0, link
    assert link["byes"] == 1 and device["state"] == "finished", device
    assert device["contact_ticks"] > 100, device
    assert 0 < link["round_trip_p50_ms"] < 50, link


def check_python_filter(source):
    """Random forces on a hand that moves v dt plus up to 20 um per axis the filter cannot foresee:
    the exact work of the held forces, summed here, never goes below zero (rounding aside; it does
    without the reserve), and the filter's own ledger is that exact sum (as in the C test)."""
    sys.path.insert(0, os.path.join(source, "plugins/devices/net/clients/python"))
    from tacta_net_device import Passivity
    peak, miss = 3.3, 2e-5  # N, m
    rng, passivity, x, exact, remote = random.Random(3), Passivity(), [0.0, 0.0, 0.0], 0.0, 0.0
    for tick in range(20000):
        v = [rng.gauss(0, 0.05) for _ in range(3)]
        remote += 1e-5 * abs(rng.gauss(0, 3))
        f = passivity.filter(x, v, 1e-3, remote, [rng.gauss(0, 3) for _ in range(3)], peak)
        moved = [vi * 1e-3 + rng.uniform(-miss, miss) for vi in v]
        exact -= sum(a * b for a, b in zip(f, moved))
        x = [a + b for a, b in zip(x, moved)]
        assert exact >= -1e-12, (tick, exact)
        assert math.hypot(*f) <= peak + 1e-12, (tick, f)
    passivity.filter(x, [0.0] * 3, 1e-3, remote, [0.0] * 3, peak)  # charges the last tick
    assert abs(passivity.ledger() - exact) < 1e-12, (passivity.ledger(), exact)
    assert passivity.dissipated > 0
    print(f"python filter: exact ledger {exact:.6f} J, dissipated {passivity.dissipated:.6f} J")


def main():
    source, build, work = sys.argv[1:4]
    check_python_filter(source)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    session = os.path.join(work, "session.csv")
    subprocess.run([os.path.join(build, "bin", "tacta"), "run", os.path.join(source, "scenes/liver_palpation.yaml"),
                    "--set", "clock.duration_s=1.5", "--set", "output.frames=false", "--record", session],
                   check=True, capture_output=True, timeout=120)
    replay(source, build, work, "c_client", [os.path.join(build, "bin", "tacta_net_replay"), session, "127.0.0.1"])
    python_client = os.path.join(source, "plugins/devices/net/clients/python/replay_session.py")
    replay(source, build, work, "python_client", [sys.executable, python_client, session, "--port"])
    print("both clients replayed the session")


if __name__ == "__main__":
    main()
