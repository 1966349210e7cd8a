// The scene loader's entry points and top level: clock, outputs, and the sections in order.
#include "tacta/scene_loader.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sched.h>
#include <sstream>
#include <thread>
#include <unistd.h>

#include "scene/did_you_mean.hpp"
#include "scene/overrides.hpp"
#include "scene/section_readers.hpp"

namespace tacta {

std::string duration_limit_problem(double duration_s, double haptic_rate_hz, size_t devices) {
  const double rows_per_tick = static_cast<double>(std::max<size_t>(devices, 1));
  const double ticks = duration_s * haptic_rate_hz;
  if (ticks * rows_per_tick <= static_cast<double>(kMaxRunTicks)) return {};
  const double longest_s = static_cast<double>(kMaxRunTicks) / rows_per_tick / haptic_rate_hz;
  return fmt::format(
      "a duration of {:g} s at {:g} Hz is {:.3g} haptic ticks{}; at most {} are allowed ({:g} s "
      "here), because the "
      "run's per-tick records (trace, tick timings, ~150 bytes a tick) are reserved before it "
      "starts so that the "
      "haptic loop never allocates",
      duration_s, haptic_rate_hz, ticks,
      devices > 1 ? fmt::format(" x {} devices = {:.3g} trace rows", devices, ticks * rows_per_tick)
                  : std::string(),
      devices > 1 ? "3600000 trace rows" : "3600000 ticks", longest_s);
}

namespace scene_detail {

ClockDesc read_clock(const Field& field) {
  field.expect_map(
      "a map {mode, haptic_rate_hz, render_rate_hz, duration_s, haptic_priority, ...}");
  field.check_keys({"mode", "haptic_rate_hz", "render_rate_hz", "duration_s", "haptic_priority",
                    "haptic_cpu", "lock_memory", "spin_us", "shallow_idle", "poll_idle", "resume"});
  ClockDesc clock;
  if (auto f = field.get("mode"))
    clock.mode = f->choice({"lockstep", "realtime"}) == "realtime" ? ClockDesc::Mode::Realtime
                                                                   : ClockDesc::Mode::Lockstep;
  // Upper bounds: 100 kHz is beyond any haptic device; 1 kHz beyond any display.
  if (auto f = field.get("haptic_rate_hz")) clock.haptic_rate_hz = f->real({0, 1e5, true, false});
  if (auto f = field.get("render_rate_hz")) {
    clock.render_rate_hz = f->real({0, 1e3, true, false});
    if (clock.render_rate_hz > clock.haptic_rate_hz)
      f->fail_expected("a render rate <= the haptic rate (" + std::to_string(clock.haptic_rate_hz) +
                       " Hz): frames are taken between haptic ticks");
  }
  if (auto f = field.get("duration_s")) {
    clock.duration_s = f->real(Range::positive());
    if (const std::string problem = duration_limit_problem(clock.duration_s, clock.haptic_rate_hz);
        !problem.empty())
      f->fail(problem);
  }
  if (auto f = field.get("haptic_priority"))
    clock.haptic_priority = static_cast<int>(f->integer(0, 99));
  if (auto f = field.get("haptic_cpu")) {
    const long cpus = sysconf(_SC_NPROCESSORS_CONF);
    clock.haptic_cpu = static_cast<int>(f->integer(-1, cpus > 0 ? cpus - 1 : 1023));
  }
  if (auto f = field.get("lock_memory")) clock.lock_memory = f->boolean();
  if (auto f = field.get("shallow_idle")) clock.shallow_idle = f->boolean();
  if (auto f = field.get("poll_idle")) clock.poll_idle = f->boolean();
  // 1 ms: a whole 1 kHz period; a longer spin would only burn the CPU.
  if (auto f = field.get("spin_us")) clock.spin_us = f->real(Range::closed(0, 1000));
  if (auto f = field.get("resume")) {
    clock.resume = f->file_path();
    std::error_code error;
    if (!std::filesystem::is_regular_file(clock.resume, error))
      f->fail("no checkpoint file at " + clock.resume);
  }
  return clock;
}

OutputDesc read_output(const Field& field) {
  field.expect_map("a map {frames, frame_times, frame_size, vtk, trace, plots, ...}");
  field.check_keys({"frames", "frame_times", "frame_size", "vtk", "vtk_interval_s", "trace",
                    "trajectory", "record_interval_s", "plots", "plot_nodes"});
  OutputDesc output;
  if (auto f = field.get("frames")) output.frames = f->boolean();
  if (auto f = field.get("frame_times")) output.frame_times = f->reals(0, Range::non_negative());
  if (auto f = field.get("frame_size")) {
    const std::vector<Field> items = f->items("a list [width, height] in pixels");
    if (items.size() != 2) f->fail_expected("a list [width, height] in pixels");
    // Bounded here as the renderer bounds it, so a scene is not refused only when its first frame is drawn.
    const auto side = [](const Field& item) {
      const int64_t pixels = item.integer(1, INT32_MAX);
      if (pixels > kMaxFrameSide)
        item.fail_expected(
            fmt::format("pixels in [1, {}] (the off-screen renderer's largest framebuffer; "
                        "an 8192 x 8192 picture is already 256 MB)",
                        kMaxFrameSide));
      return static_cast<int>(pixels);
    };
    output.frame_width = side(items[0]);
    output.frame_height = side(items[1]);
  }
  if (auto f = field.get("vtk")) output.vtk = f->boolean();
  if (auto f = field.get("vtk_interval_s")) output.vtk_interval_s = f->real(Range::positive());
  if (auto f = field.get("trace")) output.trace = f->boolean();
  if (auto f = field.get("trajectory")) output.trajectory = f->boolean();
  if (auto f = field.get("record_interval_s"))
    output.record_interval_s = f->real(Range::non_negative());
  if (auto f = field.get("plots"))
    for (const Field& item : f->items("a list of plot names"))
      output.plots.push_back(item.choice({"phase_portrait", "force", "energy", "displacement"}));
  if (auto f = field.get("plot_nodes")) output.plot_nodes = f->indices();
  return output;
}

void check_unique(const std::vector<Field>& items, const std::vector<std::string>& names,
                  const char* what) {
  for (size_t i = 0; i < names.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (names[i] == names[j])
        items[i].require("name").fail(std::string("duplicate ") + what + " name '" + names[i] +
                                      "' (first used by " + items[j].path() + ")");
}

namespace {

namespace {
// 64: past any core count a workstation running a haptic loop has. `auto`: the CPUs this
// process may run on (its affinity mask, so taskset and cgroup cpusets count), less the one the
// haptic thread uses; at least 1.
uint32_t read_threads(const Field& f) {
  constexpr int64_t kMaxThreads = 64;
  if (!f.is_scalar() || f.yaml().Scalar() != "auto") {
    if (f.is_scalar() && !f.yaml().Scalar().empty() &&
        std::isalpha(static_cast<unsigned char>(f.yaml().Scalar()[0])))
      f.fail_expected("an integer in [1, 64] or auto");
    return static_cast<uint32_t>(f.integer(1, kMaxThreads));
  }
  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  const int64_t count = sched_getaffinity(0, sizeof cpus, &cpus) == 0
                            ? CPU_COUNT(&cpus)
                            : static_cast<int64_t>(std::thread::hardware_concurrency());
  return static_cast<uint32_t>(std::clamp<int64_t>(count - 1, 1, kMaxThreads));
}
}  // namespace

SceneDesc read_scene(const Field& root) {
  root.expect_map("a scene: a map with keys name, gravity, clock, bodies, ...");
  root.check_keys({"name", "gravity", "seed", "threads", "clock", "bodies", "devices", "obstacles",
                   "collision", "swaps", "output", "events", "capacity"});
  SceneDesc scene;
  scene.name = std::filesystem::path(root.context().file).stem().string();
  if (auto f = root.get("name")) scene.name = f->text();
  if (auto f = root.get("gravity")) scene.gravity = f->vec3();
  if (auto f = root.get("seed")) scene.seed = static_cast<uint64_t>(f->integer(0, INT64_MAX));
  if (auto f = root.get("threads")) scene.threads = read_threads(*f);
  if (auto f = root.get("clock")) scene.clock = read_clock(*f);

  const Field bodies = root.require("bodies");
  const std::vector<Field> body_items = bodies.items("a list of bodies");
  if (body_items.empty()) bodies.fail_expected("at least one body");
  std::vector<std::string> names;
  for (const Field& item : body_items) {
    scene.bodies.push_back(read_body(item));
    names.push_back(scene.bodies.back().name);
  }
  check_unique(body_items, names, "body");

  if (auto f = root.get("devices")) {
    const std::vector<Field> items = f->items("a list of devices");
    names.clear();
    for (const Field& item : items) {
      scene.devices.push_back(read_device(item, scene.bodies));
      names.push_back(scene.devices.back().name);
    }
    check_unique(items, names, "device");
  }
  if (auto f = root.get("obstacles")) {
    const std::vector<Field> items = f->items("a list of obstacles");
    names.clear();
    for (const Field& item : items) {
      scene.obstacles.push_back(read_obstacle(item));
      names.push_back(scene.obstacles.back().name);
    }
    check_unique(items, names, "obstacle");
  }
  if (scene.devices.size() > 1)  // one trace row per device per tick: the bound tightens
    if (auto clock = root.get("clock"))
      if (auto f = clock->get("duration_s"))
        if (const std::string problem = duration_limit_problem(
                scene.clock.duration_s, scene.clock.haptic_rate_hz, scene.devices.size());
            !problem.empty())
          f->fail(problem);
  if (auto f = root.get("collision")) scene.collision = read_collision(*f);
  if (auto f = root.get("swaps"))
    for (const Field& item : f->items("a list of swaps {time, body, model}"))
      scene.swaps.push_back(read_swap(item, scene.bodies));
  if (auto f = root.get("output")) scene.output = read_output(*f);
  if (auto f = root.get("events")) read_events(*f, body_items, scene);
  if (auto f = root.get("capacity")) {
    f->expect_map("a map {bodies}");
    f->check_keys({"bodies"});
    // 4096: far past what a haptic scene steps at 1 kHz; each slot is reserved at load.
    if (auto b = f->get("bodies")) {
      scene.body_capacity = static_cast<uint32_t>(b->integer(1, 4096));
      size_t needed = scene.bodies.size();
      for (const BodyEventDesc& e : scene.events) needed += e.add ? 1 : 0;
      if (scene.body_capacity < needed)
        b->fail_expected("at least " + std::to_string(needed) +
                         " (the scene's bodies and the bodies its events add)");
    }
  }
  return scene;
}

SourceLocation location_of(const std::string& file, const YAML::Mark& mark) {
  SourceLocation where{file, 0, 0, ""};
  if (!mark.is_null()) {
    where.line = mark.line + 1;
    where.column = mark.column + 1;
  }
  return where;
}

}  // namespace
}  // namespace scene_detail

namespace scene_detail {
namespace {

// Parses `text` and hands its root to `read` with a context anchored at `virtual_path`; YAML
// errors become InputErrors at their mark.
template <class Read>
auto read_text(const std::string& text, const std::string& virtual_path,
               const SchemaLookup& schemas, Read&& read) {
  LoadContext context;
  context.file = virtual_path;
  context.directory = std::filesystem::absolute(virtual_path).parent_path().lexically_normal();
  context.schemas = &schemas;
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(location_of(virtual_path, e.mark), "YAML syntax error: " + e.msg);
  }
  try {
    return read(context, root);
  } catch (const YAML::Exception& e) {
    // yaml-cpp itself should not throw once parsed; report it at its mark rather than crash.
    throw InputError(location_of(virtual_path, e.mark), "malformed YAML: " + e.msg);
  }
}

}  // namespace
}  // namespace scene_detail

SceneDesc load_scene_from_string(const std::string& text, const std::string& virtual_path,
                                 const SchemaLookup& schemas,
                                 const std::vector<std::string>& overrides) {
  using namespace scene_detail;
  return read_text(text, virtual_path, schemas, [&](LoadContext& context, YAML::Node& root) {
    apply_overrides(root, overrides, context.overrides);
    SceneDesc scene = read_scene(Field(context, root, "", YAML::Mark::null_mark()));
    scene.path = virtual_path;
    scene.directory = context.directory.string();
    return scene;
  });
}

BodyDesc load_body_from_string(const std::string& text, const std::string& virtual_path,
                               const SchemaLookup& schemas) {
  using namespace scene_detail;
  return read_text(text, virtual_path, schemas, [](LoadContext& context, YAML::Node& root) {
    return read_body(Field(context, root, "", YAML::Mark::null_mark()));
  });
}

ShapeDesc load_shape_from_string(const std::string& text, const std::string& virtual_path,
                                 const SchemaLookup& schemas) {
  using namespace scene_detail;
  return read_text(text, virtual_path, schemas, [](LoadContext& context, YAML::Node& root) {
    return read_shape(Field(context, root, "", YAML::Mark::null_mark()), true);
  });
}

SceneDesc load_scene(const std::string& path, const SchemaLookup& schemas,
                     const std::vector<std::string>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLocation{path, 0, 0, ""}, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(SourceLocation{path, 0, 0, ""}, "cannot read the scene file");
  return load_scene_from_string(text.str(), path, schemas, overrides);
}

}  // namespace tacta
