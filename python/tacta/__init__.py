"""Tacta from Python: load a scene, step it, read and write its state as NumPy views.

    import tacta
    sim = tacta.Simulation("scenes/liver_palpation.yaml", overrides={"bodies.*.model": "tensor_mass"})
    sim.step(1000)
    liver = sim.bodies["liver"]
    print(liver.positions.shape, sim.report()["state_hash"])

See docs/PYTHON.md for the whole surface.
"""
from ._tacta import Body, Device, RenderError, SceneError, Simulation, compare, plugins

__all__ = ["Body", "Device", "RenderError", "SceneError", "Simulation", "compare", "plugins"]
