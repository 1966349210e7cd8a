// Plugin "ccd": narrow phase. Exact continuous test on candidate triangle pairs (6 vertex-face
// and 9 edge-edge tests each) and the primitive queries used by `tacta ccd-bench`.
// Parameter `method` picks the conservative inclusion test (default) or the plain Moore-Wilhelms
// baseline (cubic roots then inside test, which can miss contacts).
// It also answers `respond` for the whole pipeline (contact_response.hpp documents the method):
// the engine calls respond on the plugin serving the response role (this one by default).
#include <array>

#include "contact_response.hpp"
#include "plain_ccd.hpp"
#include "tacta/sdk/collision.hpp"
#include "triangle_pair_ccd.hpp"

namespace tacta::collision {

class CcdNarrowPhase {
 public:
  static constexpr const char* kName = "ccd";
  static constexpr uint32_t kRoles =
      TACTA_COLLISION_ROLE_NARROW_PHASE | TACTA_COLLISION_ROLE_RESPONSE;
  static constexpr const char* kDescription =
      "narrow phase: conservative Moore-Wilhelms CCD, vertex-face and edge-edge (inclusion test); "
      "contact response: projection + inelastic impulses with Coulomb friction";
  static constexpr uint32_t kVersion = 10000;
  static constexpr std::array<tacta_param_spec, 6> kParams{
      sdk::choice_param("method", "inclusion|plain", 0,
                        "inclusion: conservative, never misses; plain: cubic roots (baseline)"),
      sdk::real_param("distance_tolerance", "m", 1e-6, 1e-12, 1e-2,
                      "refine until the residual box is this small (conservative either way)"),
      sdk::int_param("max_iterations", 100000, 100, 10000000,
                     "boxes examined per query before answering 'contact' conservatively"),
      sdk::real_param("friction", "", 0.3, 0.0, 10.0,
                      "Coulomb friction coefficient of every contact (response)"),
      sdk::int_param("response_iterations", 8, 1, 1000,
                     "Gauss-Seidel passes over the contacts, positions then velocities"),
      sdk::real_param("response_tolerance", "m", 1e-7, 0.0, 1e-2,
                      "penetration of the thickness layer accepted after the passes"),
  };

  explicit CcdNarrowPhase(const tacta_collision_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    method_ = params.choice("method") == 1 ? CcdMethod::kPlain : CcdMethod::kInclusion;
    tolerance_.distance = params.real("distance_tolerance");
    tolerance_.max_iterations = static_cast<uint32_t>(params.integer("max_iterations"));
    response_.friction = params.real("friction");
    response_.iterations = static_cast<uint32_t>(params.integer("response_iterations"));
    response_.tolerance = params.real("response_tolerance");
  }

  uint32_t respond(tacta_collision_world& world, tacta_contact* contacts, uint32_t count) noexcept {
    return respond_to_contacts(world, contacts, count, response_);
  }

  bool vertex_face(const double* points, tacta_ccd_hit& hit) noexcept {
    return report(method_ == CcdMethod::kPlain ? vertex_face_plain(points)
                                               : vertex_face_inclusion(points, tolerance_),
                  true, hit);
  }
  bool edge_edge(const double* points, tacta_ccd_hit& hit) noexcept {
    return report(method_ == CcdMethod::kPlain ? edge_edge_plain(points)
                                               : edge_edge_inclusion(points, tolerance_),
                  false, hit);
  }

  // pairs == nullptr: every triangle pair of every two surfaces and each surface with itself
  // (brute force, for small worlds and tests).
  uint32_t detect(const tacta_collision_world& world, const tacta_collision_pair* pairs,
                  uint32_t pair_count, tacta_contact* contacts, uint32_t capacity,
                  uint32_t& count) noexcept {
    count = 0;
    uint32_t bits = 0;
    if (pairs != nullptr) {
      for (uint32_t i = 0; i < pair_count && !(bits & TACTA_COLLIDE_OVERFLOW); ++i)
        bits |= triangle_pair_contacts(world, {pairs[i].surface_a, pairs[i].element_a},
                                       {pairs[i].surface_b, pairs[i].element_b}, method_,
                                       tolerance_, contacts, capacity, count);
      return bits;
    }
    for (uint32_t sa = 0; sa < world.surface_count; ++sa)
      for (uint32_t sb = sa; sb < world.surface_count; ++sb)
        for (uint32_t ta = 0; ta < world.surfaces[sa].triangle_count; ++ta)
          for (uint32_t tb = sa == sb ? ta + 1 : 0; tb < world.surfaces[sb].triangle_count; ++tb) {
            bits |= triangle_pair_contacts(world, {sa, ta}, {sb, tb}, method_, tolerance_, contacts,
                                           capacity, count);
            if (bits & TACTA_COLLIDE_OVERFLOW) return bits;
          }
    return bits;
  }

 private:
  static bool report(const CcdResult& r, bool vertex_face, tacta_ccd_hit& hit) noexcept {
    hit.toi = r.toi;
    if (vertex_face) {
      hit.barycentric[0] = 1.0 - r.u - r.v;
      hit.barycentric[1] = r.u;
      hit.barycentric[2] = r.v;
    } else {
      hit.barycentric[0] = r.u;
      hit.barycentric[1] = r.v;
      hit.barycentric[2] = 0.0;
    }
    return r.hit;
  }

  CcdMethod method_ = CcdMethod::kInclusion;
  CcdTolerance tolerance_;
  ResponseSettings response_;
};

}  // namespace tacta::collision

TACTA_PLUGIN_EXPORT(tacta::sdk::collision_descriptor<tacta::collision::CcdNarrowPhase>())
