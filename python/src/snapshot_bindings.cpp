// Simulation.snapshot(path): a PNG of the current state, drawn headless (EGL, Mesa's llvmpipe
// without a GPU) by the same code as `tacta snapshot` (tacta/render/snapshot_frame.hpp).
#include <optional>
#include <pybind11/stl.h>
#include <stdexcept>

#include "bindings.hpp"

#if TACTA_PYTHON_HAS_RENDER
#include "tacta/render/headless.hpp"
#include "tacta/render/image.hpp"
#include "tacta/render/snapshot_frame.hpp"
#endif

namespace tacta::python {
namespace {

py::tuple write_snapshot(SimHolder& holder, const std::string& path, std::optional<int> width,
                         std::optional<int> height, bool wireframe, bool colour_by_displacement) {
#if TACTA_PYTHON_HAS_RENDER
  const SceneDesc& scene = holder.sim->scene();
  render::HeadlessOptions view;
  view.width = width.value_or(scene.output.frame_width);
  view.height = height.value_or(scene.output.frame_height);
  render::SnapshotStyle style;
  style.wireframe = wireframe;
  style.colour_by_displacement = colour_by_displacement;
  std::string no_renderer;  // EGL's reason, raised once the GIL is held again
  render::Image image;
  {
    py::gil_scoped_release released;
    std::unique_ptr<render::HeadlessRenderer> renderer;
    try {
      renderer = std::make_unique<render::HeadlessRenderer>(view);
    } catch (const std::invalid_argument&) {
      throw;  // a size out of range: ValueError
    } catch (const std::runtime_error& e) {
      no_renderer = e.what();
    }
    if (renderer)
      image = render::write_snapshot_png(*renderer, holder.sim->scene_static(),
                                         holder.sim->snapshot(), path, style);
  }
  if (!no_renderer.empty()) raise_render_error(no_renderer);
  return py::make_tuple(image.width, image.height);
#else
  (void)holder, (void)path, (void)width, (void)height, (void)wireframe,
      (void)colour_by_displacement;
  raise_render_error("this build has no renderer (configured with TACTA_BUILD_RENDER=OFF)");
#endif
}

}  // namespace

void register_snapshot(py::module_& m) {
  auto simulation = py::reinterpret_borrow<py::class_<SimHolder, SimPtr>>(m.attr("Simulation"));
  simulation.def(
      "snapshot", &write_snapshot, py::arg("path"), py::kw_only(), py::arg("width") = py::none(),
      py::arg("height") = py::none(), py::arg("wireframe") = false,
      py::arg("colour_by_displacement") = true,
      "Writes a PNG of the current state at `path` (folders made), drawn headless (EGL) like "
      "`tacta snapshot`; width and height in pixels (default: the scene's output.frame_size). "
      "Returns (width, height). Raises tacta.RenderError when no EGL context can be made.");
}

}  // namespace tacta::python
