#include "timing/body_descriptions.hpp"

#include <utility>

namespace tacta {

namespace {

BodyStatic describe(const std::string& name, const BodyTopology& topology,
                    const std::vector<uint8_t>& cut_triangles, const EmbeddedSurface* surface,
                    uint32_t revision) {
  const VolumeMesh& m = topology.mesh;
  BodyStatic bs;
  bs.name = name;
  bs.rest_positions = m.positions;
  bs.triangles = m.triangles;
  bs.tets = m.tets;
  bs.quads = m.quads;
  bs.dimension = m.dimension;
  bs.revision = revision;
  bs.cut_triangles = cut_triangles;
  if (surface != nullptr) {
    bs.surface_rest_positions = surface->rest_positions;
    bs.surface_triangles = surface->triangles;
    bs.surface_cut_triangles = surface->cut_triangles;
  }
  for (uint32_t n = 0; n < topology.fixed.size(); ++n)
    if (topology.fixed[n]) bs.fixed_nodes.push_back(n);
  return bs;
}

}  // namespace

BodyStatic describe_body(const SoftBody& b) {
  return describe(b.info.name, *b.shape.topology, b.shape.cut_triangles, b.surface.mesh.get(),
                  b.shape.cuts.revision);
}

BodyStatic describe_prepared(const SoftBody& b, const PreparedCut& cut) {
  return describe(b.info.name, *cut.shape.topology, cut.shape.cut_triangles,
                  cut.shape.surface.get(), b.shape.cuts.revision + 1);
}

DescriptionChains::DescriptionChains(size_t slots)
    : newest_(std::make_unique<std::atomic<const DescribedRevision*>[]>(slots)), slots_(slots) {
  for (size_t i = 0; i < slots; ++i) newest_[i].store(nullptr, std::memory_order_relaxed);
}

DescriptionChains::~DescriptionChains() {
  for (size_t i = 0; i < slots_; ++i)
    for (const DescribedRevision* d = newest_[i].load(); d != nullptr;)
      delete std::exchange(d, d->older);
}

void DescriptionChains::publish(size_t slot, std::unique_ptr<DescribedRevision> d) noexcept {
  if (slot >= slots_) return;
  d->older = newest_[slot].load(std::memory_order_relaxed);
  newest_[slot].store(d.release(), std::memory_order_release);
}

const BodyStatic* DescriptionChains::find(size_t slot, uint32_t revision) const noexcept {
  if (slot >= slots_) return nullptr;
  for (const DescribedRevision* d = newest_[slot].load(std::memory_order_acquire); d != nullptr;
       d = d->older)
    if (d->body.revision == revision) return &d->body;
  return nullptr;
}

}  // namespace tacta
