// report.json: what a run did, in one file a script can read (documented in docs/REPORT.md).
#include <algorithm>
#include <fstream>

#include "run_outputs.hpp"
#include "tacta/collision_api.h"
#include "tacta/json.hpp"

namespace tacta {

namespace {

void write_ticks(JsonWriter& j, const ScheduleResult& s) {
  j.key("tick_ms").begin_object();
  j.field("p50", s.tick.p50_ms).field("p99", s.tick.p99_ms).field("p999", s.tick.p999_ms);
  j.field("max", s.tick.max_ms).field("mean", s.tick.mean_ms);
  j.end_object();
}

// What the body's mesh source became: voxels (size, cells, volumes, pieces) or Gmsh tets, and
// every loader warning.
void write_mesh_origin(JsonWriter& j, const BodyResult& b, const LoadReport& load) {
  j.key("mesh").begin_object();
  j.field("summary", b.mesh).field("format", load.format);
  if (load.voxel_size > 0) {
    j.field("voxel_size_m", load.voxel_size)
        .field("voxel_cells", static_cast<uint64_t>(load.voxel_cells));
    j.field("thin_part_size_m", load.thin_part_size);
    j.field("surface_shells", static_cast<uint64_t>(load.shells));
    j.field("enclosed_volume_m3", load.enclosed_volume).field("volume_m3", load.mesh_volume);
    j.key("piece_volumes_m3").begin_array();
    for (double v : load.piece_volumes) j.value(v);
    j.end_array();
  }
  if (load.max_tets > 0) j.field("max_tets", static_cast<uint64_t>(load.max_tets));
  j.key("warnings").begin_array();
  for (const std::string& w : b.mesh_warnings) j.value(w);
  j.end_array();
  j.end_object();
}

// The status bits seen (docs/REPORT.md): name, value, severity, ticks, first time, remedy.
void write_status_bits(JsonWriter& j, const std::vector<StatusBitCount>& bits) {
  j.key("status").begin_array();
  for (const StatusBitCount& b : bits) {
    j.begin_object().field("bit", b.name).field("value", static_cast<uint64_t>(b.bit));
    j.field("severity", severity_name(b.severity))
        .field("ticks", b.ticks)
        .field("first_time_s", b.first_time_s);
    j.field("remedy", b.remedy).end_object();
  }
  j.end_array();
}

// Which plugin serves which role, each plugin's declared roles, and the buffers' use.
void write_collision(JsonWriter& j, const RunStatus& s) {
  const auto roles = [&](uint32_t mask) {
    j.begin_array();
    for (uint32_t r = 0; r < TACTA_COLLISION_ROLE_COUNT; ++r)
      if (mask & (1u << r)) j.value(tacta_collision_role_name(1u << r));
    j.end_array();
  };
  j.key("collision").begin_object();
  j.key("roles").begin_object();
  for (uint32_t r = 0; r < TACTA_COLLISION_ROLE_COUNT; ++r) {
    std::string served;
    for (const CollisionPluginResult& p : s.collision_plugins)
      if (p.serves & (1u << r)) served = p.name;
    j.field(tacta_collision_role_name(1u << r), served);
  }
  j.end_object();
  j.key("plugins").begin_array();
  for (const CollisionPluginResult& p : s.collision_plugins) {
    j.begin_object().field("name", p.name).key("declares");
    roles(p.roles);
    j.field("roles_guessed", p.roles_guessed).key("serves");
    roles(p.serves);
    j.end_object();
  }
  j.end_array();
  j.key("capacity").begin_object();
  j.field("pairs", static_cast<uint64_t>(s.pairs_capacity))
      .field("pairs_max_used", static_cast<uint64_t>(s.pairs_high_water));
  j.field("contacts", static_cast<uint64_t>(s.contacts_capacity));
  j.field("contacts_max_used", static_cast<uint64_t>(s.contacts_high_water));
  j.end_object();
  j.key("proxy_refits").begin_object();
  j.field("mode", s.proxy_sliced ? "sliced" : "every_tick");
  j.field("slices", s.proxy_slices).field("whole", s.proxy_whole_refits);
  j.end_object();
  write_status_bits(j, s.collision);
  j.end_object();
}

void write_bodies(JsonWriter& j, const World& world, const RunResult& result) {
  j.key("bodies").begin_array();
  for (size_t i = 0; i < result.bodies.size(); ++i) {
    const BodyResult& b = result.bodies[i];
    const SoftBody body = world.body(i);
    j.begin_object();
    j.field("name", b.name).field("model", b.model);
    // Only for bodies that came or went while the scene ran (scene events, Simulation::add_body).
    if (b.added_s >= 0) j.field("added_s", b.added_s);
    if (b.removed_s >= 0) j.field("removed_s", b.removed_s);
    if (b.pending) j.field("pending", true);
    // Every model the body ran, with the simulated time it took over (s): the scene's scheduled
    // swaps and the ones requested while running, in time order.
    std::vector<std::pair<double, std::string>> runs{
        {std::max(0.0, b.added_s), body.model.initial_model}};
    for (size_t s = 0; s < body.model.next_swap; ++s)
      runs.emplace_back(body.model.swaps[s].time_s, body.model.swaps[s].model_name);
    for (const RuntimeSwap& r : body.model.runtime_swaps) runs.emplace_back(r.time_s, r.model);
    std::stable_sort(runs.begin(), runs.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    j.key("models_run").begin_array();
    for (const auto& [time, model] : runs)
      j.begin_object().field("time_s", time).field("model", model).end_object();
    j.end_array();
    j.field("models_run_unlisted", body.model.runtime_swaps_unlisted);
    j.field("nodes", static_cast<uint64_t>(b.nodes))
        .field("elements", static_cast<uint64_t>(b.elements));
    write_mesh_origin(j, b, body.shape.topology->load);
    j.field("model_notes", body.model.instance->describe());
    j.field("max_displacement_m", b.max_displacement_m);
    j.field("kinetic_energy_J", b.kinetic_energy_J).field("elastic_energy_J", b.elastic_energy_J);
    j.field("initial_energy_J", b.initial_energy_J);
    if (!b.model_counters.empty()) {
      j.key("model_counters").begin_object();
      for (const auto& [name, value] : b.model_counters) j.field(name, value);
      j.end_object();
    }
    j.field("step_thread", b.own_thread ? "own" : "haptic").field("step_rate_hz", b.step_rate_hz);
    if (body.surface.mesh) {  // what the body was drawn, touched and collided through
      const EmbeddedSurface& s = *body.surface.mesh;
      j.key("surface").begin_object();
      j.field("source", s.source).field("vertices", static_cast<uint64_t>(s.vertex_count()));
      j.field("triangles", static_cast<uint64_t>(s.triangle_count()));
      j.field("extrapolated_vertices", static_cast<uint64_t>(s.extrapolated_vertices));
      j.end_object();
    }
    if (b.own_thread) {
      j.key("worker").begin_object();
      j.field("steps", b.worker_steps);
      j.key("step_ms").begin_object();
      j.field("p50", b.worker_step_ms.p50_ms)
          .field("p99", b.worker_step_ms.p99_ms)
          .field("max", b.worker_step_ms.max_ms);
      j.end_object();
      j.field("late_boundaries", b.late_boundaries).field("max_lateness_s", b.max_lateness_s);
      j.end_object();
    }
    // Probes at the end of the run: rest point, position and displacement, m.
    j.key("probes").begin_array();
    for (const Probe& probe : body.recording.probes) {
      const Vec3 x = probe.position(body.nodes.positions.data());
      j.begin_object().field("name", probe.name);
      j.key("rest").begin_array();
      for (double c : probe.rest) j.value(c);
      j.end_array().key("position").begin_array();
      for (double c : x) j.value(c);
      j.end_array().key("displacement").begin_array();
      for (size_t a = 0; a < 3; ++a) j.value(x[a] - probe.rest[a]);
      j.end_array().end_object();
    }
    j.end_array();
    if (i < result.status.bodies.size()) write_status_bits(j, result.status.bodies[i]);
    j.key("faults").begin_array();
    if (b.frozen) {
      j.begin_object();
      j.field("time_s", body.fault.time_s).field("bits", static_cast<uint64_t>(body.fault.bits));
      j.field("reason", b.fault).field("frozen", true);
      j.end_object();
    }
    j.end_array();
    j.end_object();
  }
  j.end_array();
}

void write_devices(JsonWriter& j, const World& world, const RunStatus& status) {
  j.key("devices").begin_array();
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceLink& s = world.device(d).link;
    const DeviceStats& st = world.device(d).stats;
    j.begin_object();
    j.field("name", s.name).field("plugin", s.desc.plugin);
    j.field("max_force_N", st.max_force_N);
    j.field("force_limit_N", s.device->capabilities().peak_force);
    j.field("first_contact_peak_N", st.first_contact_peak_N);
    j.field("steady_contact_N", st.steady_contact_N);
    j.field("energy_injected_J", st.energy_injected_J);
    j.field("contact_ticks", st.contact_ticks);
    j.field("first_contact_time_s", st.first_contact_time_s);
    j.field("zero_force_ticks", st.zero_force_ticks).field("clamped_ticks", st.clamped_ticks);
    j.field("state", s.state == TACTA_DEVICE_CONNECTED      ? "connected"
                     : s.state == TACTA_DEVICE_FINISHED     ? "finished"
                     : s.state == TACTA_DEVICE_DISCONNECTED ? "disconnected"
                                                            : "fault");
    if (s.status_time_s >= 0)
      j.field("status_time_s", s.status_time_s).field("status_reason", s.status_reason.data());
    j.field("reconnections", st.reconnections);
    j.field("tool_changes", world.tool(d).revision);
    if (d < status.devices.size()) write_status_bits(j, status.devices[d]);
    // The plugin's own figures (network devices: packets, drops, watchdog trips, round trip).
    const auto counters = s.device->counters();
    if (!counters.empty()) {
      j.key("link").begin_object();
      for (const auto& [name, value] : counters) j.field(name, value);
      j.end_object();
    }
    j.end_object();
  }
  j.end_array();
}

// Resident memory around the loop, and what the kernel granted the haptic thread (in lockstep
// nothing is asked for, and the note says so).
void write_realtime(JsonWriter& j, const RunResult& result) {
  const ScheduleResult& s = result.schedule;
  j.key("memory_kb").begin_object();
  j.field("rss_start", s.memory_start.rss_kb).field("rss_after_1s", s.memory_warm.rss_kb);
  j.field("rss_end", s.memory_end.rss_kb).field("peak", s.memory_end.peak_kb);
  j.key("rss_every_10s").begin_array();
  for (size_t i = 0; i < s.rss_timeline.count; ++i) j.value(s.rss_timeline.kb[i]);
  j.end_array();
  j.end_object();
  const RealtimeGrant& g = s.realtime;
  j.key("realtime").begin_object();
  j.field("scheduler", g.scheduler).field("priority", g.priority).field("nice", g.nice);
  j.field("scheduler_note", g.scheduler_note);
  // A starving SCHED_FIFO thread is demoted mid-run (kStarvingTicks misses in a row).
  j.field("demoted_at_tick", g.demoted_at_tick);
  j.field("memory_locked", g.memory_locked).field("memory_note", g.memory_note);
  j.field("shallow_idle", g.shallow_idle).field("idle_note", g.idle_note);
  j.field("haptic_cpu", g.cpu).field("cpu_note", g.cpu_note);
  j.field("helper_threads_lowered", static_cast<uint64_t>(g.helper_threads_lowered))
      .field("spin_us", g.spin_us);
  // How each tick's wait ended: spun to the deadline (spin_us at work) or woken past it.
  j.field("spun_waits", s.spun_waits).field("late_wakeups", s.late_wakeups);
  j.end_object();
}

}  // namespace

void write_report_json(const std::string& dir, const HapticLoop& loop, const World& world,
                       RunResult& result) {
  const std::string path = dir + "/report.json";
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  JsonWriter j(out);
  j.begin_object();
  j.field("scene", result.scene).field("scene_name", world.scene().name).field("mode", result.mode);
  j.field("ticks", result.schedule.ticks).field("frames", result.schedule.frames);
  j.field("sim_time_s", result.sim_time_s).field("wall_time_s", result.schedule.wall_time_s);
  j.field("haptic_rate_hz", world.scene().clock.haptic_rate_hz);
  write_ticks(j, result.schedule);
  // Where the tick's time goes: device read (and swaps), haptics (proxy, coupling, refit for its
  // queries), model steps, collision response, device write and records.
  j.key("tick_breakdown_ms").begin_object();
  const auto summary = [&](const TickRecorder& r) {
    const TickSummary t = r.summary();
    j.field("mean", t.mean_ms).field("p50", t.p50_ms).field("p99", t.p99_ms).field("max", t.max_ms);
  };
  for (int s = 0; s < HapticLoop::kStageCount; ++s) {
    j.key(HapticLoop::stage_name(s)).begin_object();
    summary(loop.stage(s));
    if (s == HapticLoop::kHaptics) {  // where the haptics stage goes: surfaces, queries, coupling
      j.key("parts").begin_object();
      for (int p = 0; p < HapticLoop::kHapticPartCount; ++p) {
        j.key(HapticLoop::haptic_part_name(p)).begin_object();
        summary(loop.haptic_part(p));
        j.end_object();
      }
      j.end_object();
    }
    j.end_object();
  }
  j.end_object();
  j.field("deadline_misses", result.schedule.deadline_misses);
  // Misses the engine's own work caused: ticks whose thread CPU time exceeded the period (the
  // other misses are time off the CPU: VM stalls, preemption, late wake-ups), after and during
  // the first second (start-up: cold caches, the first hierarchy build).
  j.field("over_budget_ticks", result.schedule.over_budget_ticks);
  j.field("warm_up_over_budget_ticks", result.schedule.warm_up_over_budget_ticks);
  j.field("max_tick_cpu_ms", result.schedule.max_tick_cpu_ms);
  j.field("max_start_jitter_ms", result.schedule.max_start_jitter_ms);
  j.field("stopped_early", result.schedule.stopped_early);
  write_realtime(j, result);
  write_bodies(j, world, result);
  write_devices(j, world, result.status);
  write_collision(j, result.status);
  j.field("status_errors", static_cast<uint64_t>(result.status.errors));
  j.field("status_warnings", static_cast<uint64_t>(result.status.warnings));
  j.key("faults").begin_array();
  for (const FaultRecord& f : loop.faults().rows()) {
    j.begin_object();
    j.field("time_s", f.time_s).field("body", f.body).field("device", f.device);
    j.field("bits", static_cast<uint64_t>(f.bits)).field("reason", f.reason.data());
    j.end_object();
  }
  j.end_array();
  j.field("dropped_records",
          loop.trace().dropped() + loop.trajectory().dropped() + loop.energy().dropped());
  j.field("dropped_faults", loop.faults().dropped());
  j.field("state_hash", result.state_hash);
  j.key("outputs").begin_array();
  for (const std::string& o : result.outputs) j.value(o);
  j.value(path);
  j.end_array();
  j.end_object();
  out << "\n";
  result.outputs.push_back(path);
}

}  // namespace tacta
