# Shared fixtures of the Python API tests. ctest sets PYTHONPATH to the build's python folder and
# TACTA_BIN to the command line; run by hand: PYTHONPATH=build/python python3 -m pytest tests/python
import os
import pathlib

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
    """A soft block on a fixed base touched from above by a mouse-driven stylus (host input)."""
    return {
        "name": "python_press",
        "gravity": [0, 0, 0],
        "clock": {"mode": "lockstep", "duration_s": 5.0},
        "bodies": [{
            "name": "block",
            "mesh": {"box_grid": {"size": [0.1, 0.05, 0.1], "cells": [4, 2, 4], "origin": [-0.05, 0, -0.05]}},
            "material": {"youngs_modulus": 2.0e4, "poisson_ratio": 0.4, "density": 1000, "rayleigh_mass": 5.0},
            "model": "tensor_mass",
            "fixed": [{"box": {"min": [-1, -0.001, -1], "max": [1, 0.001, 1]}}],
        }],
        "devices": [{
            "name": "hand",
            "plugin": "mouse",
            "params": {"start_position": [0, 0.07, 0]},
            "tool": {"sphere": {"radius": 0.005}},
            "coupling": {"stiffness": 400, "damping": 1.0},
            "touches": "block",
        }],
        "collision": {"enabled": False, "broad_phase": "bvh"},
    }
