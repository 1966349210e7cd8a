"""Writes fuzz_restore's seed: the payload (the checkpoint less its 52-byte header) of
fuzz/restore_scene.yaml after 25 ticks, a separation at x = 0.04 and 5 more ticks, as
fuzz/restore.cpp's fixture makes the header. Run from the repository root with the Python module
built: PYTHONPATH=build/python python3 fuzz/make_restore_seed.py"""
import pathlib

import numpy as np
import tacta

HEADER_BYTES = 52  # magic 8, version 4, ABI id 8, fingerprint 8, tick 8, checksum 8, length 8

sim = tacta.Simulation("fuzz/restore_scene.yaml")
sim.step(25)
p0, p1, p2, p3 = [0.04, -1, -1], [0.04, 1, -1], [0.04, 1, 1], [0.04, -1, 1]
sim.cut("beam", np.array([[p0, p1, p2], [p0, p2, p3]], dtype=float))
sim.step(5)
out = pathlib.Path("fuzz/corpus/restore/cut_beam.bin")
out.parent.mkdir(parents=True, exist_ok=True)
out.write_bytes(sim.checkpoint()[HEADER_BYTES:])
print(f"wrote {out}")
