# Bodies and devices are named by generation-checked handles (tacta.BodyHandle / DeviceHandle):
# sim.body(x) / sim.device(x) take a name, a handle or a Body / Device; a removed body's handle
# and one from another simulation raise tacta.SceneError; handles and Bodies compare and hash.
import pytest
import tacta

from conftest import beam_scene


def test_a_body_is_found_by_name_handle_or_body():
    sim = tacta.Simulation.from_dict(beam_scene())
    beam = sim.body("beam")
    handle = beam.handle
    assert isinstance(handle, tacta.BodyHandle) and handle.index == beam.index == 0
    assert sim.body(handle) == beam == sim.bodies["beam"] and sim.body(beam) == beam
    assert {handle: "x"}[sim.bodies["beam"].handle] == "x" and len({beam, sim.body("beam")}) == 1
    assert repr(handle) == f"BodyHandle(index=0, generation={handle.generation})"
    with pytest.raises(tacta.SceneError, match="did you mean 'beam'"):
        sim.body("bem")
    with pytest.raises(TypeError):
        sim.body(0)  # integers do not name bodies


def test_a_removed_or_foreign_handle_raises():
    sim, other = (tacta.Simulation.from_dict(beam_scene()) for _ in range(2))
    theirs = other.body("beam").handle
    assert theirs.index == sim.body("beam").handle.index and theirs != sim.body("beam").handle
    with pytest.raises(tacta.SceneError, match="from another simulation"):
        sim.body(theirs)
    handle = sim.body("beam").handle
    sim.remove_body(handle)
    with pytest.raises(tacta.SceneError, match="stale body handle"):
        sim.body(handle)
    with pytest.raises(tacta.SceneError, match="was removed"):
        sim.body("beam")


def test_a_device_is_found_by_name_or_handle(root):
    sim = tacta.Simulation(str(root / "scenes/liver_palpation.yaml"))
    stylus = sim.device("stylus")
    assert isinstance(stylus.handle, tacta.DeviceHandle) and stylus.index == 0
    assert sim.device(stylus.handle) == stylus == sim.devices["stylus"]
    with pytest.raises(tacta.SceneError, match="did you mean 'stylus'"):
        sim.device("stylu")
