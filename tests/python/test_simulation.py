# The Simulation surface: loading (file, dict, overrides), stepping, the clock, report and outputs.
import json

import pytest
import tacta

from conftest import beam_scene


def test_file_scene_steps_on_its_clock(root):
    sim = tacta.Simulation(str(root / "scenes/examples/beam_under_gravity.yaml"))
    assert sim.dt == pytest.approx(1e-3)
    assert (sim.tick, sim.time) == (0, 0.0)
    assert sim.step() == 1
    assert sim.step(9) == 9
    assert sim.tick == 10 and sim.time == pytest.approx(0.010)
    assert sim.advance_to(0.05) == 40
    assert sim.tick == 50 and sim.time == pytest.approx(0.05)
    assert sim.advance_to(0.02) == 0  # never backwards


def test_overrides_dict_reaches_the_scene(root):
    sim = tacta.Simulation(str(root / "scenes/examples/beam_under_gravity.yaml"),
                           overrides={"bodies.*.model": "tensor_mass", "bodies.*.material.youngs_modulus": 1.0e6})
    assert sim.bodies["beam"].model == "tensor_mass"
    sim.step(5)
    assert sim.report()["bodies"][0]["model"] == "tensor_mass"


def test_from_dict_builds_the_scene_and_gravity_acts():
    sim = tacta.Simulation.from_dict(beam_scene())
    beam = sim.bodies["beam"]
    assert beam.node_count == 36 and beam.elements.shape[1] == 4
    sim.step(200)
    tip_drop = beam.rest_positions[35, 1] - beam.positions[35, 1]
    assert tip_drop > 1e-4  # the free end sags under gravity
    assert beam.kinetic_energy > 0 and beam.elastic_energy > 0


def test_report_is_report_json(tmp_path):
    sim = tacta.Simulation.from_dict(beam_scene())
    sim.step(100)
    report = sim.report()
    assert report["ticks"] == 100
    assert report["sim_time_s"] == pytest.approx(0.1)
    assert report["bodies"][0]["name"] == "beam"
    files = sim.write_outputs(str(tmp_path))
    assert str(tmp_path / "report.json") in files
    written = json.loads((tmp_path / "report.json").read_text())
    assert written["state_hash"] == report["state_hash"]


def test_run_batch_returns_the_report():
    sim = tacta.Simulation.from_dict(beam_scene(duration=0.2))
    report = sim.run()
    assert report["ticks"] == 200 and sim.tick == 200
    report = sim.run(duration=0.1)
    assert sim.tick == 300 and report["ticks"] == 300


def test_devices_read_between_steps(root):
    sim = tacta.Simulation(str(root / "scenes/liver_palpation.yaml"))
    stylus = sim.devices["stylus"]
    assert stylus.plugin == "sim_stylus"
    sim.step(50)
    assert stylus.status == "connected"
    assert stylus.position.shape == (3,) and stylus.force.shape == (3,)
    with pytest.raises(ValueError, match="takes no host input"):
        stylus.input([0, 0, 0])
