// The automatic sizes of a surface-made body: thin parts ask for small voxels, the haptic tick
// for few tets; the coarser of the two wins, and the user is told when the budget did.
#include "mesh/tet_budget.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <string>
#include <utility>

#include "tacta/embedded_surface.hpp"
#include "tacta/mesh_build.hpp"

namespace tacta::mesh_detail {

namespace {

constexpr double kAutoVoxelsPerDiagonal = 20;  // at most bounding-box diagonal / 20
constexpr double kAutoMaxBoxCells = 1e6;       // the grid's box stays under this many cells
constexpr int kMaxBudgetTries = 12;  // voxelisations to reach the budget (2-5 typical)
constexpr int kMaxGmshTries = 4;               // Gmsh remeshes to reach the budget

// The surface's bounding-box edge lengths, m.
std::array<double, 3> extent(const SurfaceMesh& s) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < s.positions.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], s.positions[i]);
    hi[i % 3] = std::max(hi[i % 3], s.positions[i]);
  }
  return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
}

double surface_area(const SurfaceMesh& s) {
  double area = 0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const double* a = &s.positions[3 * size_t{s.triangles[3 * t]}];
    const double* b = &s.positions[3 * size_t{s.triangles[3 * t + 1]}];
    const double* c = &s.positions[3 * size_t{s.triangles[3 * t + 2]}];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                 v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    area += 0.5 * std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                             u[0] * v[1] - u[1] * v[0]);
  }
  return area;
}

// Whether a grid of this cell size over the surface's box stays under kAutoMaxBoxCells.
bool within_box_cells(const SurfaceMesh& s, double cell) {
  const std::array<double, 3> e = extent(s);
  return (e[0] / cell + 2) * (e[1] / cell + 2) * (e[2] / cell + 2) <= kAutoMaxBoxCells;
}

// The volume the tets will hold, about: the enclosed one (majority fill keeps it within a few
// %), or half the box for an open surface that encloses nothing measurable.
double expected_volume(const SurfaceMesh& s) {
  const double enclosed = std::abs(enclosed_volume(s));
  if (enclosed > 0 && std::isfinite(enclosed)) return enclosed;
  const std::array<double, 3> e = extent(s);
  return 0.5 * e[0] * e[1] * e[2];
}

void warn_coarser_than_thin_parts(const LoadReport& r, double volume, LoadReport& out) {
  if (!(r.voxel_size > r.thin_part_size * (1 + 1e-9))) return;
  const double thin_tets = 6 * volume / std::pow(r.thin_part_size, 3);
  out.warnings.push_back(fmt::format(
      "the tet budget (max_tets {}) made the voxels {:.3g} m, coarser than the {:.3g} m the "
      "surface's thin parts ask for (about {:.0f} tets): the surface is still drawn and touched "
      "as it is and each shell stays one piece, but its thin parts deform as coarse blocks "
      "(raise max_tets, or give voxel_size)",
      r.max_tets, r.voxel_size, r.thin_part_size, thin_tets));
}

// Majority voxels at h; where no cell of a budget-sized grid is mostly inside (a thin body, an
// instrument's shaft), the cells the surface crosses, which hold every shell in one piece with
// more volume than it encloses.
VolumeMesh voxelize_at(const SurfaceMesh& surface, double h, double thin, size_t max_tets,
                       LoadReport& attempt) {
  const LoadReport before = attempt;
  try {
    return voxelize(surface, h, &attempt, VoxelFill::Majority);
  } catch (const InputError&) {
    if (h <= thin * (1 + 1e-9)) throw;
  }
  attempt = before;
  try {
    VolumeMesh mesh = voxelize(surface, h, &attempt, VoxelFill::Cover);
    attempt.warnings.push_back(fmt::format(
        "no {:.3g} m voxel is mostly inside the surface: the cells it crosses were kept", h));
    return mesh;
  } catch (const InputError& e) {
    throw InputError(e.where(), fmt::format("{} (the voxel size {:.4g} m came from max_tets {}: "
                                            "give a larger max_tets, or voxel_size)",
                                            e.what(), h, max_tets));
  }
}

}  // namespace

double thin_part_voxel_size(const SurfaceMesh& s) {
  const std::array<double, 3> e = extent(s);
  double h = std::hypot(e[0], e[1], e[2]) / kAutoVoxelsPerDiagonal;
  const double area = surface_area(s), volume = std::abs(enclosed_volume(s));
  if (area > 0 && volume > 0) h = std::min(h, volume / area);
  return h;
}

