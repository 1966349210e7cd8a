// Bodies: mesh source (file or primitive), material, model, fixed regions, initial state.
#include <algorithm>
#include <fmt/format.h>
#include <string>

#include "scene/plugin_params.hpp"
#include "scene/section_readers.hpp"
#include "tacta/mesh_build.hpp"

namespace tacta::scene_detail {

namespace {

constexpr int64_t kMaxCellsPerAxis = 1000;  // keeps a typo from asking for a billion nodes

std::array<int, 3> read_cells(const Field& field, size_t axes) {
  const std::string expected =
      axes == 3 ? "a list of 3 cell counts [nx, ny, nz]" : "a list of 2 cell counts [nx, ny]";
  const std::vector<Field> items = field.items(expected);
  if (items.size() != axes) field.fail_expected(expected);
  std::array<int, 3> cells{0, 0, 0};
  for (size_t i = 0; i < axes; ++i)
    cells[i] = static_cast<int>(items[i].integer(1, kMaxCellsPerAxis));
  return cells;
}

void read_grid(const Field& field, MeshSourceDesc& mesh, size_t axes) {
  field.expect_map(axes == 3 ? "a map {size: [x, y, z], cells: [nx, ny, nz], origin: [x, y, z]}"
                             : "a map {size: [x, y], cells: [nx, ny], origin: [x, y, z]}");
  field.check_keys({"size", "cells", "origin"});
  const std::vector<double> size = field.require("size").reals(axes, Range::positive());
  mesh.size = {size[0], size[1], axes == 3 ? size[2] : 0.0};  // a planar grid has no thickness
  const Field cells = field.require("cells");
  mesh.cells = read_cells(cells, axes);
  uint64_t nodes = 1;
  for (size_t a = 0; a < axes; ++a) nodes *= static_cast<uint64_t>(mesh.cells[a]) + 1;
  if (nodes > static_cast<uint64_t>(kMaxGridNodes))
    cells.fail(fmt::format(
        "{} cells give {} grid nodes; at most {} are allowed (far past what a haptic loop "
        "steps, and a typo here would allocate gigabytes before the run)",
        axes == 3 ? fmt::format("{} x {} x {}", mesh.cells[0], mesh.cells[1], mesh.cells[2])
                  : fmt::format("{} x {}", mesh.cells[0], mesh.cells[1]),
        nodes, kMaxGridNodes));
  if (auto origin = field.get("origin")) mesh.origin = origin->vec3();
}

void read_sphere(const Field& field, MeshSourceDesc& mesh) {
  field.expect_map("a map {radius, centre, subdivisions}");
  field.check_keys({"radius", "centre", "subdivisions"});
  if (auto f = field.get("radius")) mesh.radius = f->real(Range::positive());
  if (auto f = field.get("centre")) mesh.origin = f->vec3();
  if (auto f = field.get("subdivisions")) mesh.subdivisions = static_cast<int>(f->integer(0, 6));
}

TetrahedralizeDesc read_tetrahedralize(const Field& field) {
  TetrahedralizeDesc t;
  if (field.is_scalar()) {  // `tetrahedralize: true` takes every default
    if (!field.boolean())
      field.fail("'tetrahedralize: false' is the same as leaving it out; remove it");
    return t;
  }
  field.expect_map("true, or a map {max_volume, min_dihedral, min_radius_ratio, optimize}");
  field.check_keys({"max_volume", "min_dihedral", "min_radius_ratio", "optimize"});
  if (auto f = field.get("max_volume")) t.max_volume = f->real(Range::non_negative());
  if (auto f = field.get("min_dihedral")) t.min_dihedral_deg = f->real(Range::closed(0, 60));
  if (auto f = field.get("min_radius_ratio")) t.min_radius_ratio = f->real(Range::closed(0, 0.9));
  if (auto f = field.get("optimize")) t.optimize = f->boolean();
  return t;
}

void make_unit_square(MeshSourceDesc& mesh) {
  // The paper's 4-node unit square: one quad, 1 m x 1 m, at the origin.
  mesh.kind = MeshSourceDesc::Kind::QuadGrid;
  mesh.size = {1.0, 1.0, 0.0};
  mesh.cells = {1, 1, 0};
  mesh.origin = {0.0, 0.0, 0.0};
}

std::vector<BodyDesc::NodeVector> read_node_vectors(const Field& field,
                                                    std::optional<uint64_t> node_count) {
  std::vector<BodyDesc::NodeVector> out;
  for (const Field& item : field.items("a list of {node: i, value: [x, y, z]}")) {
    item.expect_map("a map {node: i, value: [x, y, z]}");
    item.check_keys({"node", "value"});
    out.push_back({read_node(item.require("node"), node_count), item.require("value").vec3()});
  }
  return out;
}

void read_initial(const Field& field, BodyDesc& body, std::optional<uint64_t> node_count) {
  field.expect_map("a map {displacement, velocity, uniform_velocity}");
  field.check_keys({"displacement", "velocity", "uniform_velocity"});
  if (auto f = field.get("displacement"))
    body.initial_displacement = read_node_vectors(*f, node_count);
  if (auto f = field.get("velocity")) body.initial_velocity = read_node_vectors(*f, node_count);
  if (auto f = field.get("uniform_velocity")) body.uniform_velocity = f->vec3();
}

}  // namespace

// A node index, checked against the node count when the mesh is a grid.
uint32_t read_node(const Field& field, std::optional<uint64_t> node_count) {
  if (!node_count) return field.index();
  return static_cast<uint32_t>(field.integer(0, static_cast<int64_t>(*node_count) - 1));
}

std::vector<uint32_t> read_nodes(const Field& field, std::optional<uint64_t> node_count) {
  std::vector<uint32_t> out;
  for (const Field& item : field.items("a list of node indices"))
    out.push_back(read_node(item, node_count));
  if (out.empty()) field.fail_expected("a non-empty list of node indices");
  return out;
}

FixedRegionDesc read_fixed_region(const Field& field, std::optional<uint64_t> node_count) {
  field.expect_map("a map {box: {min, max}} or {nodes: [i, ...]}");
  FixedRegionDesc region;
  if (exactly_one_of(field, {"box", "nodes"}) == "nodes") {
    region.indices = read_nodes(field.require("nodes"), node_count);
    return region;
  }
  const Field box = field.require("box");
  box.expect_map("a map {min: [x, y, z], max: [x, y, z]}");
  box.check_keys({"min", "max"});
  const Vec3 lo = box.require("min").vec3();
  const Field max_field = box.require("max");
  const Vec3 hi = max_field.vec3();
  for (int axis = 0; axis < 3; ++axis)
    if (hi[static_cast<size_t>(axis)] < lo[static_cast<size_t>(axis)])
      max_field.fail_expected(
          fmt::format("a corner >= min on every axis (min is [{}, {}, {}])", lo[0], lo[1], lo[2]));
  region.box = std::array<Vec3, 2>{lo, hi};
  return region;
}

std::string exactly_one_of(const Field& field, const std::vector<std::string>& allowed) {
  std::vector<std::string> present;
  for (const std::string& key : allowed)
    if (field.has(key)) present.push_back(key);
  std::string list;
  for (const std::string& key : allowed) list += (list.empty() ? "" : ", ") + key;
  if (present.size() != 1)
    field.fail("expected exactly one of: " + list + "; found " +
               (present.empty() ? std::string("none")
                                : "several (" + present[0] + ", " + present[1] + ")"));
  return present[0];
}

std::optional<uint64_t> grid_node_count(const MeshSourceDesc& mesh) {
  const auto nodes = [&](size_t axis) { return static_cast<uint64_t>(mesh.cells[axis]) + 1; };
  switch (mesh.kind) {
    case MeshSourceDesc::Kind::BoxGrid:
    case MeshSourceDesc::Kind::BeamGrid: return nodes(0) * nodes(1) * nodes(2);
    case MeshSourceDesc::Kind::QuadGrid: return nodes(0) * nodes(1);
    default: return std::nullopt;
  }
}

MeshSourceDesc read_mesh_source(const Field& field) {
  MeshSourceDesc mesh;
  if (field.is_scalar() && field.yaml().Scalar() == "unit_square") {
    make_unit_square(mesh);
    mesh.where = field.where();
    return mesh;
  }
  field.expect_map(
      "a map with `file` or one primitive (box_grid, beam_grid, quad_grid, "
      "unit_square, sphere), or 'unit_square'");
  field.check_keys({"file", "scale", "translate", "voxel_size", "max_tets", "surface",
                    "tetrahedralize", "box_grid", "beam_grid", "quad_grid", "unit_square", "sphere"});
  const std::string source = exactly_one_of(
      field, {"file", "box_grid", "beam_grid", "quad_grid", "unit_square", "sphere"});
  if (source != "file") {
    for (const char* file_only :
         {"scale", "translate", "voxel_size", "max_tets", "tetrahedralize"})
      if (auto f = field.get(file_only))
        f->fail(std::string("'") + file_only + "' applies to a mesh `file` only, not to " + source);
  }
  const Field value = field.require(source);
  mesh.where = value.where();
  if (source == "file") {
    mesh.kind = MeshSourceDesc::Kind::File;
    mesh.path = value.file_path();
    if (auto f = field.get("scale")) {
      if (f->is_scalar()) {
        const double s = f->real(Range::positive());
        mesh.scale = {s, s, s};
      } else {
        mesh.scale = f->vec3(Range::positive());
      }
    }
    if (auto f = field.get("translate")) mesh.translate = f->vec3();
    if (auto f = field.get("voxel_size")) mesh.voxel_size = f->real(Range::non_negative());
    if (auto f = field.get("tetrahedralize")) {
      if (field.get("voxel_size"))
        f->fail("give `voxel_size` (voxel tets) or `tetrahedralize` (Gmsh), not both");
      mesh.tetrahedralize = read_tetrahedralize(*f);
    }
    if (auto f = field.get("max_tets")) {
      if (field.get("voxel_size"))
        f->fail("`voxel_size` fixes the voxels, `max_tets` sizes them automatically; give one");
      if (mesh.tetrahedralize && mesh.tetrahedralize->max_volume > 0)
        f->fail(
            "`tetrahedralize.max_volume` fixes the tets' size, `max_tets` sizes them "
            "automatically; give one");
      mesh.max_tets = f->integer(1, kMaxTetsLimit);
    }
  } else if (source == "box_grid" || source == "beam_grid") {
    mesh.kind =
        source == "box_grid" ? MeshSourceDesc::Kind::BoxGrid : MeshSourceDesc::Kind::BeamGrid;
    read_grid(value, mesh, 3);
  } else if (source == "quad_grid") {
    mesh.kind = MeshSourceDesc::Kind::QuadGrid;
    read_grid(value, mesh, 2);
  } else if (source == "unit_square") {
    if (!value.yaml().IsNull()) {
      value.expect_map("nothing, or an empty map {}");
      value.check_keys(std::vector<std::string>{});
    }
    make_unit_square(mesh);
  } else {
    mesh.kind = MeshSourceDesc::Kind::Sphere;
    mesh.origin = {0, 0, 0};
    read_sphere(value, mesh);
  }
  if (auto f = field.get("surface")) {
    if (mesh.kind == MeshSourceDesc::Kind::QuadGrid)
      f->fail("a surface can only be embedded in tetrahedra, not in a planar quad_grid");
    if (f->is_scalar() && f->yaml().Scalar() == "tet_boundary")
      mesh.surface_tet_boundary = true;
    else
      mesh.surface_path = f->file_path();
    mesh.surface_where = f->where();
  }
  return mesh;
}

BodyDesc read_body(const Field& field) {
  field.expect_map("a body: a map {name, mesh, material, model, ...}");
  field.check_keys({"name", "mesh", "material", "model", "fixed", "initial", "probe_node",
                    "prescribed", "plates", "probes", "step_rate_hz", "step_thread",
                    "local_contact", "collide"});
  BodyDesc body;
  body.where = field.where();
  body.name = field.require("name").text();
  body.mesh = read_mesh_source(field.require("mesh"));
  body.material = read_material(field.require("material"));
  PluginRef model = read_plugin(field.require("model"), TACTA_KIND_MODEL);
  body.model = std::move(model.name);
  body.model_params = std::move(model.params);
  const std::optional<uint64_t> node_count = grid_node_count(body.mesh);
  if (auto f = field.get("fixed")) {
    body.fixed_where = f->where();
    for (const Field& item : f->items("a list of fixed regions ({box: ...} or {nodes: ...})"))
      body.fixed.push_back(read_fixed_region(item, node_count));
  }
  if (auto f = field.get("initial")) read_initial(*f, body, node_count);
  if (auto f = field.get("probe_node")) body.probe_node = read_node(*f, node_count);
  read_boundary(field, body, node_count);
  if (auto f = field.get("step_rate_hz")) body.step_rate_hz = f->real(Range::non_negative());
  if (auto f = field.get("step_thread")) {
    body.own_thread = f->choice({"haptic", "own"}) == "own";
    if (body.own_thread && body.step_rate_hz <= 0)
      f->fail(
          "step_rate_hz > 0 with step_thread: own (the rate the worker thread steps the body at)");
  }
  if (auto f = field.get("local_contact"))
    body.local_contact_yielding = f->choice({"yielding", "rigid"}) == "yielding";
  if (auto f = field.get("collide")) body.collide = f->boolean();
  return body;
}

}  // namespace tacta::scene_detail
