# Shared fixtures of the Python API tests. ctest sets PYTHONPATH to the build's python folder and
# TACTA_BIN to the command line; run by hand: PYTHONPATH=build/python python3 -m pytest tests/python
import os
import pathlib
import struct
import zlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def tacta_bin():
    path = pathlib.Path(os.environ.get("TACTA_BIN", ROOT / "build" / "bin" / "tacta"))
    if not path.exists():
        pytest.fail(f"the tacta command line is not built at {path} (set TACTA_BIN)")
    return path


def beam_scene(model="corotational_fem", youngs_modulus=5.0e5, duration=1.0):
    """The cantilever of scenes/examples/beam_under_gravity.yaml, as a dict."""
    return {
        "name": "python_beam",
        "gravity": [0, -9.81, 0],
        "clock": {"mode": "lockstep", "duration_s": duration},
        "bodies": [{
            "name": "beam",
            "mesh": {"beam_grid": {"size": [0.4, 0.05, 0.05], "cells": [8, 1, 1], "origin": [0, 0, 0]}},
            "material": {"youngs_modulus": youngs_modulus, "poisson_ratio": 0.45, "density": 1100,
                         "rayleigh_mass": 0.5},
            "model": model,
            "fixed": [{"box": {"min": [-0.001, -1, -1], "max": [0.001, 1, 1]}}],
        }],
    }


def pressed_block_scene():
    """scenes/examples/hand_press.yaml: a soft block touched from above by a mouse-driven stylus."""
    return str(ROOT / "scenes/examples/hand_press.yaml")


def read_png_rgb(path):
    """(width, height, rows of RGB bytes) of an 8-bit RGB or RGBA PNG, decoded with zlib alone."""
    data = pathlib.Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    at, idat = 8, b""
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        chunk = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", chunk[:10])
            assert depth == 8 and colour in (2, 6), (depth, colour)
        elif kind == b"IDAT":
            idat += chunk
        at += 12 + length
    channels = 3 if colour == 2 else 4
    stride = width * channels
    raw, rows, previous = zlib.decompress(idat), [], bytearray(stride)
    for y in range(height):
        filter_type, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):  # undo the row filter (PNG spec section 9)
            left = line[i - channels] if i >= channels else 0
            up, corner = previous[i], previous[i - channels] if i >= channels else 0
            if filter_type == 1:
                line[i] = (line[i] + left) & 255
            elif filter_type == 2:
                line[i] = (line[i] + up) & 255
            elif filter_type == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif filter_type == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        rows.append(bytes(line[j] for j in range(stride) if j % channels < 3))
        previous = line
    return width, height, rows
