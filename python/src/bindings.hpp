// Shared pieces of the `tacta` Python module: the simulation holder every view keeps alive, the
// scene-error translation, and the per-concern registration functions (one .cpp each).
#pragma once

#include <functional>
#include <memory>
#include <pybind11/pybind11.h>
#include <string>
#include <vector>

#include "tacta/error.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/sim/simulation.hpp"

namespace tacta::python {

namespace py = pybind11;

// A Python device attached to one engine device: obj.read() -> target (m) fed through the
// plugin's lock-free input, obj.write(force) with the force last sent (N). Called with the GIL
// held between chunks of `every_ticks` haptic ticks, never inside one.
struct PythonDevice {
  DeviceHandle device;
  uint64_t every_ticks = 1;
  py::object object;
};

// One loaded scene. Bodies, devices and NumPy views hold a shared_ptr to it, so the engine
// arrays they point into live as long as any of them does. The registry is declared first so it
// outlives the Simulation (plugin libraries stay open while instances exist).
struct SimHolder {
  std::shared_ptr<PluginRegistry> plugins;
  std::unique_ptr<Simulation> sim;
  std::vector<PythonDevice> python_devices;
  TickStatus last_status;  // OR-ed over every chunk of the last step()/advance_to()
};
using SimPtr = std::shared_ptr<SimHolder>;

// A body or device of a simulation: its handle (checked by the engine on every use) and its name
// (kept, so a removed body still prints as itself); holding it keeps the simulation alive.
template <class HandleT>
struct Entity {
  SimPtr holder;
  HandleT handle;
  std::string name;
  Simulation& sim() const { return *holder->sim; }
  friend bool operator==(const Entity& a, const Entity& b) {
    return a.holder == b.holder && a.handle == b.handle;
  }
};
using Body = Entity<BodyHandle>;
using Device = Entity<DeviceHandle>;

// sim.body(x) / sim.device(x): x a name, a handle, or a Body / Device of this simulation.
Body body_of(const SimPtr& holder, const py::object& which);
Device device_of(const SimPtr& holder, const py::object& which);

// The process-wide plugin registry, loaded on first use (searched folders: docs/PYTHON.md).
std::shared_ptr<PluginRegistry> shared_plugins();

// Raises tacta.SceneError (a ValueError) with file, line, column and key from an InputError.
[[noreturn]] void raise_scene_error(const InputError& error);

// Steps `ticks` haptic ticks with the GIL released, stopping at every Python device's boundary
// to call it with the GIL held. Returns the ticks run.
uint64_t step_driving_devices(SimHolder& holder, uint64_t ticks);

// {"bodies.*.model": "tensor_mass"} (or a list of "key=value") -> the command line's --set strings.
std::vector<std::string> override_strings(const py::object& overrides);

// Text for the scene reader: a str as it is (YAML), a dict or list as JSON (YAML reads JSON).
std::string yaml_text(const py::object& value);

// A JSON file the engine writes, `write(dir)` returning its path, read back as Python objects:
// written with the GIL released into a private temporary folder, removed afterwards. How the
// report and the comparison table reach Python with exactly the numbers of their files.
py::object json_written_by(const std::function<std::string(const std::string& dir)>& write);

// Raises tacta.RenderError (a RuntimeError): no picture could be made (no EGL, no renderer).
[[noreturn]] void raise_render_error(const std::string& message);

void register_errors(py::module_& m);
void register_handles(py::module_& m);
void register_simulation(py::module_& m);
void register_bodies(py::module_& m);
void register_cut(py::module_& m);
void register_devices(py::module_& m);
void register_snapshot(py::module_& m);
void register_compare(py::module_& m);
void register_log(py::module_& m);

}  // namespace tacta::python
