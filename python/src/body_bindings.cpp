// tacta.Body: one body's node state as NumPy views onto the engine's own arrays (no copy), its
// mesh, loads, model swaps, parameters and energies. sim.bodies maps names to them.
#include <pybind11/numpy.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "tacta/plugin_registry.hpp"

namespace tacta::python {
namespace {

// A (rows, columns) view of engine memory. Its base is a capsule owning a reference to the
// simulation, so the array keeps the engine arrays alive however long Python holds it. The
// engine never re-allocates a body's arrays after load (model swaps carry them over).
template <typename T>
py::array view(const SimPtr& holder, const T* data, size_t rows, size_t columns, bool writable) {
  py::capsule owner(new SimPtr(holder), [](void* p) { delete static_cast<SimPtr*>(p); });
  py::array_t<T> out(columns == 1 ? std::vector<py::ssize_t>{static_cast<py::ssize_t>(rows)}
                                  : std::vector<py::ssize_t>{static_cast<py::ssize_t>(rows),
                                                             static_cast<py::ssize_t>(columns)},
                     data, owner);
  if (!writable)
    py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return out;
}

// Copies `values` (n, 3) into a state array and tells the model (its history restarts).
void write_state(Body& b, double* target,
                 const py::array_t<double, py::array::c_style | py::array::forcecast>& values) {
  const size_t n = b.sim().body_arrays(b.handle).nodes;
  if (values.ndim() != 2 || values.shape(0) != static_cast<py::ssize_t>(n) || values.shape(1) != 3)
    throw py::value_error("expected an array of shape (" + std::to_string(n) + ", 3)");
  std::copy(values.data(), values.data() + 3 * n, target);
  b.sim().state_written(b.handle);
}

// A property getter: a view of one of the body's node arrays, `columns` values per node.
template <typename Pointer>
auto node_array(Pointer BodyArrays::*member, size_t columns, bool writable) {
  return [member, columns, writable](Body& b) {
    const BodyArrays a = b.sim().body_arrays(b.handle);
    return view(b.holder, a.*member, a.nodes, columns, writable);
  };
}

auto node_setter(double* BodyArrays::*member) {
  return [member](Body& b,
                  const py::array_t<double, py::array::c_style | py::array::forcecast>& values) {
    write_state(b, b.sim().body_arrays(b.handle).*member, values);
  };
}

py::object param_value(const tacta_param_value& v) {
  if (v.values != nullptr) return py::cast(std::vector<double>(v.values, v.values + v.count));
  if (v.text != nullptr) return py::str(v.text);
  return py::float_(v.number);
}

// Same model: the current parameters with the given ones changed; another model: only the given
// ones (the engine fills the rest with the model's defaults). Names are checked against the schema.
ParamSet swap_params(const Body& b, const std::string& model, const py::kwargs& given) {
  const auto schema = b.holder->plugins->schema(TACTA_KIND_MODEL, model);
  if (!schema)
    throw InputError(
        {b.sim().scene().path, 0, 0, "bodies." + b.sim().body_name(b.handle) + ".model"},
        b.holder->plugins->unknown_name_message(TACTA_KIND_MODEL, model));
  ParamSet params =
      model == b.sim().body_model(b.handle) ? b.sim().body_params(b.handle) : ParamSet{};
  for (const auto& [key, value] : given) {
    const std::string name = py::str(key).cast<std::string>();
    const tacta_param_spec* spec = nullptr;
    std::string known;
    for (const tacta_param_spec& s : *schema) {
      if (name == s.name) spec = &s;
      known += (known.empty() ? "" : ", ") + std::string(s.name);
    }
    if (spec == nullptr)
      throw InputError(
          {b.sim().scene().path, 0, 0, "bodies." + b.sim().body_name(b.handle) + ".params." + name},
          "model '" + model + "' has no parameter '" + name + "'; it has: " + known);
    if (spec->type == TACTA_PARAM_VECTOR)
      params.add_vector(name, value.cast<std::vector<double>>());
    else if (py::isinstance<py::str>(value))
      params.add_text(name, value.cast<std::string>());
    else if (!params.set_number(name, value.cast<double>()))
      params.add_number(name, value.cast<double>());
  }
  return params;
}

py::list body_faults(const Body& b) {
  py::list out;
  const RunResult report = b.sim().report();
  const BodyResult& r = report.bodies.at(b.handle.index);
  if (r.frozen || !r.fault.empty()) out.append(r.fault);
  return out;
}

}  // namespace

void register_bodies(py::module_& m) {
  py::class_<Body>(m, "Body", "One body of a Simulation: sim.body('liver'), sim.bodies['liver'].")
      .def_readonly("name", &Body::name)
      .def_readonly("handle", &Body::handle, "its tacta.BodyHandle (index, generation)")
      .def_property_readonly(
          "index", [](const Body& b) { return b.handle.index; },
          "its row in sim.report()['bodies'] (handle.index)")
      .def(py::self == py::self)
      .def("__hash__", [](const Body& b) { return std::hash<BodyHandle>{}(b.handle); })
      .def_property_readonly(
          "alive", [](const Body& b) { return b.sim().body_alive(b.handle); },
          "False once the body was removed (sim.remove_body)")
      .def_property_readonly("node_count",
                             [](const Body& b) { return b.sim().body_arrays(b.handle).nodes; })
      .def_property("positions", node_array(&BodyArrays::positions, 3, true),
                    node_setter(&BodyArrays::positions),
                    "(n, 3) float64 view of the node positions, m. Assigning copies in and calls "
                    "state_written(); "
                    "after writing through the view, call state_written() before the next step.")
      .def_property("velocities", node_array(&BodyArrays::velocities, 3, true),
                    node_setter(&BodyArrays::velocities),
                    "(n, 3) float64 view of the node velocities, m/s; written like positions.")
      .def_property_readonly("rest_positions", node_array(&BodyArrays::rest_positions, 3, false),
                             "(n, 3) read-only view of the rest positions, m")
      .def_property_readonly(
          "fixed",
          [](Body& b) {
            const BodyArrays a = b.sim().body_arrays(b.handle);
            return view(b.holder, reinterpret_cast<const bool*>(a.fixed), a.nodes, 1, false);
          },
          "(n,) read-only bool view: nodes held at rest")
      .def_property_readonly("masses", node_array(&BodyArrays::masses, 1, false),
                             "(n,) read-only view of the lumped node masses, kg")
      .def_property_readonly(
          "elements",
          [](Body& b) {
            const VolumeMesh& mesh = b.sim().body_mesh(b.handle);
            return view(b.holder, mesh.tets.data(), mesh.tet_count(), 4, false);
          },
          "(m, 4) read-only uint32 view of the tetrahedra (node indices)")
      .def_property_readonly(
          "surface",
          [](Body& b) {
            const std::vector<uint32_t>& tris = b.sim().surface_triangles(b.handle);
            return view(b.holder, tris.data(), tris.size() / 3, 3, false);
          },
          "(k, 3) read-only uint32 view of the triangles drawn and touched (into "
          "surface_positions)")
      .def_property_readonly(
          "surface_positions",
          [](Body& b) {
            std::vector<double> p = b.sim().surface_positions(b.handle);
            py::array_t<double> out({static_cast<py::ssize_t>(p.size() / 3), py::ssize_t{3}});
            std::copy(p.begin(), p.end(), out.mutable_data());
            return out;
          },
          "(v, 3) copy of the surface's current vertex positions, m")
      .def(
          "state_written", [](Body& b) { b.sim().state_written(b.handle); },
          "Call after writing positions or velocities through their views (the model restarts its "
          "history).")
      .def(
          "apply_force",
          [](Body& b, const std::vector<uint32_t>& nodes,
             const py::array_t<double, py::array::c_style | py::array::forcecast>& forces) {
            const std::vector<double> f(forces.data(), forces.data() + forces.size());
            b.sim().set_applied_forces(b.handle, nodes, f);
          },
          py::arg("nodes"), py::arg("forces"),
          "A load (N) on `nodes`, forces shaped (len(nodes), 3); kept for every step until cleared "
          "or replaced.")
      .def("clear_forces", [](Body& b) { b.sim().clear_applied_forces(b.handle); })
      .def_property_readonly(
          "model", [](const Body& b) { return b.sim().body_model(b.handle); },
          "the model asked for last (a swap applies at the next tick)")
      .def_property_readonly(
          "params",
          [](const Body& b) {
            const ParamSet& p = b.sim().body_params(b.handle);
            py::dict out;
            for (size_t i = 0; i < p.names().size(); ++i)
              out[py::str(p.names()[i])] = param_value(p.data()[i]);
            return out;
          },
          "the model's parameters as last asked for")
      .def(
          "swap_model",
          [](Body& b, const std::string& model, const py::kwargs& params) {
            b.sim().request_model_swap(b.handle, model, swap_params(b, model, params));
          },
          py::arg("model"),
          "Swaps to `model` with keyword parameters at the next tick; positions and velocities "
          "carry over "
          "(the NumPy views stay valid). Raises tacta.SceneError when the model refuses the body.")
      .def(
          "set_param",
          [](Body& b, const std::string& name, double value) {
            return b.sim().set_param(b.handle, name, value);
          },
          py::arg("name"), py::arg("value"),
          "Changes one model parameter; True when the model took it live, False when it took a "
          "swap.")
      .def_property_readonly(
          "kinetic_energy", [](const Body& b) { return b.sim().kinetic_energy(b.handle); }, "J")
      .def_property_readonly(
          "elastic_energy", [](const Body& b) { return b.sim().elastic_energy(b.handle); }, "J")
      .def_property_readonly("faults", &body_faults,
                             "why the body was frozen (diverged), if it was: a list of text")
      .def("__repr__", [](const Body& b) {
        if (!b.sim().body_alive(b.handle)) return "<tacta.Body '" + b.name + "', removed>";
        return "<tacta.Body '" + b.name + "' " + b.sim().body_model(b.handle) + ", " +
               std::to_string(b.sim().body_arrays(b.handle).nodes) + " nodes>";
      });

  auto simulation = py::reinterpret_borrow<py::class_<SimHolder, SimPtr>>(m.attr("Simulation"));
  simulation.def_property_readonly(
      "bodies",
      [](const SimPtr& h) {
        py::dict out;
        for (const BodyHandle handle : h->sim->bodies()) {
          const std::string& name = h->sim->body_name(handle);
          out[py::str(name)] = Body{h, handle, name};
        }
        return out;
      },
      "{name: Body}: the bodies present (removed ones left out), in the order they came");
  simulation.def("body", &body_of, py::arg("body"),
                 "The Body named `body` (or the one a tacta.BodyHandle / Body names). Raises "
                 "tacta.SceneError for an unknown name (with a did-you-mean) or a removed body.");
  simulation.def(
      "add_body",
      [](const SimPtr& h, const py::object& body) {
        const BodyHandle handle = h->sim->add_body(yaml_text(body));
        return Body{h, handle, h->sim->body_name(handle)};
      },
      py::arg("body"),
      "Adds a body (a dict as a scene lists it under `bodies`, or that YAML text); it enters at "
      "the next tick. Raises tacta.SceneError for a bad description, a name in use or no free slot "
      "(scene key capacity.bodies). Returns its Body.");
  simulation.def(
      "remove_body",
      [](const SimPtr& h, const py::object& body) { h->sim->remove_body(body_of(h, body).handle); },
      py::arg("body"),
      "Removes a body (a Body, its handle or its name) at the next tick; it stays in the report. "
      "Views already "
      "taken keep the state it had; any other use of its Body raises tacta.SceneError.");
}

}  // namespace tacta::python
