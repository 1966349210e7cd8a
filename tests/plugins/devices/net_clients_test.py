#!/usr/bin/env python3
"""The net device's two shipped clients end to end, each in its own process against `tacta run`
in another: a recorded session (tacta run --record) replayed as if it were hardware by the C
example (tacta_net_replay) and by the pure-Python one (replay_session.py). Each run must take
every datagram, touch the liver, end with the client's BYE (no fault, exit 0) and report its link.

    net_clients_test.py SOURCE_DIR BUILD_DIR WORK_DIR
"""
import json
import os
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
                            "--set", "devices.0.params.watchdog=0.5"])  # s: a loaded CI machine stalls Python
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


def main():
    source, build, work = sys.argv[1:4]
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
