// tacta.Simulation: loading a scene (file or dict), stepping with the GIL released, running a
// batch, the report and the outputs.
#include <filesystem>
#include <optional>
#include <pybind11/stl.h>
#include <random>
#include <span>

#include "bindings.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"

namespace tacta::python {

// {"bodies.*.model": "tensor_mass", "clock.duration_s": 0.5} -> the command line's key=value
// strings. Text goes as is (YAML reads it), numbers and booleans as YAML scalars, lists and
// dicts as JSON flow (YAML is a superset of JSON). A list of "key=value" strings is taken as is.
std::vector<std::string> override_strings(const py::object& overrides) {
  std::vector<std::string> out;
  if (overrides.is_none()) return out;
  if (!py::isinstance<py::dict>(overrides)) return overrides.cast<std::vector<std::string>>();
  const py::object dumps = py::module_::import("json").attr("dumps");
  for (const auto& [key, value] : overrides.cast<py::dict>()) {
    std::string text;
    if (py::isinstance<py::str>(value))
      text = value.cast<std::string>();
    else if (py::isinstance<py::bool_>(value))
      text = value.cast<bool>() ? "true" : "false";
    else if (py::isinstance<py::float_>(value))
      text = py::repr(value).cast<std::string>();
    else
      text = dumps(value).cast<std::string>();
    out.push_back(py::str(key).cast<std::string>() + "=" + text);
  }
  return out;
}

std::string yaml_text(const py::object& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  return py::module_::import("json").attr("dumps")(value).cast<std::string>();
}

namespace {

SimPtr open_scene(const std::function<SceneDesc(const SchemaLookup&)>& load) {
  auto holder = std::make_shared<SimHolder>();
  holder->plugins = shared_plugins();
  RegistrySchemas schemas(*holder->plugins);
  const SceneDesc scene = load(schemas);
  holder->sim = std::make_unique<Simulation>(scene, *holder->plugins);
  return holder;
}

SimPtr from_file(const std::string& path, const py::object& overrides) {
  const std::vector<std::string> sets = override_strings(overrides);
  return open_scene([&](const SchemaLookup& schemas) { return load_scene(path, schemas, sets); });
}

SimPtr from_dict(const py::dict& scene, const std::string& base_dir, const py::object& overrides) {
  const std::string text = yaml_text(scene);
  const std::vector<std::string> sets = override_strings(overrides);
  // The virtual file's folder anchors relative mesh paths; its name is what messages show.
  const std::string virtual_path = (std::filesystem::path(base_dir) / "<dict>.yaml").string();
  return open_scene([&](const SchemaLookup& schemas) {
    return load_scene_from_string(text, virtual_path, schemas, sets);
  });
}

py::object report_dict(SimHolder& holder) {
  return json_written_by([&](const std::string& dir) { return holder.sim->write_report(dir); });
}

py::object run_batch(SimHolder& holder, std::optional<double> duration,
                     std::optional<bool> realtime, const std::string& out_dir) {
  if (!holder.python_devices.empty())
    throw py::value_error(
        "run() drives no Python device (they are called between step() chunks); use step()");
  RunOptions options;
  options.duration_s = duration;
  options.realtime = realtime;
  options.out_dir = out_dir;
  {
    py::gil_scoped_release released;
    holder.sim->run(options);
  }
  return report_dict(holder);
}

}  // namespace

py::object json_written_by(const std::function<std::string(const std::string& dir)>& write) {
  std::random_device entropy;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("tacta-py-" + std::to_string(entropy()) + std::to_string(entropy()));
  py::object result;
  try {
    std::string path;
    {
      py::gil_scoped_release released;
      path = write(dir.string());
    }
    const py::object file =
        py::module_::import("io").attr("open")(path, "r", py::arg("encoding") = "utf-8");
    result = py::module_::import("json").attr("load")(file);
    file.attr("close")();
  } catch (...) {
    std::filesystem::remove_all(dir);
    throw;
  }
  std::filesystem::remove_all(dir);
  return result;
}

void register_simulation(py::module_& m) {
  py::class_<SimHolder, SimPtr>(
      m, "Simulation",
      "A loaded scene, stepped from Python. Simulation(path, overrides=None) loads a "
      "scene file; Simulation.from_dict(scene) one built in Python.")
      .def(py::init(&from_file), py::arg("path"), py::arg("overrides") = py::none(),
           "Loads the scene file at `path`; `overrides` is a dict {key.path: value} (or a list of "
           "'key.path=value' strings), as the command line's --set. Raises tacta.SceneError.")
      .def_static(
          "from_dict", &from_dict, py::arg("scene"), py::arg("base_dir") = ".",
          py::arg("overrides") = py::none(),
          "A scene given as a dict (the YAML structure); relative mesh paths are taken from "
          "`base_dir`. Raises tacta.SceneError.")
      .def(
          "step", [](SimHolder& h, uint64_t n) { return step_driving_devices(h, n); },
          py::arg("n") = 1, "Advances n haptic ticks (GIL released) and returns how many ran.")
      .def(
          "advance_to",
          [](SimHolder& h, double t) {
            const double now = h.sim->time(), dt = h.sim->dt();
            if (!(t > now + 0.5 * dt)) return uint64_t{0};
            return step_driving_devices(h, static_cast<uint64_t>(std::llround((t - now) / dt)));
          },
          py::arg("t"),
          "Steps whole ticks until time reaches t (s), to within half a tick; returns the ticks.")
      .def("run", &run_batch, py::arg("duration") = py::none(), py::arg("realtime") = py::none(),
           py::arg("out_dir") = "",
           "Runs `duration` s more (default: the scene's) on the scene's clock or the one asked "
           "for, "
           "GIL released; returns the report dict.")
      .def_property_readonly(
          "time", [](const SimHolder& h) { return h.sim->time(); }, "simulated time, s")
      .def_property_readonly(
          "tick", [](const SimHolder& h) { return h.sim->tick(); }, "haptic ticks run")
      .def_property_readonly(
          "dt", [](const SimHolder& h) { return h.sim->dt(); }, "one haptic tick, s")
      .def_property_readonly(
          "last_status",
          [](const SimHolder& h) {
            py::dict d;
            d["model_bits"] = h.last_status.model_bits;
            d["collision_bits"] = h.last_status.collision_bits;
            d["device_bits"] = h.last_status.device_bits;
            d["error"] = h.last_status.error;
            return d;
          },
          "what the last step()/advance_to() raised: model (TACTA_STEP_*), collision and device "
          "bits OR-ed over its ticks, and 'error' (e.g. a body faulted and froze); "
          "report()['status'] "
          "has the names, counts and remedies")
      .def_property_readonly("scene_path", [](const SimHolder& h) { return h.sim->scene().path; })
      .def_property_readonly(
          "warnings", [](const SimHolder& h) { return h.sim->load_warnings(); },
          "legal but likely mistaken parts of the scene, with file, line and key")
      .def("report", &report_dict,
           "The report so far: report.json's content as a dict (docs/REPORT.md).")
      .def(
          "write_outputs",
          [](SimHolder& h, const std::string& dir) {
            py::gil_scoped_release released;
            return h.sim->write_outputs(dir);
          },
          py::arg("dir"),
          "Writes report.json, the CSV records and plots into dir; returns the files.")
      .def(
          "checkpoint",
          [](SimHolder& h, std::optional<std::string> path) {
            const std::vector<uint8_t> bytes = h.sim->save_state();
            if (path) h.sim->save_state(*path);
            return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
          },
          py::arg("path") = py::none(),
          "The run's state between steps as bytes (also written to path when given): a fresh "
          "Simulation of the same scene that restores it continues bit for bit. Raises "
          "ValueError naming the body whose model cannot be saved.")
      .def(
          "restore",
          [](SimHolder& h, const py::object& source) {
            if (py::isinstance<py::bytes>(source)) {
              const std::string bytes = source.cast<std::string>();
              h.sim->restore_state(std::span<const uint8_t>(
                  reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
            } else {
              h.sim->restore_state(py::str(source).cast<std::string>());
            }
            return h.sim->checkpoint_notes();
          },
          py::arg("source"),
          "Restores a checkpoint (bytes, or a path) taken from the same scene; returns notes on "
          "what could not be carried (live devices reconnect). Raises ValueError saying what "
          "does not match.");
}

}  // namespace tacta::python
