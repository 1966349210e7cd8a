// VTK output for ParaView: one XML UnstructuredGrid (.vtu) per body and frame, and a .pvd
// collection that lists them by time. Points in m, displacement in m, velocity in m/s, stress in Pa.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "tacta/mesh.hpp"

namespace tacta::output {

// A named field, `components` values per point (or per cell), in the units its name implies.
struct VtkField {
  std::string name;  // e.g. "displacement", "velocity", "stress"
  int components = 1;
  std::span<const double> values;
};

// What one .vtu holds. The spans are read during write_vtu only (no ownership).
struct VtkGrid {
  std::span<const double> points;       // 3 per point, m
  std::span<const uint32_t> tets;       // 4 per tetrahedron
  std::span<const uint32_t> quads;      // 4 per quad (planar meshes)
  std::span<const uint32_t> triangles;  // 3 per triangle (surfaces, planar meshes)
  std::vector<VtkField> point_data;
  std::vector<VtkField> cell_data;  // cells in order: tets, then quads, then triangles
};

// The cells of a simulation mesh as VTK sees them: tets for a volume; quads, else triangles,
// for a planar mesh; the boundary triangles of a volume mesh without tets.
VtkGrid grid_of(const VolumeMesh& mesh, std::span<const double> current_positions);

enum class VtkEncoding {
  Ascii,   // readable, larger
  Base64,  // "binary" inline: base64 of raw little-endian arrays with a UInt64 size header
};

// Writes the grid; throws tacta::InputError naming the file and the inconsistent array (e.g. a
// field with the wrong count, or an index past the points) or the I/O failure.
void write_vtu(const std::filesystem::path& file, const VtkGrid& grid,
               VtkEncoding encoding = VtkEncoding::Base64);

// A time series: `<dir>/<name>_<step>.vtu` files listed in `<dir>/<name>.pvd`, which is rewritten
// after every step so it is valid even if the run stops early.
class VtkSeries {
 public:
  VtkSeries(std::filesystem::path directory, std::string name,
            VtkEncoding encoding = VtkEncoding::Base64);
  // Writes the step's .vtu and the updated .pvd; returns the .vtu path.
  std::filesystem::path write(double time_s, const VtkGrid& grid);
  const std::filesystem::path& pvd_file() const { return pvd_file_; }
  size_t step_count() const { return steps_.size(); }

 private:
  struct Step {
    double time_s;
    std::string file;  // relative to the .pvd's directory
  };
  void write_pvd() const;
  std::filesystem::path directory_;
  std::string name_;
  VtkEncoding encoding_;
  std::filesystem::path pvd_file_;
  std::vector<Step> steps_;
};

}  // namespace tacta::output
