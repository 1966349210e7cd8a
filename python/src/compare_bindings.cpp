// tacta.compare(scene, models): one scene run once per model, the table of `tacta compare` (the
// same code, tacta/compare/compare.hpp) as a list of dicts, the rows of compare.json.
#include <filesystem>
#include <optional>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "tacta/compare/compare.hpp"

namespace tacta::python {
namespace {

py::object compare(const std::string& scene, const std::vector<std::string>& models,
                   const py::object& overrides, std::optional<double> duration,
                   const std::string& reference, const std::string& out_dir) {
  CompareOptions options;
  options.scene = scene;
  options.models = models;
  options.overrides = override_strings(overrides);
  if (duration) {
    if (!(*duration > 0)) throw py::value_error("duration: expected a simulated time > 0 s");
    options.duration_s = *duration;
  }
  options.reference = reference;
  options.out_dir = out_dir;
  const std::shared_ptr<PluginRegistry> plugins = shared_plugins();
  CompareSummary summary;
  std::string chart_warning;
  {
    py::gil_scoped_release released;
    summary = run_comparison(options, *plugins);
    if (!out_dir.empty()) write_compare_outputs(out_dir, summary, chart_warning);
  }
  if (!chart_warning.empty() && PyErr_WarnEx(PyExc_RuntimeWarning, chart_warning.c_str(), 1) != 0)
    throw py::error_already_set();
  const py::object table = json_written_by([&](const std::string& dir) {
    std::filesystem::create_directories(dir);
    const std::string path = (std::filesystem::path(dir) / "compare.json").string();
    write_compare_json(path, summary);
    return path;
  });
  return table["models"];
}

}  // namespace

void register_compare(py::module_& m) {
  m.def("compare", &compare, py::arg("scene"), py::arg("models"), py::kw_only(),
        py::arg("overrides") = py::none(), py::arg("duration") = py::none(),
        py::arg("reference") = "", py::arg("out_dir") = "",
        "Runs the scene file once per model (every body takes it; lockstep; GIL released) like "
        "`tacta compare` and returns its table: one dict per model with compare.json's columns "
        "(docs/COMPARE.md). models: names or 'name:param=value:...'; overrides as for Simulation; "
        "duration in s (default the scene's); reference: one of models; out_dir: also write every "
        "run's outputs and compare.json/csv/png there. Raises tacta.SceneError for bad input.");
}

}  // namespace tacta::python
