// tacta.set_log_handler / tacta.set_log_level: the engine's messages (warnings, plugins' log
// lines) to a Python callable instead of stderr, e.g. logging.getLogger("tacta").log.
#include "bindings.hpp"
#include "tacta/log.hpp"

namespace tacta::python {
namespace {

// The logging module's numbers, so the handler can be Logger.log itself.
int logging_level(LogLevel level) {
  switch (level) {
    case LogLevel::debug: return 10;
    case LogLevel::info: return 20;
    case LogLevel::warning: return 30;
    default: return 40;
  }
}

void set_handler(py::object handler) {
  if (handler.is_none()) {
    set_log_sink(nullptr);
    return;
  }
  // Shared so that the sink's copies release the callable together, with the GIL taken.
  auto held = std::shared_ptr<py::object>(new py::object(std::move(handler)), [](py::object* o) {
    py::gil_scoped_acquire gil;
    delete o;
  });
  set_log_sink([held](LogLevel level, const std::string& message) {
    if (!Py_IsInitialized()) return;
    py::gil_scoped_acquire gil;  // messages come from whichever thread logged them
    try {
      (*held)(logging_level(level), message);
    } catch (py::error_already_set& e) {
      e.discard_as_unraisable("tacta log handler");
    }
  });
}

}  // namespace

void register_log(py::module_& m) {
  m.def("set_log_handler", &set_handler, py::arg("handler"),
        "Send the engine's messages to handler(level, message) (level as the logging module "
        "numbers them: 10 debug, 20 info, 30 warning, 40 error), e.g. "
        "logging.getLogger('tacta').log; None puts back the default (stderr).");
  m.def(
      "set_log_level",
      [](const std::string& name) {
        const std::optional<LogLevel> level = log_level_named(name);
        if (!level)
          throw py::value_error("expected 'debug', 'info', 'warning', 'error' or 'off', found '" +
                                name + "'");
        set_log_level(*level);
      },
      py::arg("level"), "Drop the engine's messages below this level (default 'info').");
  // The handler holds Python objects: let go of it before the interpreter goes.
  py::module_::import("atexit").attr("register")(py::cpp_function([] { set_log_sink(nullptr); }));
}

}  // namespace tacta::python