VolumeMesh voxelize_within_budget(const SurfaceMesh& surface, size_t max_tets, LoadReport& r) {
  const double thin = thin_part_voxel_size(surface);
  if (!(thin > 0) || !std::isfinite(thin))
    throw InputError({surface.source, 0, 0, ""},
                     "the surface is flat or a point: it encloses no volume");
  const double volume = expected_volume(surface);
  // Cells ~ volume / h^3, 6 tets each: the cell that meets the budget, then checked by counting.
  double h = std::max(thin, std::cbrt(6 * volume / static_cast<double>(max_tets)));
  if (!within_box_cells(surface, h)) {
    const double wanted = h;
    while (!within_box_cells(surface, h)) h *= 1.1;
    r.warnings.push_back(fmt::format(
        "the automatic size asks for {:.3g} m voxels; {:.3g} m was used to keep the grid under a "
        "million cells (give voxel_size, or tetrahedralize, to choose)",
        wanted, h));
  }
  const LoadReport before = r;
  // tets(h) falls as h grows: the finest h known to fit is searched between the coarsest known
  // over the budget and it (geometric bisection), stopping within 20 % of the budget.
  double over = 0, fits = INFINITY;
  VolumeMesh best;
  LoadReport best_report;
  int refinements = 0;
  for (int tries = 1; tries <= kMaxBudgetTries; ++tries) {
    LoadReport attempt = before;
    VolumeMesh mesh = voxelize_at(surface, h, thin, max_tets, attempt);
    const size_t tets = mesh.tet_count();
    if (tets > max_tets) {
      over = std::max(over, h);
      h = std::isfinite(fits)
              ? std::sqrt(over * fits)
              : h * std::max(1.02, 1.01 * std::cbrt(static_cast<double>(tets) / max_tets));
      continue;
    }
    // Where the inside cells split a shell apart, a finer grid (up to 3 times 1.5x finer) is
    // tried while it fits the budget and the box, before the crossed cells join the pieces.
    const double finer = h / 1.5;
    if (over == 0 && attempt.split_pieces > 0 && refinements < 3 &&
        within_box_cells(surface, finer) &&
        1.5 * 1.5 * 1.5 * static_cast<double>(tets) <= static_cast<double>(max_tets)) {
      h = finer;
      ++refinements;
      continue;
    }
    if (h < fits) {
      fits = h;
      best = std::move(mesh);
      best_report = std::move(attempt);
    }
    if (over == 0 || 5 * tets >= 4 * max_tets || fits < 1.02 * over) break;
    h = std::sqrt(over * fits);
  }
  if (!std::isfinite(fits))
    throw InputError({surface.source, 0, 0, ""},
                     fmt::format("no voxel size up to {:.4g} m fits max_tets {} after {} tries; "
                                 "give voxel_size",
                                 h, max_tets, kMaxBudgetTries));
  // Joining split pieces by the crossed cells can triple the volume (and the tets), so the tet
  // count jumps with h (Armadillo at max_tets 1000: 1 m 1,194 tets, 1.05 m 3,204 joined, 1.1 m
  // 912, 1.3 m 1,848 joined): where the best fit was joined or is under 80 % of the budget,
  // sizes around it are tried for one that fits with more tets and needs no join.
  if (best_report.split_pieces > 0 || 5 * best.tet_count() < 4 * max_tets) {
    for (int k = -6; k <= 3; ++k) {
      const double near = fits * std::pow(1.04, k);
      if (k == 0 || near < thin) continue;
      LoadReport attempt = before;
      VolumeMesh mesh = voxelize_at(surface, near, thin, max_tets, attempt);
      if (mesh.tet_count() <= max_tets && attempt.split_pieces == 0 &&
          (best_report.split_pieces > 0 || mesh.tet_count() > best.tet_count())) {
        best = std::move(mesh);
        best_report = std::move(attempt);
      }
    }
  }
  r = std::move(best_report);
  r.max_tets = max_tets;
  r.thin_part_size = thin;
  if (refinements > 0) {
    r.warnings.push_back(fmt::format(
        "the automatic voxel size was made {} times 1.5x finer to keep each surface shell in "
        "one piece",
        refinements));
  }
  warn_coarser_than_thin_parts(r, volume, r);
  return best;
}

VolumeMesh tetrahedralize_within_budget(const SurfaceMesh& surface,
                                        const TetrahedralizeDesc& options, size_t max_tets,
                                        LoadReport& r) {
  const LoadReport before = r;
  // A closed surface of F triangles gives at least about F tets (Bunny.stl: 2,728 -> 8,535):
  // past the budget already, Gmsh is not asked to keep it as it is.
  if (surface.triangle_count() <= max_tets) {
    VolumeMesh mesh = tetrahedralize(surface, options, &r);
    if (mesh.tet_count() <= max_tets) {
      r.max_tets = max_tets;
      return mesh;
    }
    r = before;
  }
  // Remeshed at a largest tet volume that fits: about V / max_volume tets (liver.obj: 0.87),
  // scattered by the patches' remeshing (Bunny.stl: 1.0-1.2), hence 20 % of margin.
  TetrahedralizeDesc sized = options;
  sized.max_volume = 1.2 * expected_volume(surface) / static_cast<double>(max_tets);
  VolumeMesh best;
  LoadReport best_report;
  for (int tries = 1; tries <= kMaxGmshTries; ++tries) {
    LoadReport attempt = before;
    VolumeMesh mesh = tetrahedralize(surface, sized, &attempt);
    const size_t tets = mesh.tet_count();
    const bool fits = tets <= max_tets;
    if (fits || best.tets.empty() || tets < best.tet_count()) {
      best = std::move(mesh);
      best_report = std::move(attempt);
      best_report.budget_max_volume = sized.max_volume;
    }
    if (fits) break;
    sized.max_volume *= 1.15 * static_cast<double>(tets) / static_cast<double>(max_tets);
  }
  r = std::move(best_report);
  r.max_tets = max_tets;
  if (best.tet_count() > max_tets) {
    r.warnings.push_back(fmt::format(
        "Gmsh gave {} tets at max_volume {:.3g} m^3, more than max_tets {}, after {} tries; give "
        "max_volume to choose",
        best.tet_count(), r.budget_max_volume, max_tets, kMaxGmshTries));
  }
  // The remeshed tets' boundary is not the user's surface: that one is drawn and touched.
  SurfaceMesh shown = surface;
  if (enclosed_volume(shown) < 0) {
    for (size_t t = 0; t < shown.triangle_count(); ++t) {
      std::swap(shown.triangles[3 * t + 1], shown.triangles[3 * t + 2]);
      if (shown.corner_uvs.empty()) continue;
      std::swap(shown.corner_uvs[6 * t + 2], shown.corner_uvs[6 * t + 4]);
      std::swap(shown.corner_uvs[6 * t + 3], shown.corner_uvs[6 * t + 5]);
    }
  }
  best.embedding = bind_surface_to_tets(shown, best, &r);
  return best;
}

}  // namespace tacta::mesh_detail
