#include "checkpoint/shape_state.hpp"

#include <cmath>
#include <memory>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "tacta/embedded_surface.hpp"
#include "tacta/mesh_io.hpp"
#include "topology/cut_mesh.hpp"
#include "world/body_cut.hpp"

namespace tacta {

namespace {

// Bounds on a saved array's length before it is read (the reader also checks it against the
// bytes left, so a forged length cannot allocate past the checkpoint's own size).
constexpr uint64_t kMaxEntries = uint64_t{1} << 28;

// An embedded surface is saved as the embedding it is made from (make_embedded_surface derives
// each vertex's nodes and the extrapolated count from it), with its cut triangles.
void save_surface(CheckpointWriter& out, const EmbeddedSurface& s) {
  out.array(s.triangles);
  out.array(s.corner_uvs);
  out.array(s.rest_positions);
  out.array(s.tet);
  out.array(s.weights);
  out.array(s.cut_triangles);
  out.text(s.source);
}

bool all_finite(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

// The surface made again on `mesh` (the cut mesh, which carries no embedding of its own) by
// make_embedded_surface, which checks the binding (a tet and 4 weights a vertex, tets and
// corners in range); sizes and numbers it does not check are checked here.
std::unique_ptr<EmbeddedSurface> read_surface(CheckpointReader& in, VolumeMesh& mesh) {
  Embedding e;
  e.surface.triangles = in.array<uint32_t>("the surface's triangles", kMaxEntries);
  e.surface.corner_uvs = in.array<double>("the surface's corner uvs", kMaxEntries);
  e.surface.positions = in.array<double>("the surface's rest positions", kMaxEntries);
  e.element = in.array<uint32_t>("the surface's tets", kMaxEntries);
  e.weights = in.array<double>("the surface's weights", kMaxEntries);
  std::vector<uint8_t> cut = in.array<uint8_t>("the surface's cut triangles", kMaxEntries);
  e.surface.source = in.text("the surface's source");
  const size_t t = e.surface.triangle_count();
  if (e.surface.triangles.size() % 3 != 0 || e.surface.positions.size() % 3 != 0 ||
      (!e.surface.corner_uvs.empty() && e.surface.corner_uvs.size() != 6 * t) ||
      (!cut.empty() && cut.size() != t))
    in.fail("the cut body's embedded surface: array sizes that do not agree (" +
            std::to_string(e.surface.vertex_count()) + " vertices, " + std::to_string(t) +
            " triangles)");
  if (!all_finite(e.surface.positions) || !all_finite(e.weights) ||
      !all_finite(e.surface.corner_uvs))
    in.fail("the cut body's embedded surface: a number that is not finite");
  mesh.embedding = std::move(e);
  std::unique_ptr<EmbeddedSurface> s;
  try {
    s = std::make_unique<EmbeddedSurface>(make_embedded_surface(mesh));
  } catch (const InputError& error) {
    in.fail(std::string("the cut body's embedded surface: ") + error.what());
  }
  mesh.embedding.reset();  // the body holds the surface; a cut mesh carries none
  s->cut_triangles = std::move(cut);
  return s;
}

// The saved cut topology, checked whole before it is used.
NewShape read_cut_shape(CheckpointReader& in, const BodyTopology& current, size_t loaded_nodes) {
  NewShape shape;
  shape.topology = std::make_unique<BodyTopology>();
  BodyTopology& t = *shape.topology;
  t.material = current.material;
  t.load = current.load;
  t.mesh.source = current.mesh.source;
  t.mesh.positions = in.array<double>("the cut mesh's rest positions", kMaxEntries);
  t.mesh.tets = in.array<uint32_t>("the cut mesh's tets", kMaxEntries);
  t.mesh.triangles = in.array<uint32_t>("the cut mesh's boundary", kMaxEntries);
  t.mesh.edges = in.array<uint32_t>("the cut mesh's edges", kMaxEntries);
  t.fixed = in.array<uint8_t>("the cut mesh's held nodes", kMaxEntries);
  shape.cut_triangles = in.array<uint8_t>("the cut faces' tags", kMaxEntries);
  shape.loaded_node = in.array<uint32_t>("the cut mesh's loaded nodes", kMaxEntries);
  if (!all_finite(t.mesh.positions)) in.fail("the cut mesh: a rest position is not finite");
  if (const std::vector<std::string> problems = topology_problems(t.mesh); !problems.empty())
    in.fail("the cut mesh: " + problems.front());
  const size_t nodes = t.mesh.node_count();
  if (t.fixed.size() != nodes)
    in.fail("the cut mesh: " + std::to_string(t.fixed.size()) + " held-node flags for " +
            std::to_string(nodes) + " nodes");
  if (!shape.cut_triangles.empty() && shape.cut_triangles.size() != t.mesh.triangles.size() / 3)
    in.fail("the cut mesh: " + std::to_string(shape.cut_triangles.size()) + " cut-face tags for " +
            std::to_string(t.mesh.triangles.size() / 3) + " boundary triangles");
  if (shape.loaded_node.size() != nodes)
    in.fail("the cut mesh: " + std::to_string(shape.loaded_node.size()) + " loaded nodes for " +
            std::to_string(nodes) + " nodes");
  for (uint32_t n : shape.loaded_node)
    if (n >= loaded_nodes) in.fail("the cut mesh: a node copies one past the loaded mesh's");
  t.masses = lumped_masses(t.mesh, t.material.density);
  if (in.pod<uint8_t>("whether the cut body has an embedded surface") != 0)
    shape.surface = read_surface(in, t.mesh);
  return shape;
}

// The shape the scene loaded, for a body cut since whose checkpoint predates any cut.
NewShape loaded_shape(const SoftBody& b) {
  NewShape shape;
  shape.topology = std::make_unique<BodyTopology>();
  const BodyTopology& loaded = b.shape.loaded();
  shape.topology->mesh = loaded.mesh;
  shape.topology->material = loaded.material;
  shape.topology->load = loaded.load;
  shape.topology->masses = loaded.masses;
  shape.topology->fixed = loaded.fixed;
  if (const EmbeddedSurface* surface = b.shape.retired.front().surface.get())
    shape.surface = std::make_unique<EmbeddedSurface>(*surface);
  return shape;
}

}  // namespace

void save_shape(CheckpointWriter& out, const SoftBody& b) {
  out.pod(b.shape.cuts);
  out.array(b.recording.recorded_nodes);
  out.pod(static_cast<uint8_t>(b.recording.probe_node.has_value()));
  out.pod(b.recording.probe_node.value_or(0));
  out.pod(static_cast<uint64_t>(b.recording.probes.size()));
  for (const Probe& p : b.recording.probes) {
    out.pod(p.nodes);
    out.pod(p.weights);
  }
  out.array(b.shape.crack);  // a blade's crossed faces not open yet: an uncut body may have some
  if (b.shape.cuts.revision == 0) return;
  const BodyTopology& t = *b.shape.topology;
  out.array(t.mesh.positions);
  out.array(t.mesh.tets);
  out.array(t.mesh.triangles);
  out.array(t.mesh.edges);
  out.array(t.fixed);
  out.array(b.shape.cut_triangles);
  out.array(b.shape.loaded_node);
  out.pod(static_cast<uint8_t>(b.surface.mesh != nullptr));
  if (b.surface.mesh) save_surface(out, *b.surface.mesh);
}

bool load_shape(CheckpointReader& in, World& world, size_t slot) {
  const SoftBody b = world.body(slot);
  const auto totals = in.pod<CutTotals>("the body's cut totals");
  std::vector<uint32_t> recorded = in.array<uint32_t>("the recorded nodes", kMaxEntries);
  if (recorded.size() != b.recording.recorded_nodes.size())
    in.fail(std::to_string(recorded.size()) + " recorded nodes in the checkpoint, " +
            std::to_string(b.recording.recorded_nodes.size()) + " in the scene");
  const bool has_probe_node = in.pod<uint8_t>("whether a probe node is recorded") != 0;
  const auto probe_node = in.pod<uint32_t>("the probe node");
  if (has_probe_node != b.recording.probe_node.has_value())
    in.fail("a probe node in one of the checkpoint and the scene, not the other");
  const auto probe_count = in.pod<uint64_t>("the probe count");
  if (probe_count != b.recording.probes.size())
    in.fail(std::to_string(probe_count) + " probes in the checkpoint, " +
            std::to_string(b.recording.probes.size()) + " in the scene");
  std::vector<Probe> probes = b.recording.probes;
  for (Probe& p : probes) {
    p.nodes = in.pod<std::array<uint32_t, 4>>("a probe's nodes");
    p.weights = in.pod<std::array<double, 4>>("a probe's weights");
  }
  std::vector<std::array<uint32_t, 3>> crack =
      in.array<std::array<uint32_t, 3>>("the crack", kMaxEntries);

  NewShape shape;
  if (totals.revision > 0)
    shape = read_cut_shape(in, *b.shape.topology, b.shape.loaded().mesh.node_count());
  else if (b.shape.cuts.revision > 0)
    shape = loaded_shape(b);
  const size_t nodes = shape.topology ? shape.topology->mesh.node_count() : b.node_count();
  auto past = [&](uint32_t n) { return n >= nodes; };
  bool bad = has_probe_node && past(probe_node);
  for (uint32_t n : recorded) bad = bad || past(n);
  for (const auto& face : crack)
    for (uint32_t n : face) bad = bad || past(n);
  for (const Probe& p : probes)
    for (size_t c = 0; c < 4; ++c) bad = bad || past(p.nodes[c]) || !std::isfinite(p.weights[c]);
  if (bad)
    in.fail("a recorded node, probe or crack face names a node past the body's " +
            std::to_string(nodes));

  const bool reshape = shape.topology != nullptr;
  if (reshape) {
    shape.topology->view = make_view(shape.topology->mesh);
    // The scene's boundary motion (the one loaded, kept when cuts replaced it) on the new mesh.
    const BoundaryMotion* loaded_motion = b.shape.retired.empty()
                                              ? b.constraints.boundary.get()
                                              : b.shape.retired.front().boundary.get();
    if (loaded_motion != nullptr) {
      std::vector<uint32_t> source = shape.loaded_node;
      if (source.empty()) {  // the loaded mesh itself
        source.resize(nodes);
        std::iota(source.begin(), source.end(), 0u);
      }
      shape.boundary = loaded_motion->carried(source, shape.topology->mesh, shape.topology->masses);
    }
    const SourceLocation where{world.scene().path, 0, 0, "bodies." + b.info.name};
    ShapeModels models = make_shape_models(world, b, *shape.topology, where);
    const std::vector<double> zero(3 * nodes, 0.0);
    install_shape(b, std::move(shape), std::move(models), zero, zero, zero);
  }
  b.shape.cuts = totals;
  b.shape.crack = std::move(crack);
  b.recording.recorded_nodes = std::move(recorded);
  if (has_probe_node) b.recording.probe_node = probe_node;
  b.recording.probes = std::move(probes);
  return reshape;
}

void shape_positions_loaded(const SoftBody& b) {
  if (b.surface.mesh) update_embedded_surface(*b.surface.mesh, b.nodes.positions.data());
}

}  // namespace tacta
