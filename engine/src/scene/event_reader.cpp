// The scene's `events`: bodies added and removed, tools changed and cuts made while it runs.
#include <algorithm>

#include "scene/did_you_mean.hpp"
#include "scene/section_readers.hpp"

namespace tacta::scene_detail {

namespace {

// One cut event's blade, at most this many triangles: a scripted incision needs tens, and a
// cut's cost grows with its triangles times the tets near each.
constexpr size_t kMaxCutTriangles = 10'000;

// The body `field` names, which must be one of `names` (the scene's and the events' adds).
std::string known_body(const Field& field, const std::vector<std::string>& names) {
  const std::string name = field.text();
  if (std::find(names.begin(), names.end(), name) != names.end()) return name;
  std::string message =
      "no body named '" + name + "' among the scene's bodies and the events' adds";
  if (auto hint = closest_match(name, names)) message += "; did you mean '" + *hint + "'?";
  field.fail(message);
  return name;
}

// `change_tool: {device, tool}`: the device must be one of the scene's.
ToolChangeDesc read_tool_change(const Field& field, const std::vector<DeviceDesc>& devices) {
  field.expect_map("a map {device: device name, tool: a shape}");
  field.check_keys({"device", "tool"});
  ToolChangeDesc change;
  const Field device = field.require("device");
  change.device = device.text();
  if (std::none_of(devices.begin(), devices.end(),
                   [&](const DeviceDesc& d) { return d.name == change.device; }))
    device.fail("no device named '" + change.device + "' among the scene's devices");
  change.tool = read_shape(field.require("tool"), true);
  return change;
}

// `cut: {body, mode, triangles | quad}`: the blade's swept surface as points [x, y, z] (m, world
// frame), three per triangle, or a quad p0 p1 p2 p3 read as the triangles (p0, p1, p2), (p0, p2, p3).
CutEventDesc read_cut(const Field& field, const std::vector<std::string>& bodies) {
  field.expect_map(
      "a map {body: body name, mode: remove | separate, triangles: [[x, y, z], ...] (3 points a "
      "triangle) or quad: [[x, y, z] x 4]}");
  field.check_keys({"body", "mode", "triangles", "quad"});
  CutEventDesc cut;
  cut.where = field.where();
  cut.body = known_body(field.require("body"), bodies);
  if (auto f = field.get("mode")) cut.mode = read_cut_mode(*f);
  const std::string key = exactly_one_of(field, {"triangles", "quad"});
  const Field blade = field.require(key);
  const std::vector<Field> points = blade.items("a list of points [x, y, z]");
  if (key == "quad" && points.size() != 4)
    blade.fail_expected("4 points [x, y, z] (a quad p0 p1 p2 p3), found " +
                        std::to_string(points.size()));
  if (key == "triangles" && (points.empty() || points.size() % 3 != 0))
    blade.fail_expected("points [x, y, z], 3 per triangle (a positive multiple of 3), found " +
                        std::to_string(points.size()));
  if (points.size() / 3 > kMaxCutTriangles)
    blade.fail_expected("at most " + std::to_string(kMaxCutTriangles) + " triangles, found " +
                        std::to_string(points.size() / 3));
  std::vector<Vec3> corners;
  for (const Field& point : points) corners.push_back(point.vec3());
  if (key == "quad")
    corners = {corners[0], corners[1], corners[2], corners[0], corners[2], corners[3]};
  for (const Vec3& c : corners) cut.triangles.insert(cut.triangles.end(), c.begin(), c.end());
  return cut;
}

}  // namespace

// Bodies entering ({time, add: {a body}}) or leaving ({time, remove: name}), tools changed
// ({time, change_tool: {device, tool}}) and cuts ({time, cut: {body, ...}}), kept in time order.
// Names stay unique across bodies and added ones.
void read_events(const Field& field, const std::vector<Field>& body_items, SceneDesc& scene) {
  std::vector<Field> named = body_items;
  std::vector<std::string> names;
  for (const BodyDesc& b : scene.bodies) names.push_back(b.name);
  for (const Field& item :
       field.items("a list of events {time, add | remove | change_tool | cut}")) {
    item.expect_map(
        "an event: a map {time, add: {a body}}, {time, remove: body name}, {time, change_tool: "
        "{device, tool}} or {time, cut: {body, mode, triangles}}");
    item.check_keys({"time", "add", "remove", "change_tool", "cut"});
    BodyEventDesc event;
    event.time = item.require("time").real(Range::non_negative());
    event.where = item.where();
    const std::string what = exactly_one_of(item, {"add", "remove", "change_tool", "cut"});
    if (what == "change_tool") {
      event.change_tool = read_tool_change(item.require("change_tool"), scene.devices);
    } else if (what == "add") {
      event.add = read_body(item.require("add"));
      named.push_back(item.require("add"));
      names.push_back(event.add->name);
      check_unique(named, names, "body");
    } else if (what == "cut") {
      event.cut = read_cut(item.require("cut"), names);
    } else {
      event.remove = known_body(item.require("remove"), names);
    }
    if (!scene.events.empty() && event.time < scene.events.back().time)
      item.require("time").fail(
          "events are listed in time order (this one is earlier than the one before)");
    scene.events.push_back(std::move(event));
  }
}

}  // namespace tacta::scene_detail
