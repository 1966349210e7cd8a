#!/usr/bin/env python3
"""Replays a recorded device session (a device log CSV from `tacta run SCENE --record log.csv`)
to a Tacta simulation's `net` device as if it were hardware, with the pure-Python client.

    replay_session.py LOG.csv [--host 127.0.0.1] [--port 18950]
"""
import argparse
import csv
import math
import sys
import time

from tacta_net_device import Capabilities, NetDevice

COLUMNS = ["time_s", "px", "py", "pz", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "buttons", "fx", "fy", "fz"]


def read_log(path):
    with open(path, newline="") as f:
        reader = csv.reader(f)
        if next(reader, None) != COLUMNS:
            sys.exit(f"{path}:1: expected the header {','.join(COLUMNS)}")
        rows = []
        for line, row in enumerate(reader, start=2):
            try:
                rows.append([float(x) for x in row])
            except ValueError:
                sys.exit(f"{path}:{line}: expected {len(COLUMNS)} numbers")
            if len(row) != len(COLUMNS):
                sys.exit(f"{path}:{line}: expected {len(COLUMNS)} numbers, found {len(row)}")
        return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("log")
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=18950)
    args = parser.parse_args()
    rows = read_log(args.log)
    caps = Capabilities()
    dev = NetDevice(args.host, args.port, caps)
    start, first, last, peak = time.monotonic(), rows[0][0], rows[0][0], 0.0
    for row in rows:
        delay = start + (row[0] - first) - time.monotonic()
        if delay > 0:
            time.sleep(delay)
        velocity = row[8:11]
        dev.send_state(row[1:4], velocity, row[4:8], int(row[11]))
        dev.poll()
        force = dev.passivity.filter(row[1:4], velocity, row[0] - last, dev.remote_budget(), dev.force(),
                                      caps.peak_force)
        last = row[0]
        peak = max(peak, math.sqrt(sum(x * x for x in force)))
    dev.close()
    print(f"states sent {len(rows)}, forces received {dev.received}, dropped {dev.dropped}, "
          f"malformed {dev.malformed}, peak force {peak:.3f} N, last round trip {dev.round_trip_s * 1e3:.3f} ms, "
          f"ledger {dev.passivity.ledger():.6f} J")


if __name__ == "__main__":
    main()
