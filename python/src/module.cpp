// The `tacta` Python module (compiled part `tacta._tacta`): scene errors, the plugin list, and
// the registration of simulations, bodies and devices. See docs/PYTHON.md.
#include <dlfcn.h>
#include <filesystem>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "tacta/live_params.hpp"

namespace tacta::python {
namespace {

PyObject* scene_error_type = nullptr;   // tacta.SceneError, owned by the module for its life
PyObject* render_error_type = nullptr;  // tacta.RenderError, likewise

py::dict plugin_list() {
  const std::shared_ptr<PluginRegistry> registry = shared_plugins();
  py::list loaded, refused;
  for (const LoadedDescriptor& d : registry->list()) {
    py::dict row;
    row["kind"] = tacta_kind_name(d.descriptor->kind);
    row["name"] = d.descriptor->name;
    row["file"] = d.file;
    if (d.descriptor->kind == TACTA_KIND_MODEL)
      row["live_params"] = live_param_names(*d.descriptor);
    loaded.append(row);
  }
  for (const RefusedPlugin& r : registry->refused()) {
    py::dict row;
    row["file"] = r.file;
    row["reason"] = r.reason;
    refused.append(row);
  }
  py::dict out;
  out["loaded"] = loaded;
  out["refused"] = refused;
  out["search_paths"] = registry->search_paths();
  return out;
}

// <folder of _tacta.so>/plugins: where an installed package (pip, a wheel) carries its plugins.
// The build tree's module has no such folder and keeps the engine's default search.
std::string package_plugin_dir() {
  static const char anchor = 0;  // any address inside this library names its file
  Dl_info info{};
  if (dladdr(&anchor, &info) == 0 || !info.dli_fname) return {};
  const std::filesystem::path dir = std::filesystem::path(info.dli_fname).parent_path() / "plugins";
  std::error_code ec;
  return std::filesystem::is_directory(dir, ec) ? dir.string() : std::string();
}

}  // namespace

std::shared_ptr<PluginRegistry> shared_plugins() {
  // Loaded once with the GIL held; read-only afterwards, so simulations on several threads share it.
  static std::shared_ptr<PluginRegistry> registry;
  if (!registry) {
    auto loading = std::make_shared<PluginRegistry>();
    if (const std::string own = package_plugin_dir(); !own.empty()) loading->add_first_path(own);
    loading->load();
    registry = std::move(loading);
  }
  return registry;
}

void raise_scene_error(const InputError& error) {
  const SourceLocation& where = error.where();
  py::object type = py::reinterpret_borrow<py::object>(scene_error_type);
  py::object instance = type(error.what());
  instance.attr("file") = where.file;
  instance.attr("line") = where.line;
  instance.attr("column") = where.column;
  instance.attr("key") = where.key_path;
  PyErr_SetObject(scene_error_type, instance.ptr());
  throw py::error_already_set();
}

void raise_render_error(const std::string& message) {
  PyErr_SetString(render_error_type, message.c_str());
  throw py::error_already_set();
}

void register_errors(py::module_& m) {
  // An exception class of the module, kept for the module's life.
  auto add_error = [&m](const char* name, const char* doc, PyObject* base) {
    PyObject* type =
        PyErr_NewExceptionWithDoc((std::string("tacta.") + name).c_str(), doc, base, nullptr);
    m.attr(name) = py::reinterpret_borrow<py::object>(type);
    return type;
  };
  scene_error_type = add_error(
      "SceneError",
      "Bad input: a scene, override, mesh, plugin name or parameter. Attributes: file, line, "
      "column (1-based, 0 when unknown) and key (the key path, e.g. 'bodies[0].material.E').",
      PyExc_ValueError);
  render_error_type =
      add_error("RenderError",
                "No picture could be made: no headless EGL context (needs Mesa's libegl-mesa0 and "
                "libgl1-mesa-dri), or a build without the renderer. The message says which.",
                PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const InputError& error) {
      try {
        raise_scene_error(error);
      } catch (py::error_already_set& set) {
        set.restore();  // the translator leaves the Python error set
      }
    }
  });
}

}  // namespace tacta::python

PYBIND11_MODULE(_tacta, m) {
  using namespace tacta::python;
  m.doc() = "Tacta: real-time elastic bodies with force feedback (compiled part; import tacta)";
  m.attr("__version__") = TACTA_VERSION;
  register_errors(m);
  register_handles(m);
  register_simulation(m);
  register_bodies(m);
  register_cut(m);
  register_devices(m);
  register_snapshot(m);
  register_compare(m);
  register_log(m);
  m.def(
      "plugins", &plugin_list,
      "What the plugin loader found: {'loaded': [{kind, name, file}], 'refused': [{file, reason}], "
      "'search_paths': [...]}");
}
