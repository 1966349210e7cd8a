#include "output/vtk_observer.hpp"

#include <filesystem>

#include "tacta/output/vtk_writer.hpp"

namespace tacta {

namespace {

class VtkObserver final : public FrameObserver {
 public:
  VtkObserver(std::string directory, double interval_s)
      : directory_(std::move(directory)), interval_s_(interval_s) {}

  void on_start(const SceneStatic& scene) override {
    std::filesystem::create_directories(directory_);
    for (const BodyStatic& b : scene.bodies) add_series(b);
  }

  void on_frame(const SceneStatic& scene, const Snapshot& snapshot) override {
    if (snapshot.time_s + 1e-9 < next_time_s_) return;
    next_time_s_ = snapshot.time_s + interval_s_;
    // A body added between steps joins the scene's description after on_start.
    while (series_.size() < scene.bodies.size()) add_series(scene.bodies[series_.size()]);
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
      const BodyStatic& b = scene.bodies[i];
      const BodySnapshot& s = snapshot.bodies[i];
      if (!s.present) continue;                          // not in the scene yet, or removed
      displacement_[i].resize(b.rest_positions.size());  // a cut changes the node count
      for (size_t k = 0; k < displacement_[i].size(); ++k)
        displacement_[i][k] = s.positions[k] - b.rest_positions[k];
      output::VtkGrid grid;
      grid.points = s.positions;
      if (!b.tets.empty())
        grid.tets = b.tets;
      else if (!b.quads.empty())
        grid.quads = b.quads;
      else
        grid.triangles = b.triangles;
      grid.point_data.push_back({"displacement", 3, displacement_[i]});
      grid.point_data.push_back({"velocity", 3, s.velocities});
      if (!s.von_mises.empty()) grid.point_data.push_back({"von_mises_stress", 1, s.von_mises});
      series_[i].write(snapshot.time_s, grid);
      if (b.surface_triangles.empty() ||
          s.surface_positions.size() != b.surface_rest_positions.size())
        continue;
      surface_displacement_[i].resize(s.surface_positions.size());
      for (size_t k = 0; k < s.surface_positions.size(); ++k)
        surface_displacement_[i][k] = s.surface_positions[k] - b.surface_rest_positions[k];
      output::VtkGrid surface;
      surface.points = s.surface_positions;
      surface.triangles = b.surface_triangles;
      surface.point_data.push_back({"displacement", 3, surface_displacement_[i]});
      surface_series_[i].write(snapshot.time_s, surface);
    }
  }

  void add_series(const BodyStatic& b) {
    series_.emplace_back(directory_, b.name);
    displacement_.emplace_back(b.rest_positions.size(), 0.0);
    // The embedded surface, the one the body is seen and touched through, as a series of its own.
    surface_series_.emplace_back(directory_, b.name + "_surface");
    surface_displacement_.emplace_back(b.surface_rest_positions.size(), 0.0);
  }

  std::vector<std::string> finish() override {
    std::vector<std::string> files;
    for (const output::VtkSeries& s : series_) files.push_back(s.pvd_file().string());
    for (const output::VtkSeries& s : surface_series_)
      if (s.step_count() > 0) files.push_back(s.pvd_file().string());
    return files;
  }

 private:
  std::string directory_;
  double interval_s_;
  double next_time_s_ = 0;
  std::vector<output::VtkSeries> series_;
  std::vector<std::vector<double>> displacement_;  // 3 per node, m, scratch per body
  std::vector<output::VtkSeries> surface_series_;  // per body; written only for embedded surfaces
  std::vector<std::vector<double>> surface_displacement_;  // 3 per surface vertex, m
};

}  // namespace

std::unique_ptr<FrameObserver> make_vtk_observer(const std::string& directory, double interval_s) {
  return std::make_unique<VtkObserver>(directory, interval_s);
}

}  // namespace tacta
