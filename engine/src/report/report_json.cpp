// report.json: what a run did, in one file a script can read (documented in docs/REPORT.md).
#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "run_outputs.hpp"
#include "tacta/collision_api.h"

namespace tacta {

namespace {

using Json = nlohmann::ordered_json;

Json ticks(const TickSummary& t) {
  return Json{{"p50", t.p50_ms},
              {"p99", t.p99_ms},
              {"p999", t.p999_ms},
              {"max", t.max_ms},
              {"mean", t.mean_ms}};
}

// What the body's mesh source became: voxels (size, cells, volumes, pieces) or Gmsh tets, and
// every loader warning.
Json mesh_origin(const BodyResult& b, const LoadReport& load) {
  Json j = {{"summary", b.mesh}, {"format", load.format}};
  if (load.voxel_size > 0) {
    j["voxel_size_m"] = load.voxel_size;
    j["voxel_cells"] = static_cast<uint64_t>(load.voxel_cells);
    j["thin_part_size_m"] = load.thin_part_size;
    j["surface_shells"] = static_cast<uint64_t>(load.shells);
    j["enclosed_volume_m3"] = load.enclosed_volume;
    j["volume_m3"] = load.mesh_volume;
    j["piece_volumes_m3"] = load.piece_volumes;
  }
  if (load.max_tets > 0) j["max_tets"] = static_cast<uint64_t>(load.max_tets);
  j["warnings"] = b.mesh_warnings;
  return j;
}

// The status bits seen (docs/REPORT.md): name, value, severity, ticks, first time, remedy.
Json status_bits(const std::vector<StatusBitCount>& bits) {
  Json list = Json::array();
  for (const StatusBitCount& b : bits)
    list.push_back({{"bit", b.name},
                    {"value", static_cast<uint64_t>(b.bit)},
                    {"severity", severity_name(b.severity)},
                    {"ticks", b.ticks},
                    {"first_time_s", b.first_time_s},
                    {"remedy", b.remedy}});
  return list;
}

// Which plugin serves which role, each plugin's declared roles, and the buffers' use.
Json collision(const RunStatus& s) {
  const auto roles = [](uint32_t mask) {
    Json list = Json::array();
    for (uint32_t r = 0; r < TACTA_COLLISION_ROLE_COUNT; ++r)
      if (mask & (1u << r)) list.push_back(tacta_collision_role_name(1u << r));
    return list;
  };
  Json served_by = Json::object();
  for (uint32_t r = 0; r < TACTA_COLLISION_ROLE_COUNT; ++r) {
    std::string served;
    for (const CollisionPluginResult& p : s.collision_plugins)
      if (p.serves & (1u << r)) served = p.name;
    served_by[tacta_collision_role_name(1u << r)] = served;
  }
  Json plugins = Json::array();
  for (const CollisionPluginResult& p : s.collision_plugins)
    plugins.push_back({{"name", p.name},
                       {"declares", roles(p.roles)},
                       {"roles_guessed", p.roles_guessed},
                       {"serves", roles(p.serves)}});
  return Json{{"roles", served_by},
              {"plugins", plugins},
              {"capacity",
               {{"pairs", static_cast<uint64_t>(s.pairs_capacity)},
                {"pairs_max_used", static_cast<uint64_t>(s.pairs_high_water)},
                {"contacts", static_cast<uint64_t>(s.contacts_capacity)},
                {"contacts_max_used", static_cast<uint64_t>(s.contacts_high_water)}}},
              {"proxy_refits",
               {{"mode", s.proxy_sliced ? "sliced" : "every_tick"},
                {"slices", s.proxy_slices},
                {"whole", s.proxy_whole_refits},
                {"patch_gathers", s.patch_gathers},
                {"patch_upkeep_gathers", s.patch_upkeep_gathers},
                {"patch_queries", s.patch_queries},
                {"clear_answers", s.clear_answers},
                {"clear_bound_answers", s.clear_bound_answers}}},
              {"status", status_bits(s.collision)}};
}

Json body_entry(const World& world, const RunResult& result, size_t i) {
  const BodyResult& b = result.bodies[i];
  const SoftBody body = world.body(i);
  Json j = {{"name", b.name}, {"model", b.model}};
  // Only for bodies that came or went while the scene ran (scene events, Simulation::add_body).
  if (b.added_s >= 0) j["added_s"] = b.added_s;
  if (b.removed_s >= 0) j["removed_s"] = b.removed_s;
  if (b.pending) j["pending"] = true;
  // Every model the body ran, with the simulated time it took over (s): the scene's scheduled
  // swaps and the ones requested while running, in time order.
  std::vector<std::pair<double, std::string>> runs{
      {std::max(0.0, b.added_s), body.model.initial_model}};
  for (size_t s = 0; s < body.model.next_swap; ++s)
    runs.emplace_back(body.model.swaps[s].time_s, body.model.swaps[s].model_name);
  for (const RuntimeSwap& r : body.model.runtime_swaps) runs.emplace_back(r.time_s, r.model);
  std::stable_sort(runs.begin(), runs.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  Json& models_run = j["models_run"] = Json::array();
  for (const auto& [time, model] : runs) models_run.push_back({{"time_s", time}, {"model", model}});
  j["models_run_unlisted"] = body.model.runtime_swaps_unlisted;
  j["nodes"] = static_cast<uint64_t>(b.nodes);
  j["elements"] = static_cast<uint64_t>(b.elements);
  j["mesh"] = mesh_origin(b, body.shape.topology->load);
  j["model_notes"] = body.model.instance->describe();
  j["max_displacement_m"] = b.max_displacement_m;
  j["kinetic_energy_J"] = b.kinetic_energy_J;
  j["elastic_energy_J"] = b.elastic_energy_J;
  j["initial_energy_J"] = b.initial_energy_J;
  if (!b.model_counters.empty()) {
    Json& counters = j["model_counters"] = Json::object();
    for (const auto& [name, value] : b.model_counters) counters[name] = value;
  }
  if (const CutTotals& c = body.shape.cuts; c.revision > 0 || c.cuts_missed > 0)
    j["cuts"] = {
        {"revision", c.revision},
        {"tets_removed", c.tets_removed},
        {"nodes_removed", c.nodes_removed},
        {"nodes_added", c.nodes_added},
        {"faces_separated", c.faces_separated},
        {"blades_missed", c.cuts_missed},
        {"removed_mass_kg", c.removed_mass_kg},
        {"removed_energy_J", c.removed_energy_J},
        {"wall_ms_mean", c.wall_ms_total / static_cast<double>(c.revision + c.cuts_missed)},
        {"wall_ms_max", c.wall_ms_max},
        {"install_ms_max", body.shape.install_ms_max}};
  j["step_thread"] = b.own_thread ? "own" : "haptic";
  j["step_rate_hz"] = b.step_rate_hz;
  if (body.surface.mesh) {  // what the body was drawn, touched and collided through
    const EmbeddedSurface& s = *body.surface.mesh;
    j["surface"] = {{"source", s.source},
                    {"vertices", static_cast<uint64_t>(s.vertex_count())},
                    {"triangles", static_cast<uint64_t>(s.triangle_count())},
                    {"extrapolated_vertices", static_cast<uint64_t>(s.extrapolated_vertices)}};
  }
  if (b.own_thread) {
    j["worker"] = {{"steps", b.worker_steps},
                   {"step_ms",
                    {{"p50", b.worker_step_ms.p50_ms},
                     {"p99", b.worker_step_ms.p99_ms},
                     {"max", b.worker_step_ms.max_ms}}},
                   {"late_boundaries", b.late_boundaries},
                   {"max_lateness_s", b.max_lateness_s}};
  }
  // Probes at the end of the run: rest point, position and displacement, m.
  Json& probes = j["probes"] = Json::array();
  for (const Probe& probe : body.recording.probes) {
    const Vec3 x = probe.position(body.nodes.positions.data());
    probes.push_back({{"name", probe.name},
                      {"rest", probe.rest},
                      {"position", x},
                      {"displacement", Json::array({x[0] - probe.rest[0], x[1] - probe.rest[1],
                                                    x[2] - probe.rest[2]})}});
  }
  if (i < result.status.bodies.size()) j["status"] = status_bits(result.status.bodies[i]);
  Json& faults = j["faults"] = Json::array();
  if (b.frozen)
    faults.push_back({{"time_s", body.fault.time_s},
                      {"bits", static_cast<uint64_t>(body.fault.bits)},
                      {"reason", b.fault},
                      {"frozen", true}});
  return j;
}

Json device_entry(const World& world, const RunStatus& status, size_t d) {
  const DeviceLink& s = world.device(d).link;
  const DeviceStats& st = world.device(d).stats;
  Json j = {{"name", s.name},
            {"plugin", s.desc.plugin},
            {"max_force_N", st.max_force_N},
            {"force_limit_N", s.device->capabilities().peak_force},
            {"first_contact_peak_N", st.first_contact_peak_N},
            {"steady_contact_N", st.steady_contact_N},
            {"energy_injected_J", st.energy_injected_J},
            {"contact_ticks", st.contact_ticks},
            {"first_contact_time_s", st.first_contact_time_s},
            {"zero_force_ticks", st.zero_force_ticks},
            {"clamped_ticks", st.clamped_ticks},
            {"state", s.state == TACTA_DEVICE_CONNECTED      ? "connected"
                      : s.state == TACTA_DEVICE_FINISHED     ? "finished"
                      : s.state == TACTA_DEVICE_DISCONNECTED ? "disconnected"
                                                             : "fault"}};
  if (s.status_time_s >= 0) {
    j["status_time_s"] = s.status_time_s;
    j["status_reason"] = s.status_reason.data();
  }
  j["reconnections"] = st.reconnections;
  j["tool_changes"] = world.tool(d).revision;
  if (const DeviceStats& stats = world.device(d).stats; stats.held_blade)
    j["blade"] = {{"cuts", stats.blade_cuts},
                  {"cuts_refused", stats.blade_cuts_refused},
                  {"triangles_dropped", stats.blade_triangles_dropped}};
  if (d < status.devices.size()) j["status"] = status_bits(status.devices[d]);
  // The plugin's own figures (network devices: packets, drops, watchdog trips, round trip).
  const auto counters = s.device->counters();
  if (!counters.empty()) {
    Json& link = j["link"] = Json::object();
    for (const auto& [name, value] : counters) link[name] = value;
  }
  return j;
}

// Resident memory around the loop, and what the kernel granted the haptic thread (in lockstep
// nothing is asked for, and the note says so).
void add_realtime(Json& j, const RunResult& result) {
  const ScheduleResult& s = result.schedule;
  Json rss_every_10s = Json::array();
  for (size_t i = 0; i < s.rss_timeline.count; ++i) rss_every_10s.push_back(s.rss_timeline.kb[i]);
  j["memory_kb"] = {{"rss_start", s.memory_start.rss_kb},
                    {"rss_after_1s", s.memory_warm.rss_kb},
                    {"rss_end", s.memory_end.rss_kb},
                    {"peak", s.memory_end.peak_kb},
                    {"rss_every_10s", rss_every_10s}};
  const RealtimeGrant& g = s.realtime;
  j["realtime"] = {
      {"scheduler", g.scheduler},
      {"priority", g.priority},
      {"nice", g.nice},
      {"scheduler_note", g.scheduler_note},
      // A starving SCHED_FIFO thread is demoted mid-run (kStarvingTicks misses in a row).
      {"demoted_at_tick", g.demoted_at_tick},
      {"memory_locked", g.memory_locked},
      {"memory_note", g.memory_note},
      {"shallow_idle", g.shallow_idle},
      {"idle_note", g.idle_note},
      {"poll_idle", g.poll_idle},
      {"poll_note", g.poll_note},
      {"haptic_cpu", g.cpu},
      {"cpu_note", g.cpu_note},
      {"helper_threads_lowered", static_cast<uint64_t>(g.helper_threads_lowered)},
      {"spin_us", g.spin_us},
      {"timer_slack_ns", g.timer_slack_ns},
      // How each tick's wait ended: spun to the deadline (spin_us at work) or woken
      // past it.
      {"spun_waits", s.spun_waits},
      {"late_wakeups", s.late_wakeups}};
}

}  // namespace

void write_report_json(const std::string& dir, const HapticLoop& loop, const World& world,
                       RunResult& result) {
  const std::string path = dir + "/report.json";
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  Json j = {{"scene", result.scene},
            {"scene_name", world.scene().name},
            {"mode", result.mode},
            {"ticks", result.schedule.ticks},
            {"frames", result.schedule.frames},
            {"sim_time_s", result.sim_time_s},
            {"wall_time_s", result.schedule.wall_time_s},
            {"haptic_rate_hz", world.scene().clock.haptic_rate_hz},
            {"tick_ms", ticks(result.schedule.tick)}};
  // Where the tick's time goes: device read (and swaps), haptics (proxy, coupling, refit for its
  // queries), model steps, collision response, device write and records.
  const auto summary = [](const TickRecorder& r) {
    const TickSummary t = r.summary();
    return Json{{"mean", t.mean_ms}, {"p50", t.p50_ms}, {"p99", t.p99_ms}, {"max", t.max_ms}};
  };
  Json& breakdown = j["tick_breakdown_ms"] = Json::object();
  for (int s = 0; s < HapticLoop::kStageCount; ++s) {
    Json stage = summary(loop.stage(s));
    if (s == HapticLoop::kHaptics) {  // where the haptics stage goes: surfaces, queries, coupling
      Json& parts = stage["parts"] = Json::object();
      for (int p = 0; p < HapticLoop::kHapticPartCount; ++p)
        parts[HapticLoop::haptic_part_name(p)] = summary(loop.haptic_part(p));
    }
    breakdown[HapticLoop::stage_name(s)] = stage;
  }
  j["deadline_misses"] = result.schedule.deadline_misses;
  // Misses the engine's own work caused: ticks whose thread CPU time exceeded the period (the
  // other misses are time off the CPU: VM stalls, preemption, late wake-ups), after and during
  // the first second (start-up: cold caches, the first hierarchy build).
  j["over_budget_ticks"] = result.schedule.over_budget_ticks;
  Json& listed = j["over_budget_tick_indices"] = Json::array();
  for (uint64_t i = 0; i < std::min<uint64_t>(result.schedule.over_budget_ticks,
                                              ScheduleResult::kMaxListedOverBudget);
       ++i)
    listed.push_back(result.schedule.over_budget_tick_list[i]);
  j["warm_up_over_budget_ticks"] = result.schedule.warm_up_over_budget_ticks;
  j["max_tick_cpu_ms"] = result.schedule.max_tick_cpu_ms;
  j["max_start_jitter_ms"] = result.schedule.max_start_jitter_ms;
  j["stopped_early"] = result.schedule.stopped_early;
  add_realtime(j, result);
  Json& bodies = j["bodies"] = Json::array();
  for (size_t i = 0; i < result.bodies.size(); ++i) bodies.push_back(body_entry(world, result, i));
  Json& devices = j["devices"] = Json::array();
  for (size_t d = 0; d < world.device_count(); ++d)
    devices.push_back(device_entry(world, result.status, d));
  j["collision"] = collision(result.status);
  j["status_errors"] = static_cast<uint64_t>(result.status.errors);
  j["status_warnings"] = static_cast<uint64_t>(result.status.warnings);
  Json& faults = j["faults"] = Json::array();
  for (const FaultRecord& f : loop.faults().rows())
    faults.push_back({{"time_s", f.time_s},
                      {"body", f.body},
                      {"device", f.device},
                      {"bits", static_cast<uint64_t>(f.bits)},
                      {"reason", f.reason.data()}});
  j["dropped_records"] =
      loop.trace().dropped() + loop.trajectory().dropped() + loop.energy().dropped();
  j["dropped_faults"] = loop.faults().dropped();
  j["state_hash"] = result.state_hash;
  Json outputs = result.outputs;
  outputs.push_back(path);
  j["outputs"] = outputs;
  // NaN and infinities, which JSON cannot hold, are written as null; bytes that are not UTF-8
  // become U+FFFD.
  out << j.dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
  result.outputs.push_back(path);
}

}  // namespace tacta
