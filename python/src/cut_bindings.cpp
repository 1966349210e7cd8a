// sim.cut(body, triangles, mode) and sim.body_revision(body): cutting from Python between steps
// (Simulation::cut), the blade given as any array-like of triangles.
#include <cmath>
#include <pybind11/numpy.h>
#include <string>

#include "bindings.hpp"

namespace tacta::python {
namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// "(2, 3, 3)"
std::string shape_text(const Doubles& a) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) text += (d ? ", " : "") + std::to_string(a.shape(d));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

// The blade as 9 doubles a triangle (three corners, m): from an (n, 3, 3) array of triangles, a
// (3n, 3) array of corners or 9n flat numbers.
std::vector<double> blade_triangles(const Doubles& a) {
  const bool triangles = a.ndim() == 3 && a.shape(1) == 3 && a.shape(2) == 3;
  const bool corners = a.ndim() == 2 && a.shape(1) == 3 && a.shape(0) % 3 == 0;
  const bool flat = a.ndim() == 1 && a.shape(0) % 9 == 0;
  if (!triangles && !corners && !flat)
    throw py::value_error(
        "expected triangles shaped (n, 3, 3), corners shaped (3n, 3) or 9n flat "
        "numbers (m), got shape " +
        shape_text(a));
  std::vector<double> out(a.data(), a.data() + a.size());
  for (double x : out)
    if (!std::isfinite(x)) throw py::value_error("the blade's triangles hold a non-finite number");
  return out;
}

py::dict summary_dict(const CutSummary& s) {
  py::dict out;
  out["changed"] = s.changed;
  out["revision"] = s.revision;
  out["tets_removed"] = s.tets_removed;
  out["nodes_removed"] = s.nodes_removed;
  out["nodes_added"] = s.nodes_added;
  out["faces_separated"] = s.faces_separated;
  out["tets"] = s.tets;
  out["nodes"] = s.nodes;
  return out;
}

}  // namespace

void register_cut(py::module_& m) {
  auto simulation = py::reinterpret_borrow<py::class_<SimHolder, SimPtr>>(m.attr("Simulation"));
  simulation.def(
      "cut",
      [](const SimPtr& h, const py::object& body, const Doubles& triangles,
         const std::string& mode) {
        CutMode cut_mode;
        if (!parse_cut_mode(mode, cut_mode))
          throw py::value_error("mode must be 'remove' or 'separate', got '" + mode + "'");
        const BodyHandle handle = body_of(h, body).handle;
        const std::vector<double> blade = blade_triangles(triangles);
        CutSummary summary;
        {
          py::gil_scoped_release released;
          summary = h->sim->cut(handle, blade, cut_mode);
        }
        return summary_dict(summary);
      },
      py::arg("body"), py::arg("triangles"), py::arg("mode") = "separate",
      "Cuts `body` (a name, Body or BodyHandle) between steps with a blade's swept surface: "
      "`triangles` (m, world frame) shaped (n, 3, 3), (3n, 3) or 9n flat. mode 'separate' opens "
      "the mesh faces the blade crosses (no mass lost), 'remove' takes out the tets it passes "
      "through. Returns {changed, revision, tets_removed, nodes_removed, nodes_added, "
      "faces_separated, tets, nodes}; a blade that misses changes nothing. The body's arrays are "
      "new after a cut that changed it: take its views again. Raises tacta.SceneError when the "
      "body's model takes no cuts or a removal would leave no tet, ValueError for a bad shape or "
      "mode.");
  simulation.def(
      "body_revision",
      [](const SimPtr& h, const py::object& body) {
        return h->sim->body_revision(body_of(h, body).handle);
      },
      py::arg("body"), "How many cuts have changed `body` so far (0: never cut).");
}

}  // namespace tacta::python
