// tacta.Device: a device's last sample and force between steps, host input, and devices written
// in Python. A Python device is driven between chunks of haptic ticks, never inside one: the
// 1 kHz loop runs with the GIL released and only sees the plugin's lock-free input slot.
#include <algorithm>
#include <cmath>
#include <pybind11/numpy.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "tacta/device_api.h"

namespace tacta::python {
namespace {

const char* state_name(int32_t state) {
  switch (state) {
    case TACTA_DEVICE_CONNECTED: return "connected";
    case TACTA_DEVICE_DISCONNECTED: return "disconnected";
    case TACTA_DEVICE_FAULT: return "fault";
    case TACTA_DEVICE_FINISHED: return "finished";
    default: return "unknown";
  }
}

py::array_t<double> vec3(const double* v) {
  py::array_t<double> out(3);
  std::copy(v, v + 3, out.mutable_data());
  return out;
}

void feed(SimHolder& holder, DeviceHandle device, const std::vector<double>& values) {
  if (!holder.sim->device_input(device, values.data(), static_cast<uint32_t>(values.size())))
    throw py::value_error(
        "device '" + holder.sim->device_name(device) + "' (plugin " +
        holder.sim->device_plugin(device) +
        ") takes no host input; a Python device needs an input device such as plugin: mouse");
}

// One exchange with a Python device: it gets the force last sent, then gives its next target.
void exchange(SimHolder& holder, const PythonDevice& pd) {
  const DeviceReading reading = holder.sim->device_reading(pd.device);
  pd.object.attr("write")(vec3(reading.force));
  const std::vector<double> target = pd.object.attr("read")().cast<std::vector<double>>();
  if (target.size() != 3)
    throw py::value_error("a Python device's read() returns 3 values (x, y, z in m)");
  feed(holder, pd.device, target);
}

}  // namespace

uint64_t step_driving_devices(SimHolder& holder, uint64_t ticks) {
  Simulation& sim = *holder.sim;
  uint64_t done = 0;
  holder.last_status = {};
  while (done < ticks) {
    uint64_t chunk = ticks - done;
    // Exchanges fall on absolute ticks (multiples of every_ticks), so step(1) a thousand times
    // and step(1000) drive a Python device identically.
    for (const PythonDevice& pd : holder.python_devices) {
      const uint64_t phase = sim.tick() % pd.every_ticks;
      if (phase == 0) exchange(holder, pd);
      chunk = std::min(chunk, pd.every_ticks - phase);
    }
    StepResult ran;
    {
      py::gil_scoped_release released;
      ran = sim.step(chunk);
    }
    holder.last_status.merge(ran.status);
    done += ran.ticks;
    if (ran.ticks < chunk) break;  // the run ended (every device finished)
  }
  return done;
}

void register_devices(py::module_& m) {
  py::class_<Device>(m, "Device",
                     "One device of a Simulation: sim.device('stylus'), sim.devices['stylus'].")
      .def_readonly("name", &Device::name)
      .def_readonly("handle", &Device::handle, "its tacta.DeviceHandle (index, generation)")
      .def_property_readonly(
          "index", [](const Device& d) { return d.handle.index; },
          "its row in sim.report()['devices'] (handle.index)")
      .def(py::self == py::self)
      .def("__hash__", [](const Device& d) { return std::hash<DeviceHandle>{}(d.handle); })
      .def_property_readonly("plugin",
                             [](const Device& d) { return d.sim().device_plugin(d.handle); })
      .def_property_readonly(
          "position",
          [](const Device& d) { return vec3(d.sim().device_reading(d.handle).position); },
          "(3,) the last sampled stylus position, m")
      .def_property_readonly(
          "proxy", [](const Device& d) { return vec3(d.sim().device_reading(d.handle).proxy); },
          "(3,) the god-object proxy on the touched surface, m")
      .def_property_readonly(
          "force", [](const Device& d) { return vec3(d.sim().device_reading(d.handle).force); },
          "(3,) the force last sent to the device, N (zero after a fault)")
      .def_property_readonly(
          "status",
          [](const Device& d) { return state_name(d.sim().device_reading(d.handle).state); },
          "'connected', 'disconnected', 'fault' or 'finished'")
      .def_property_readonly(
          "in_contact", [](const Device& d) { return d.sim().device_reading(d.handle).in_contact; })
      .def(
          "input",
          [](Device& d, const std::vector<double>& values) { feed(*d.holder, d.handle, values); },
          py::arg("values"),
          "Hands values to the plugin's input entry (mouse: a target x, y, z in m).")
      .def(
          "attach",
          [](Device& d, py::object object, double rate_hz) {
            if (!py::hasattr(object, "read") || !py::hasattr(object, "write"))
              throw py::type_error("a Python device has read() -> (x, y, z) and write(force)");
            if (!(rate_hz > 0) || !std::isfinite(rate_hz))
              throw py::value_error("rate_hz must be > 0");
            const double per_tick = 1.0 / (rate_hz * d.sim().dt());
            const uint64_t every =
                std::max<uint64_t>(1, static_cast<uint64_t>(std::llround(per_tick)));
            auto& list = d.holder->python_devices;
            std::erase_if(list, [&](const PythonDevice& pd) { return pd.device == d.handle; });
            list.push_back({d.handle, every, std::move(object)});
            return every;
          },
          py::arg("device"), py::arg("rate_hz") = 100.0,
          "Drives this device from a Python object at rate_hz (default 100 Hz) of simulated time: "
          "at every 1/rate_hz boundary step() calls device.write(force) then feeds device.read() "
          "to the plugin's input. Returns the haptic ticks between calls.")
      .def(
          "change_tool",
          [](Device& d, const py::object& tool) { d.sim().change_tool(d.handle, yaml_text(tool)); },
          py::arg("tool"),
          "Replaces the tool this device carries at the next tick: a shape as a scene gives "
          "`tool` ({'sphere': {'radius': 0.004}}). The proxy takes its radius and starts afresh "
          "where the device is. Raises tacta.SceneError for a bad shape or a change still "
          "waiting for its tick.")
      .def(
          "detach",
          [](Device& d) {
            std::erase_if(d.holder->python_devices,
                          [&](const PythonDevice& pd) { return pd.device == d.handle; });
          },
          "Stops driving this device from Python (its last target stays).")
      .def("__repr__", [](const Device& d) {
        return "<tacta.Device '" + d.name + "' " + d.sim().device_plugin(d.handle) + ">";
      });

  auto simulation = py::reinterpret_borrow<py::class_<SimHolder, SimPtr>>(m.attr("Simulation"));
  simulation.def_property_readonly(
      "devices",
      [](const SimPtr& h) {
        py::dict out;
        for (const DeviceHandle handle : h->sim->devices()) {
          const std::string& name = h->sim->device_name(handle);
          out[py::str(name)] = Device{h, handle, name};
        }
        return out;
      },
      "{name: Device}, in scene order");
  simulation.def("device", &device_of, py::arg("device"),
                 "The Device named `device` (or the one a tacta.DeviceHandle / Device names). "
                 "Raises tacta.SceneError for an unknown name (with a did-you-mean).");
}

}  // namespace tacta::python
