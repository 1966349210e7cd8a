// Everything around the bodies: tool and obstacle shapes, devices, obstacles, the collision
// pipeline and timed model swaps.
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <string>

#include "scene/did_you_mean.hpp"
#include "scene/plugin_params.hpp"
#include "scene/section_readers.hpp"
#include "tacta/vec3.hpp"

namespace tacta::scene_detail {

namespace {

std::vector<std::string> body_names(const std::vector<BodyDesc>& bodies) {
  std::vector<std::string> names;
  for (const BodyDesc& body : bodies) names.push_back(body.name);
  return names;
}

// A body name that must exist; `wildcard_allowed` also accepts "*".
std::string read_body_name(const Field& field, const std::vector<BodyDesc>& bodies,
                           bool wildcard_allowed) {
  const std::string name = field.text();
  if (wildcard_allowed && name == "*") return name;
  for (const BodyDesc& body : bodies)
    if (body.name == name) return name;
  std::vector<std::string> names = body_names(bodies);
  if (wildcard_allowed) names.insert(names.begin(), "*");
  field.fail(unknown_name_message("body", name, names));
}

void read_position(const Field& shape, ShapeDesc& out) {
  if (auto f = shape.get("position")) out.position = f->vec3();
}

}  // namespace

CutMode read_cut_mode(const Field& field) {
  CutMode mode = CutMode::kSeparate;
  parse_cut_mode(field.choice({cut_mode_name(CutMode::kRemove), cut_mode_name(CutMode::kSeparate)}),
                 mode);
  return mode;
}

// `blade: {edge: [[x, y, z], [x, y, z]], button, mode, interval}` (device frame, m; s).
BladeDesc read_blade(const Field& field) {
  field.expect_map(
      "a map {edge: [[x, y, z], [x, y, z]] (m, device frame), button, mode: separate | remove, "
      "interval (s)}");
  field.check_keys({"edge", "button", "mode", "interval"});
  BladeDesc blade;
  blade.where = field.where();
  if (auto f = field.get("edge")) {
    const std::vector<Field> ends =
        f->items("the blade's two end points [[x, y, z], [x, y, z]] (m)");
    if (ends.size() != 2) f->fail_expected("two end points [[x, y, z], [x, y, z]] (m)");
    blade.edge = {ends[0].vec3(), ends[1].vec3()};
    if (!(norm(sub(blade.edge[1], blade.edge[0])) > 0))
      f->fail_expected("two different end points (a blade of length > 0)");
  }
  if (auto f = field.get("button")) blade.button = static_cast<uint32_t>(f->integer(0, 31));
  if (auto f = field.get("mode")) blade.mode = read_cut_mode(*f);
  // Past a second, a cut lags the hand too far to follow it; 1 ms is a cut at every tick.
  if (auto f = field.get("interval")) blade.interval_s = f->real(Range::closed(0.001, 1.0));
  return blade;
}

ShapeDesc read_shape(const Field& field, bool tool) {
  field.expect_map(tool ? "a tool: a map with one of sphere, capsule, box, plane, mesh, and blade "
                          "when it cuts"
                        : "a shape: a map with one of sphere, capsule, box, plane, mesh");
  if (tool)
    field.check_keys({"sphere", "capsule", "box", "plane", "mesh", "blade"});
  else
    field.check_keys({"sphere", "capsule", "box", "plane", "mesh"});
  const std::string kind = exactly_one_of(field, {"sphere", "capsule", "box", "plane", "mesh"});
  const Field body = field.require(kind);
  ShapeDesc shape;
  if (kind == "sphere") {
    shape.kind = ShapeDesc::Kind::Sphere;
    body.expect_map("a map {radius, position}");
    body.check_keys({"radius", "position"});
    if (auto f = body.get("radius")) shape.radius = f->real(Range::positive());
  } else if (kind == "capsule") {
    shape.kind = ShapeDesc::Kind::Capsule;
    body.expect_map("a map {radius, half_length, position}");
    body.check_keys({"radius", "half_length", "position"});
    if (auto f = body.get("radius")) shape.radius = f->real(Range::positive());
    if (auto f = body.get("half_length")) shape.half_length = f->real(Range::positive());
  } else if (kind == "box") {
    shape.kind = ShapeDesc::Kind::Box;
    body.expect_map("a map {half_extents, position}");
    body.check_keys({"half_extents", "position"});
    if (auto f = body.get("half_extents")) shape.half_extents = f->vec3(Range::positive());
  } else if (kind == "plane") {
    shape.kind = ShapeDesc::Kind::Plane;
    body.expect_map("a map {normal, offset}");
    body.check_keys({"normal", "offset"});
    if (auto f = body.get("normal")) {
      const Vec3 n = f->vec3();
      const double length = norm(n);
      if (!(length > 0)) f->fail_expected("a non-zero normal vector");
      shape.normal = {n[0] / length, n[1] / length, n[2] / length};  // stored unit length
    }
    if (auto f = body.get("offset")) shape.offset = f->real();
  } else {
    shape.kind = ShapeDesc::Kind::Mesh;
    body.expect_map("a map {file, position}");
    body.check_keys({"file", "position"});
    const Field file = body.require("file");
    shape.path = file.file_path();
    shape.path_where = file.where();
  }
  if (kind != "plane") read_position(body, shape);
  if (auto f = field.get("blade"); f && tool) shape.blade = read_blade(*f);
  return shape;
}

DeviceDesc read_device(const Field& field, const std::vector<BodyDesc>& bodies) {
  field.expect_map(
      "a device: a map {name, plugin, params, tool, coupling, touches, stream_surface}");
  field.check_keys({"name", "plugin", "params", "tool", "coupling", "touches", "stream_surface"});
  DeviceDesc device;
  device.where = field.where();
  device.name = field.require("name").text();
  std::optional<Field> params = field.get("params");
  if (params) params->expect_map("a map of the device plugin's parameters");
  PluginRef plugin = read_plugin(field.require("plugin"), TACTA_KIND_DEVICE, params);
  device.plugin = std::move(plugin.name);
  device.params = std::move(plugin.params);
  if (auto f = field.get("tool")) device.tool = read_shape(*f, true);
  if (auto f = field.get("coupling")) {
    f->expect_map("a map {stiffness, damping, passivity, first_contact}");
    f->check_keys({"stiffness", "damping", "passivity", "first_contact"});
    if (auto k = f->get("stiffness")) device.coupling_stiffness = k->real(Range::positive());
    if (auto b = f->get("damping")) device.coupling_damping = b->real(Range::non_negative());
    if (auto p = f->get("passivity")) device.coupling_passivity = p->boolean();
    if (auto o = f->get("first_contact")) device.coupling_first_contact = o->boolean();
  }
  if (auto f = field.get("touches")) device.touches = read_body_name(*f, bodies, false);
  if (auto f = field.get("stream_surface"))
    device.stream_simulation_surface = f->choice({"embedded", "simulation"}) == "simulation";
  return device;
}

ObstacleDesc read_obstacle(const Field& field) {
  field.expect_map("an obstacle: a map {name, shape}");
  field.check_keys({"name", "shape"});
  ObstacleDesc obstacle;
  obstacle.name = field.require("name").text();
  obstacle.shape = read_shape(field.require("shape"));
  return obstacle;
}

CollisionDesc read_collision(const Field& field) {
  field.expect_map("a map {enabled, broad_phase, narrow_phase, convex, friction, ...}");
  field.check_keys({"enabled", "broad_phase", "narrow_phase", "convex", "plugins", "friction",
                    "self_collision", "thickness", "proxy_refit"});
  CollisionDesc collision;
  collision.enabled = true;  // writing the section turns collision on unless it says otherwise
  if (auto f = field.get("enabled")) collision.enabled = f->boolean();
  // Friction is one coefficient per scene (docs/SCENES.md, `collision.friction`): written as
  // `collision.friction` or as a collision plugin's own `friction` parameter. The plugin parameter
  // written in the scene sets it when `collision.friction` is not written; both written with
  // different values is refused here, naming both, rather than one silently replacing the other.
  std::optional<Field> scene_friction = field.get("friction");
  std::optional<Field> plugin_friction;  // the first plugin map that writes `friction`
  const auto refuse_if_different = [](const Field& here, double value, const Field& other) {
    const double first = other.real(Range::non_negative());
    if (value != first)
      here.fail(fmt::format(
          "friction is given twice with different values: {:g} here and {:g} at {} (line {}); "
          "the scene has one Coulomb coefficient, so write it once (collision.friction, or the "
          "plugin's friction parameter)",
          value, first, other.path(), other.where().line));
  };
  const auto note_plugin_friction = [&](const Field& plugin_field) {
    if (!plugin_field.is_map()) return;
    auto f = plugin_field.get("friction");
    if (!f) return;
    const double value = f->real(Range::non_negative());
    if (scene_friction) refuse_if_different(*f, value, *scene_friction);
    if (plugin_friction)
      refuse_if_different(*f, value, *plugin_friction);
    else
      plugin_friction = *f;
  };
  const auto stage = [&](const char* key, std::string& name, ParamSet& params) {
    if (auto f = field.get(key)) {
      PluginRef plugin = read_plugin(*f, TACTA_KIND_COLLISION, std::nullopt, collision.enabled);
      name = std::move(plugin.name);
      params = std::move(plugin.params);
      note_plugin_friction(*f);
    } else if (collision.enabled) {
      // The default plugin is still checked, with its defaults, when collision is on.
      Field implicit(field.context(), YAML::Node(name), child_path(field.path(), key),
                     field.yaml().Mark());
      params = read_plugin(implicit, TACTA_KIND_COLLISION).params;
    }
  };
  stage("broad_phase", collision.broad_phase, collision.broad_params);
  stage("narrow_phase", collision.narrow_phase, collision.narrow_params);
  stage("convex", collision.convex, collision.convex_params);
  if (auto f = field.get("plugins")) {
    // Whether each plugin declares its role is checked when the pipeline is built (its roles are
    // in the plugin's function table), at this key's file and line.
    static constexpr const char* kRoles[] = {"broad_phase", "proxy", "narrow_phase", "response"};
    f->expect_map("a map {broad_phase, proxy, narrow_phase, response} of collision plugin names");
    f->check_keys({kRoles[0], kRoles[1], kRoles[2], kRoles[3]});
    for (size_t r = 0; r < 4; ++r) {
      if (auto role = f->get(kRoles[r])) {
        PluginRef plugin =
            read_plugin(*role, TACTA_KIND_COLLISION, std::nullopt, collision.enabled);
        collision.role_plugins[r] = std::move(plugin.name);
        collision.role_params[r] = std::move(plugin.params);
        collision.role_where[r] = role->where();
        note_plugin_friction(*role);
      }
    }
  }
  if (scene_friction)
    collision.friction = scene_friction->real(Range::non_negative());
  else if (plugin_friction)
    collision.friction = plugin_friction->real(Range::non_negative());
  if (auto f = field.get("self_collision")) collision.self_collision = f->boolean();
  if (auto f = field.get("proxy_refit"))
    collision.proxy_refit_sliced = f->choice({"sliced", "every_tick"}) == "sliced";
  collision.thickness_where = field.where();
  collision.thickness_where.key_path = child_path(field.path(), "thickness");
  if (auto f = field.get("thickness")) {
    collision.thickness = f->real(Range::non_negative());
    collision.thickness_where = f->where();
  }
  return collision;
}

SwapDesc read_swap(const Field& field, const std::vector<BodyDesc>& bodies) {
  field.expect_map("a swap: a map {time, body, model}");
  field.check_keys({"time", "body", "model"});
  SwapDesc swap;
  swap.time = field.require("time").real(Range::non_negative());
  swap.body = read_body_name(field.require("body"), bodies, true);
  PluginRef model = read_plugin(field.require("model"), TACTA_KIND_MODEL);
  swap.model = std::move(model.name);
  swap.params = std::move(model.params);
  return swap;
}

}  // namespace tacta::scene_detail
