#include "systems/body_systems.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <optional>

namespace tacta {

namespace {

constexpr double kTimeSlack_s = 1e-12;  // s: a boundary due "now" despite rounding

void swap_models(BodyModel& model, const BodySettings& settings, NodeState& nodes, NodeLoads& loads,
                 double time, double haptic_dt) noexcept {
  const double dt = settings.step_dt(haptic_dt);
  while (model.next_swap < model.swaps.size() &&
         model.swaps[model.next_swap].time_s <= time + kTimeSlack_s) {
    // The scheduled instance was built at load time; the outgoing one is parked in its place
    // and destroyed with the world, so nothing is freed on the haptic thread.
    std::swap(model.instance, model.swaps[model.next_swap].model);
    ++model.next_swap;
    model.instance->begin(state_view(nodes, loads, time), dt);
  }
  ModelInstance* incoming = model.mailbox->incoming.exchange(nullptr, std::memory_order_acq_rel);
  if (incoming == nullptr) return;
  ModelInstance* outgoing = model.instance.release();
  model.instance.reset(incoming);
  ModelInstance* head = model.mailbox->retired.load(std::memory_order_relaxed);
  do {
    outgoing->retired_next = head;
  } while (!model.mailbox->retired.compare_exchange_weak(head, outgoing, std::memory_order_release,
                                                         std::memory_order_relaxed));
  if (model.runtime_swaps.size() < model.runtime_swaps.capacity())
    model.runtime_swaps.push_back({time, incoming->name()});
  else
    ++model.runtime_swaps_unlisted;
  model.instance->begin(state_view(nodes, loads, time), dt);
}

// A body on a worker: this tick's contact joins the period's impulse; at the body's boundary the
// finished step is collected, swaps are taken while the model is idle, and the next step posted.
bool step_on_worker(World& world, size_t body, BodyWorker& w, TickEvents& events, double time,
                    double dt) noexcept {
  const SoftBody b = world.body(body);
  w.accumulate(b.loads.contact_forces, dt);
  if (time + kTimeSlack_s < b.progress.next_step_s) return true;
  if (!w.finish_step(time)) return true;  // realtime: still stepping, render on the old state
  const StepOutcome& out = w.last_outcome();
  events.stepped(body, out.bits, time);
  if (out.why != nullptr) {
    // Detected on the tick the step is collected: the device force drops in this same tick.
    events.faulted(body, out.bits, out.why, time);
    return false;
  }
  swap_models(b.model, b.settings, b.nodes, b.loads, time,
              1.0 / world.scene().clock.haptic_rate_hz);
  w.post(time, b.settings.period_s);
  // The next boundary counts from this post: a late step shifts the body's clock, it never
  // makes the worker run two steps back to back.
  b.progress.next_step_s = std::max(b.progress.next_step_s + b.settings.period_s,
                                    time + b.settings.period_s - kTimeSlack_s);
  return true;
}

}  // namespace

void start_contact_sums(World& world) noexcept {
  world.bodies_in_scene<NodeLoads>().each([](ecs::Entity, InScene&, NodeLoads& loads) {
    if (loads.applied_forces.empty())
      std::fill(loads.contact_forces.begin(), loads.contact_forces.end(), 0.0);
    else
      std::copy(loads.applied_forces.begin(), loads.applied_forces.end(),
                loads.contact_forces.begin());
  });
}

void take_model_swaps(World& world, double time) noexcept {
  const double haptic_dt = 1.0 / world.scene().clock.haptic_rate_hz;
  world.bodies_in_scene<BodyModel, BodySettings, NodeState, NodeLoads>().each(
      [&](ecs::Entity, InScene&, BodyModel& model, BodySettings& settings, NodeState& nodes,
          NodeLoads& loads) {
        if (!settings.own_thread) swap_models(model, settings, nodes, loads, time, haptic_dt);
      });
}

namespace {

// A body due to step on the tick's thread this tick, and what its step gave.
struct DueStep {
  size_t body = 0;
  double dt = 0;  // s
  double divergence_limit_m = 0;
  ModelInstance* model = nullptr;
  const BodyTopology* topology = nullptr;
  StepArrays arrays;
  BoundaryMotion* boundary = nullptr;
  FaultState* fault = nullptr;
  StepProgress* progress = nullptr;
  StepOutcome out;
};

// The due bodies of one tick, stepped in groups of kGroup (on the stack: no allocation).
struct DueSteps {
  static constexpr size_t kGroup = 16;
  std::array<DueStep, kGroup> steps;
  std::array<uint32_t, kGroup> order;  // the slowest (its last step in a group) first
  size_t count = 0;
  Vec3 gravity{};
  double time = 0;  // s
};

void step_one(DueStep& d, const Vec3& gravity, double time, bool timed) noexcept {
  const auto start =
      timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  d.out = step_body_arrays(*d.model, *d.topology, gravity, d.divergence_limit_m, d.arrays, time,
                           d.dt, d.boundary);
  if (timed)
    d.progress->step_wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void step_due(void* user, uint32_t begin, uint32_t end, uint32_t) {
  auto& due = *static_cast<DueSteps*>(user);
  for (uint32_t i = begin; i < end; ++i)
    step_one(due.steps[due.order[i]], due.gravity, due.time, true);
}

// What a step gave, told to the tick's ledger. False when it faulted.
bool report_step(const DueStep& d, TickEvents& events, double time) noexcept {
  events.stepped(d.body, d.out.bits, time);
  if (d.out.why != nullptr) {
    events.faulted(d.body, d.out.bits, d.out.why, time);
    return false;
  }
  d.fault->max_displacement_m = std::max(d.fault->max_displacement_m, d.out.max_displacement);
  return true;
}

// Steps the group, one body per job on the scene's threads (a model's own parallel_for then
// runs serially inside its job, over the same fixed chunks; a group of one runs on the caller
// outside any job, so its model's parallel_for has the threads), the slowest last time first so
// the threads finish close together (the order changes no result), and reports them in body
// order.
bool step_group(World& world, DueSteps& due, TickEvents& events) noexcept {
  for (uint32_t i = 0; i < due.count; ++i) due.order[i] = i;
  // An insertion sort: std::stable_sort may allocate its buffer.
  const auto cost = [&](uint32_t i) { return due.steps[i].progress->step_wall_ms; };
  for (uint32_t i = 1; i < due.count; ++i)
    for (uint32_t j = i; j > 0 && cost(due.order[j]) > cost(due.order[j - 1]); --j)
      std::swap(due.order[j], due.order[j - 1]);
  world.jobs().parallel_for(static_cast<uint32_t>(due.count), 1, &step_due, &due);
  bool healthy = true;
  for (size_t i = 0; i < due.count; ++i)
    healthy = report_step(due.steps[i], events, due.time) && healthy;
  due.count = 0;
  return healthy;
}

}  // namespace

bool step_bodies(World& world, const std::vector<std::unique_ptr<BodyWorker>>& workers,
                 TickEvents& events, double time, double dt) noexcept {
  // With threads >= 2 the due bodies are gathered and stepped together; else each steps here.
  std::optional<DueSteps> group;
  if (world.threads() > 1) {
    group.emplace();
    group->gravity = world.scene().gravity;
    group->time = time;
  }
  bool healthy = true;
  world
      .bodies_in_scene<FaultState, BodySettings, StepProgress, BodyModel, RestShape, NodeState,
                       NodeLoads, BodyConstraints>()
      .each([&](ecs::Entity e, InScene&, FaultState& fault, const BodySettings& settings,
                StepProgress& progress, BodyModel& model, RestShape& shape, NodeState& nodes,
                NodeLoads& loads, BodyConstraints& constraints) {
        if (fault.frozen) return;
        const size_t body = e.index;
        if (BodyWorker* w = body < workers.size() ? workers[body].get() : nullptr) {
          healthy = step_on_worker(world, body, *w, events, time, dt) && healthy;
          return;
        }
        double step_dt = dt;
        if (settings.period_s > 0) {
          // A slower body steps once its own clock falls due, by its own period.
          if (time + kTimeSlack_s < progress.next_step_s) return;
          progress.next_step_s += settings.period_s;
          step_dt = settings.period_s;
        }
        DueStep d;
        d.body = body;
        d.dt = step_dt;
        d.divergence_limit_m = settings.divergence_limit_m;
        d.model = model.instance.get();
        d.topology = shape.topology.get();
        d.arrays = {nodes.positions, nodes.velocities, loads.external_forces, nodes.step_start,
                    loads.contact_forces};
        d.boundary = constraints.boundary.get();
        d.fault = &fault;
        d.progress = &progress;
        if (!group) {
          step_one(d, world.scene().gravity, time, false);
          healthy = report_step(d, events, time) && healthy;
          return;
        }
        if (group->count == DueSteps::kGroup)
          healthy = step_group(world, *group, events) && healthy;
        group->steps[group->count++] = d;
      });
  if (group && group->count > 0) healthy = step_group(world, *group, events) && healthy;
  return healthy;
}

void record_bodies(World& world, double time, Recorder<TrajectoryRow>& trajectory,
                   Recorder<ProbeRow>& probes) noexcept {
  world.bodies_in_scene<NodeState, Recording>().each(
      [&](ecs::Entity e, InScene&, NodeState& nodes, Recording& recording) {
        const auto body = static_cast<uint32_t>(e.index);
        for (uint32_t n : recording.recorded_nodes) {
          TrajectoryRow row{time, body, n, {}, {}};
          for (int a = 0; a < 3; ++a) {
            row.x[a] = nodes.positions[3 * n + a];
            row.v[a] = nodes.velocities[3 * n + a];
          }
          trajectory.push(row);
        }
        for (size_t p = 0; p < recording.probes.size(); ++p) {
          const Vec3 x = recording.probes[p].position(nodes.positions.data());
          probes.push({time, body, static_cast<uint32_t>(p), {x[0], x[1], x[2]}});
        }
      });
}

}  // namespace tacta
