# Body state as NumPy views onto the engine's arrays: no copy, valid across steps and model
# swaps, read-only where writing would break an invariant, writes the model is told about.
import gc

import numpy as np
import pytest
import tacta

from conftest import beam_scene


def test_views_share_the_engine_memory():
    sim = tacta.Simulation.from_dict(beam_scene())
    beam = sim.bodies["beam"]
    first, second = beam.positions, beam.positions
    assert first.shape == (36, 3) and first.dtype == np.float64
    assert np.shares_memory(first, second)  # both point into the engine's array
    before = first.copy()
    sim.step(50)
    assert not np.array_equal(first, before)  # the same view sees the new state
    assert np.array_equal(first, sim.bodies["beam"].positions)


def test_invariants_are_read_only():
    beam = tacta.Simulation.from_dict(beam_scene()).bodies["beam"]
    for name in ("rest_positions", "fixed", "masses", "elements", "surface"):
        array = getattr(beam, name)
        assert not array.flags.writeable, name
        with pytest.raises(ValueError):
            array[0] = 0
    assert beam.fixed.dtype == np.bool_ and beam.fixed.sum() == 4
    assert beam.masses.sum() == pytest.approx(1100 * 0.4 * 0.05 * 0.05)
    assert beam.positions.flags.writeable and beam.velocities.flags.writeable


def test_views_keep_the_simulation_alive():
    positions = tacta.Simulation.from_dict(beam_scene()).bodies["beam"].positions
    gc.collect()
    assert positions[35, 0] == pytest.approx(0.4)  # still the engine's memory, not freed


def fnv1a_hex(array):
    """The report's state_hash (FNV-1a 64 over the positions' bytes) computed from a view."""
    h = 1469598103934665603
    for byte in np.ascontiguousarray(array).tobytes():
        h = ((h ^ byte) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"


def test_views_stay_valid_across_a_model_swap():
    sim = tacta.Simulation.from_dict(beam_scene())
    beam = sim.bodies["beam"]
    positions, velocities = beam.positions, beam.velocities  # held across the swap
    sim.step(100)
    beam.swap_model("tensor_mass")
    assert beam.model == "tensor_mass"
    before = positions.copy()
    sim.step(100)
    assert not np.array_equal(positions, before)  # the held view moves with the new model's steps
    assert np.shares_memory(positions, beam.positions) and np.shares_memory(velocities, beam.velocities)
    report = sim.report()
    assert report["bodies"][0]["model"] == "tensor_mass"
    # What the held view shows is the engine's state: the report hashes the same bytes.
    assert fnv1a_hex(positions) == report["state_hash"]


def test_swap_model_checks_its_parameters():
    beam = tacta.Simulation.from_dict(beam_scene()).bodies["beam"]
    with pytest.raises(tacta.SceneError, match="no parameter 'stifness'"):
        beam.swap_model("corotational_fem", stifness=3)
    with pytest.raises(tacta.SceneError, match="did you mean"):
        beam.swap_model("tensor_mas")
    beam.swap_model("corotational_fem", tolerance=1e-7)
    assert beam.params["tolerance"] == pytest.approx(1e-7)


def test_set_param_live_or_by_swap():
    sim = tacta.Simulation.from_dict(beam_scene())
    beam = sim.bodies["beam"]
    live = beam.set_param("tolerance", 1e-6)
    assert live  # corotational_fem lists tolerance as live: changed in place, no swap
    models = {p["name"]: p for p in tacta.plugins()["loaded"] if p["kind"] == "model"}
    assert "tolerance" in models["corotational_fem"]["live_params"]
    assert not beam.set_param("restart_factor", 4)  # not live: a swap to the same model
    assert beam.params["tolerance"] == pytest.approx(1e-6)
    sim.step(5)
    with pytest.raises(tacta.SceneError):
        beam.set_param("no_such_parameter", 1.0)


def test_written_state_is_what_the_next_step_starts_from():
    sim = tacta.Simulation.from_dict(beam_scene(), overrides={"gravity": [0, 0, 0]})
    beam = sim.bodies["beam"]
    beam.positions[:, 1] += 0.01  # a rigid lift of every node: no strain
    beam.state_written()
    sim.step(1)
    free = ~beam.fixed
    assert np.allclose(beam.positions[free, 1], beam.rest_positions[free, 1] + 0.01, atol=1e-3)
    beam.velocities = np.zeros((36, 3))  # the setter copies in and tells the model
    with pytest.raises(ValueError, match=r"shape \(36, 3\)"):
        beam.positions = np.zeros((3, 3))


def test_applied_forces_act_until_cleared():
    sim = tacta.Simulation.from_dict(beam_scene(), overrides={"gravity": [0, 0, 0]})
    beam = sim.bodies["beam"]
    tip = np.flatnonzero(beam.rest_positions[:, 0] > 0.399)  # the 4 nodes of the free end
    beam.apply_force(tip.tolist(), np.tile([0.0, 0.0, 0.5], (len(tip), 1)))
    sim.step(200)
    assert beam.positions[35, 2] - beam.rest_positions[35, 2] > 1e-4  # pushed along +z
    beam.clear_forces()
    with pytest.raises(tacta.SceneError, match="past the body"):
        beam.apply_force([99], [[0, 0, 1]])
    assert beam.faults == []


def test_last_status_says_what_the_last_step_raised():
    sim = tacta.Simulation.from_dict(beam_scene())
    beam = sim.bodies["beam"]
    sim.step(10)
    assert sim.last_status["error"] is False
    beam.positions[35, 0] = float("nan")  # the free tip
    beam.state_written()
    sim.step(5)
    assert sim.last_status["error"] is True and sim.last_status["model_bits"] != 0
    assert len(beam.faults) == 1
    sim.step(5)
    assert sim.last_status["error"] is False  # frozen: nothing more is raised
