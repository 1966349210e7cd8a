# A device's tool changed from Python between steps: the proxy takes the new radius at the next
# tick (on a rigid block's top face, y = 0.05 m, it rests one radius above), report.json counts
# the change, and bad requests raise tacta.SceneError.
import pytest
import tacta

from conftest import pressed_block_scene

TOP = 0.05  # m, the block's top face


def rigid_block():
    """hand_press with every node of the block fixed, so its top face stays at y = 0.05 m."""
    return {
        "name": "rigid_press",
        "gravity": [0, 0, 0],
        "clock": {"mode": "lockstep", "duration_s": 5.0},
        "bodies": [{
            "name": "block",
            "mesh": {"box_grid": {"size": [0.1, 0.05, 0.1], "cells": [2, 1, 2],
                                  "origin": [-0.05, 0, -0.05]}},
            "material": {"youngs_modulus": 2.0e4, "poisson_ratio": 0.4, "density": 1000},
            "model": "corotational_fem",
            "fixed": [{"box": {"min": [-1, -1, -1], "max": [1, 1, 1]}}],
        }],
        "devices": [{
            "name": "hand", "plugin": "mouse",
            "params": {"start_position": [0.005, 0.07, 0.005]},
            "tool": {"sphere": {"radius": 0.005}},
            "coupling": {"stiffness": 400, "damping": 1.0},
            "touches": "block",
        }],
        "collision": {"enabled": False, "broad_phase": "bvh"},
    }


def test_change_tool_moves_the_proxy_by_the_radius_change():
    sim = tacta.Simulation.from_dict(rigid_block())
    hand = sim.devices["hand"]
    hand.input([0.005, 0.04, 0.005])  # the hand pulls the stylus 10 mm into the block
    sim.step(600)
    assert hand.in_contact
    assert hand.proxy[1] - TOP == pytest.approx(0.005, abs=3e-4)
    hand.change_tool({"sphere": {"radius": 0.008}})
    with pytest.raises(tacta.SceneError, match="still waiting"):
        hand.change_tool("{sphere: {radius: 0.001}}")
    sim.step(600)
    assert hand.in_contact
    assert hand.proxy[1] - TOP == pytest.approx(0.008, abs=3e-4)
    assert sim.report()["devices"][0]["tool_changes"] == 1


def test_bad_tool_is_a_scene_error():
    sim = tacta.Simulation(pressed_block_scene())
    with pytest.raises(tacta.SceneError):
        sim.devices["hand"].change_tool({"cube": {"size": 1}})
    with pytest.raises(tacta.SceneError):
        sim.devices["hand"].change_tool({"sphere": {"radius": -0.001}})
