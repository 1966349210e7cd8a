"""Tacta from Python: load a scene, step it, read and write its state as NumPy views.

    import tacta
    sim = tacta.Simulation("scenes/liver_palpation.yaml", overrides={"bodies.*.model": "tensor_mass"})
    sim.step(1000)
    liver = sim.body("liver")
    print(liver.positions.shape, sim.report()["state_hash"])

See docs/PYTHON.md for the whole surface, docs/SWEEPS.md for tacta.sweep (runs on Dask).
"""
import os as _os

# A pip-installed package carries the report's plot scripts; the build tree's module finds them
# in the source tree. Set before the first run that plots.
_plots = _os.path.join(_os.path.dirname(__file__), "plots")
if _os.path.isdir(_plots):
    _os.environ.setdefault("TACTA_PLOT_SCRIPTS", _plots)

from ._tacta import (  # noqa: E402
    Body, BodyHandle, Device, DeviceHandle, RenderError, SceneError, Simulation, __version__, compare, plugins,
    set_log_handler, set_log_level,
)

__all__ = ["Body", "BodyHandle", "Device", "DeviceHandle", "RenderError", "SceneError", "Simulation", "compare",
           "plugins", "set_log_handler", "set_log_level", "sweep"]


def __getattr__(name):
    # tacta.sweep is imported on first use: it needs pandas and dask.distributed, the rest does not.
    if name == "sweep":
        import importlib
        return importlib.import_module(".sweep", __name__)
    raise AttributeError(f"module 'tacta' has no attribute '{name}'")
