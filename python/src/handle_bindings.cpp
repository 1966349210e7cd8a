// tacta.BodyHandle / tacta.DeviceHandle: the engine's generation-checked handles as Python values
// (index, generation, equality, hashing), and sim.body(x) / sim.device(x), which take a name, a
// handle or a Body / Device and give the Body / Device.
#include <pybind11/operators.h>

#include "bindings.hpp"

namespace tacta::python {
namespace {

template <class HandleT>
void bind_handle(py::module_& m, const char* name, const char* doc) {
  py::class_<HandleT>(m, name, doc)
      .def_readonly("index", &HandleT::index, "its row in sim.report()['bodies'/'devices']")
      .def_readonly("generation", &HandleT::generation,
                    "changes when the body is removed; differs between simulations")
      .def(py::self == py::self)
      .def(py::self != py::self)
      .def("__hash__", [](const HandleT& h) { return std::hash<HandleT>{}(h); })
      .def("__repr__", [name](const HandleT& h) {
        return std::string(name) + "(index=" + std::to_string(h.index) +
               ", generation=" + std::to_string(h.generation) + ")";
      });
}

}  // namespace

Body body_of(const SimPtr& holder, const py::object& which) {
  Simulation& sim = *holder->sim;
  BodyHandle handle;
  if (py::isinstance<py::str>(which))
    handle = sim.body(which.cast<std::string>());
  else if (py::isinstance<Body>(which))
    handle = which.cast<const Body&>().handle;
  else if (py::isinstance<BodyHandle>(which))
    handle = which.cast<BodyHandle>();
  else
    throw py::type_error("expected a body's name, a tacta.Body or a tacta.BodyHandle");
  return Body{holder, handle, sim.body_name(handle)};  // body_name checks the handle
}

Device device_of(const SimPtr& holder, const py::object& which) {
  Simulation& sim = *holder->sim;
  DeviceHandle handle;
  if (py::isinstance<py::str>(which))
    handle = sim.device(which.cast<std::string>());
  else if (py::isinstance<Device>(which))
    handle = which.cast<const Device&>().handle;
  else if (py::isinstance<DeviceHandle>(which))
    handle = which.cast<DeviceHandle>();
  else
    throw py::type_error("expected a device's name, a tacta.Device or a tacta.DeviceHandle");
  return Device{holder, handle, sim.device_name(handle)};
}

void register_handles(py::module_& m) {
  bind_handle<BodyHandle>(m, "BodyHandle",
                          "A body's handle: Body.handle; stale once the body is removed.");
  bind_handle<DeviceHandle>(m, "DeviceHandle", "A device's handle: Device.handle.");
}

}  // namespace tacta::python
