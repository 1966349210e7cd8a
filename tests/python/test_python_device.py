# A device written in Python closes a loop: a force controller moves the mouse plugin's target
# (host input) until the block pushes back with the force it asks for. It is called every 10 ticks
# (100 Hz of simulated time) between chunks of haptic ticks, never inside the 1 kHz loop.
import numpy as np
import pytest
import tacta

from conftest import beam_scene, pressed_block_scene


class ForceController:
    """Integral control of the target height so the contact force reaches `setpoint` N (up)."""

    def __init__(self, setpoint, start):
        self.setpoint = setpoint
        self.target = np.array(start, dtype=float)
        self.forces = []

    def write(self, force):
        self.forces.append(np.array(force))

    def read(self):
        error = self.setpoint - (self.forces[-1][1] if self.forces else 0.0)
        self.target[1] -= 2e-4 * error  # m per N per call: 100 Hz, well inside the hand's bandwidth
        return self.target


def test_python_force_controller_closes_the_loop():
    sim = tacta.Simulation(pressed_block_scene())
    hand = sim.devices["hand"]
    controller = ForceController(setpoint=1.0, start=[0, 0.06, 0])
    assert hand.attach(controller, rate_hz=100) == 10
    sim.step(3000)
    assert len(controller.forces) == 300  # every 10 ticks, at ticks 0, 10, ..., 2990
    assert hand.status == "connected" and hand.in_contact
    assert hand.force[1] == pytest.approx(1.0, abs=0.05)
    assert hand.position[1] < 0.05 + 0.005  # the tool is pressed into the block's top (y = 0.05)
    assert sim.bodies["block"].faults == []


def test_python_device_calls_fall_on_absolute_ticks():
    hashes = []
    for chunks in ([1] * 200, [200], [3, 97, 100]):
        sim = tacta.Simulation(pressed_block_scene())
        sim.devices["hand"].attach(ForceController(setpoint=0.5, start=[0, 0.055, 0]), rate_hz=250)
        for n in chunks:
            sim.step(n)
        hashes.append(sim.report()["state_hash"])
    assert hashes[0] == hashes[1] == hashes[2]


def test_python_device_needs_an_input_device(root):
    sim = tacta.Simulation(str(root / "scenes/liver_palpation.yaml"))
    sim.devices["stylus"].attach(ForceController(1.0, [0, 0, 0]))
    with pytest.raises(ValueError, match="takes no host input"):
        sim.step(1)
    with pytest.raises(TypeError):
        sim.devices["stylus"].attach(object())
    beam = tacta.Simulation.from_dict(beam_scene())
    assert beam.devices == {}
