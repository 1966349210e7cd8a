// A body's boundary motion and probes: `prescribed` displacements (constant, ramp or table; some
// or all axes), rigid `plates` that press the body, and `probes` at rest points.
#include <cmath>
#include <fmt/format.h>
#include <set>
#include <string>

#include "scene/section_readers.hpp"
#include "tacta/vec3.hpp"

namespace tacta::scene_detail {

namespace {

constexpr const char* kSeriesForms =
    "[x, y, z] (constant), {ramp: {to: [x, y, z], start_s, duration_s}} or {table: [[t, x, y, z], "
    "...]}";

TimeSeriesDesc read_ramp(const Field& field) {
  field.expect_map("a map {to: [x, y, z], start_s, duration_s}");
  field.check_keys({"from", "to", "start_s", "duration_s"});
  const Vec3 from = field.has("from") ? field.require("from").vec3() : Vec3{0, 0, 0};
  const Vec3 to = field.require("to").vec3();
  const double start =
      field.has("start_s") ? field.require("start_s").real(Range::non_negative()) : 0.0;
  const double duration = field.require("duration_s").real(Range::positive());
  return {{start, start + duration}, {from, to}};
}

TimeSeriesDesc read_table(const Field& field) {
  TimeSeriesDesc series;
  for (const Field& row : field.items("a list of rows [t, x, y, z] (s, then the value)")) {
    const std::vector<double> r = row.reals(4);
    if (!series.times_s.empty() && !(r[0] > series.times_s.back()))
      row.fail_expected(
          fmt::format("a time after the previous row's {} s (times strictly increasing)",
                      series.times_s.back()));
    if (r[0] < 0) row.fail_expected("a time >= 0 s");
    series.times_s.push_back(r[0]);
    series.values.push_back({r[1], r[2], r[3]});
  }
  if (series.times_s.empty()) field.fail_expected("at least one row [t, x, y, z]");
  return series;
}

TimeSeriesDesc read_series(const Field& field) {
  if (field.is_list()) return {{0.0}, {field.vec3()}};
  field.expect_map(kSeriesForms);
  field.check_keys({"ramp", "table"});
  if (exactly_one_of(field, {"ramp", "table"}) == "ramp") return read_ramp(field.require("ramp"));
  return read_table(field.require("table"));
}

std::array<bool, 3> read_axes(const Field& field) {
  std::array<bool, 3> axes{false, false, false};
  for (const Field& item : field.items("a list of axes, e.g. [x, z]")) {
    const std::string axis = item.choice({"x", "y", "z"});
    bool& slot = axes[static_cast<size_t>(axis[0] - 'x')];
    if (slot) item.fail("axis '" + axis + "' is listed twice");
    slot = true;
  }
  if (!axes[0] && !axes[1] && !axes[2]) field.fail_expected("at least one of x, y, z");
  return axes;
}

PrescribedDesc read_prescribed(const Field& field, std::optional<uint64_t> node_count) {
  field.expect_map("a map {region, displacement, axes}");
  field.check_keys({"region", "displacement", "axes"});
  PrescribedDesc p;
  p.where = field.where();
  p.region = read_fixed_region(field.require("region"), node_count);
  p.displacement = read_series(field.require("displacement"));
  if (auto f = field.get("axes")) p.axes = read_axes(*f);
  return p;
}

PlateDesc read_plate(const Field& field, std::optional<uint64_t> node_count,
                     std::set<std::string>& names) {
  field.expect_map("a map {name, region, point, normal, motion, contact}");
  field.check_keys({"name", "region", "point", "normal", "motion", "contact"});
  PlateDesc plate;
  plate.where = field.where();
  const Field name = field.require("name");
  plate.name = name.text();
  if (!names.insert(plate.name).second)
    name.fail("plate name '" + plate.name + "' is used twice in this body");
  plate.region = read_fixed_region(field.require("region"), node_count);
  plate.point = field.require("point").vec3();
  const Field normal_field = field.require("normal");
  const Vec3 n = normal_field.vec3();
  const double length = norm(n);
  if (!(length > 1e-12))
    normal_field.fail_expected("a non-zero normal (from the plate into the body)");
  plate.normal = {n[0] / length, n[1] / length, n[2] / length};
  plate.motion = field.has("motion") ? read_series(field.require("motion"))
                                     : TimeSeriesDesc{{0.0}, {Vec3{0, 0, 0}}};
  if (auto f = field.get("contact")) plate.stuck = f->choice({"frictionless", "stuck"}) == "stuck";
  return plate;
}

ProbeDesc read_probe(const Field& field, std::set<std::string>& names) {
  field.expect_map("a map {name, position: [x, y, z]}");
  field.check_keys({"name", "position"});
  ProbeDesc probe;
  const Field name = field.require("name");
  probe.name = name.text();
  if (!names.insert(probe.name).second)
    name.fail("probe name '" + probe.name + "' is used twice in this body");
  probe.rest = field.require("position").vec3();
  return probe;
}

}  // namespace

void read_boundary(const Field& body, BodyDesc& desc, std::optional<uint64_t> node_count) {
  if (auto f = body.get("prescribed"))
    for (const Field& item :
         f->items("a list of prescribed displacements {region, displacement, axes}"))
      desc.prescribed.push_back(read_prescribed(item, node_count));
  std::set<std::string> names;
  if (auto f = body.get("plates"))
    for (const Field& item :
         f->items("a list of plates {name, region, point, normal, motion, contact}"))
      desc.plates.push_back(read_plate(item, node_count, names));
  names.clear();
  if (auto f = body.get("probes"))
    for (const Field& item : f->items("a list of probes {name, position: [x, y, z]}"))
      desc.probes.push_back(read_probe(item, names));
}

}  // namespace tacta::scene_detail
