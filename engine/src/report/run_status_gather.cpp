#include "report/run_status_gather.hpp"

#include <fmt/format.h>

#include "collision/collision_context.hpp"

namespace tacta {

namespace {

// One console line per bit seen that is a warning or an error; counts the kinds.
void summarise(const std::string& who, const std::vector<StatusBitCount>& bits, RunStatus& status) {
  for (const StatusBitCount& b : bits) {
    if (b.severity == StatusSeverity::Info) continue;
    (b.severity == StatusSeverity::Error ? status.errors : status.warnings) += 1;
    status.lines.push_back(fmt::format("{}: {}: {} on {} tick(s) from t = {:.3f} s; {}",
                                       severity_name(b.severity), who, b.name, b.ticks,
                                       b.first_time_s, b.remedy));
  }
}

}  // namespace

RunStatus collect_run_status(const HapticLoop& loop, const World& world,
                             const CollisionContext* collision) {
  RunStatus status;
  for (size_t i = 0; i < world.body_count(); ++i) {
    status.bodies.push_back(describe(loop.body_status(i), StatusSource::Model));
    summarise("body " + world.body(i).info.name, status.bodies.back(), status);
  }
  for (size_t d = 0; d < world.device_count(); ++d) {
    status.devices.push_back(describe(loop.device_status(d), StatusSource::Device));
    summarise("device " + world.device(d).link.name, status.devices.back(), status);
  }
  status.collision = describe(loop.collision_status(), StatusSource::Collision);
  summarise("collision", status.collision, status);
  if (collision != nullptr) {
    for (const CollisionPluginUse& u : collision->plugin_uses())
      status.collision_plugins.push_back({u.name, u.roles, u.roles_guessed, u.serves});
    status.pairs_capacity = collision->pairs_capacity();
    status.contacts_capacity = collision->contacts_capacity();
    status.pairs_high_water = collision->pairs_high_water();
    status.contacts_high_water = collision->contacts_high_water();
    status.proxy_slices = collision->proxy_slices();
    status.proxy_whole_refits = collision->proxy_whole_refits();
    status.proxy_sliced = collision->proxy_sliced();
    status.patch_gathers = collision->patch_gathers();
    status.patch_upkeep_gathers = collision->patch_upkeep_gathers();
    status.patch_queries = collision->patch_queries();
    status.clear_answers = collision->clear_answers();
    status.clear_bound_answers = collision->clear_bound_answers();
  }
  return status;
}

}  // namespace tacta
