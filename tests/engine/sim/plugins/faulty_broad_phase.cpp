// Test plugin: a broad phase whose every hierarchy update answers TACTA_COLLIDE_NOT_FINITE (an
// error) and that finds no pair, so a test can see a collision plugin's returned bits reach the
// tick's status, Simulation::step()'s result and report.json.
#include <array>

#include "tacta/sdk/collision.hpp"

namespace {

class FaultyBroadPhase {
 public:
  static constexpr const char* kName = "test_faulty_broad_phase";
  static constexpr const char* kDescription =
      "a broad phase whose updates report non-finite input (test only)";
  static constexpr uint32_t kVersion = 10000;
  static constexpr uint32_t kRoles = TACTA_COLLISION_ROLE_BROAD_PHASE;
  static constexpr std::array<tacta_param_spec, 0> kParams{};
  explicit FaultyBroadPhase(const tacta_collision_setup&) {}
  uint32_t update(const tacta_collision_world&) noexcept { return TACTA_COLLIDE_NOT_FINITE; }
  uint32_t find_pairs(const tacta_collision_world&, tacta_collision_pair*, uint32_t,
                      uint32_t& count) noexcept {
    count = 0;
    return TACTA_COLLIDE_OK;
  }
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::collision_descriptor<FaultyBroadPhase>())
