# Bodies added and removed while a simulation steps (Simulation.add_body / remove_body): the new
# body steps from the next tick, a removed one leaves sim.bodies and the tick, its held Body
# raises, views already taken keep the state it had, and the report keeps it.
import numpy as np
import pytest
import tacta

from conftest import beam_scene


def cube(name, y=0.5):
    return {
        "name": name,
        "mesh": {"box_grid": {"size": [0.05, 0.05, 0.05], "cells": [1, 1, 1], "origin": [1.0, y, 0]}},
        "material": {"youngs_modulus": 1.0e5, "poisson_ratio": 0.3, "density": 1000},
        "model": "corotational_fem",
    }


def test_an_added_body_falls_from_the_next_tick():
    sim = tacta.Simulation.from_dict(beam_scene())
    sim.step(10)
    dropped = sim.add_body(cube("dropped"))
    assert set(sim.bodies) == {"beam", "dropped"} and dropped.alive
    start = dropped.positions.copy()
    sim.step(200)  # 0.2 s of free fall: 0.196 m
    fall = start[:, 1].mean() - dropped.positions[:, 1].mean()
    assert fall == pytest.approx(0.5 * 9.81 * 0.2 ** 2, rel=0.02)
    assert np.allclose(dropped.positions[:, 0], start[:, 0], atol=1e-9)  # nothing pushes it sideways


def test_a_removed_body_stops_and_its_handle_raises():
    sim = tacta.Simulation.from_dict(beam_scene())
    dropped = sim.add_body(cube("dropped"))
    sim.step(50)
    held = dropped.positions  # a view taken before the removal
    sim.remove_body("dropped")
    sim.step(1)
    at_removal = held.copy()
    sim.step(100)
    assert np.array_equal(held, at_removal)  # the view still reads, and the body no longer moves
    assert "dropped" not in sim.bodies and not dropped.alive
    assert "removed" in repr(dropped)
    with pytest.raises(tacta.SceneError, match="stale body handle"):
        dropped.positions
    with pytest.raises(tacta.SceneError, match="stale body handle"):
        dropped.apply_force([0], [[0, 0, 1]])
    with pytest.raises(tacta.SceneError, match="stale body handle"):
        sim.remove_body(dropped)
    report = sim.report()
    row = next(b for b in report["bodies"] if b["name"] == "dropped")
    assert row["removed_s"] == pytest.approx(0.05, abs=1e-9)  # the start of the next tick
    assert sim.bodies["beam"].positions.shape == (36, 3)  # the other body goes on


def test_bad_additions_are_scene_errors():
    sim = tacta.Simulation.from_dict(beam_scene())
    with pytest.raises(tacta.SceneError, match="youngs_modulus"):
        sim.add_body({**cube("bad"), "material": {"youngs_modulus": -1, "poisson_ratio": 0.3, "density": 1000}})
    with pytest.raises(tacta.SceneError):
        sim.add_body(cube("beam"))  # the name is in use
    with pytest.raises(tacta.SceneError, match="unknown body .nobody."):
        sim.remove_body("nobody")
    assert set(sim.bodies) == {"beam"}  # nothing half-added
