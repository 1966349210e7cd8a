// What the render side is told of a body's mesh (BodyStatic), and how a new one reaches it while
// the haptic thread runs: each revision a cut makes is described once, kept unchanged for the rest
// of the session in a chain per body slot (newest first, published by one atomic store), and the
// render task takes from it the revision each snapshot says its arrays follow. Nothing is
// allocated or freed on the haptic thread, and nothing the render thread reads is changed in place.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "tacta/sim/snapshot.hpp"
#include "world/body_cut.hpp"
#include "world/world.hpp"

namespace tacta {

// Body `b`'s description as its mesh stands.
BodyStatic describe_body(const SoftBody& b);
// The description body `b` will have once `cut` (changed) is applied: revision one past b's.
BodyStatic describe_prepared(const SoftBody& b, const PreparedCut& cut);

// One description in a body's chain.
struct DescribedRevision {
  BodyStatic body;
  const DescribedRevision* older = nullptr;
};

class DescriptionChains {
 public:
  explicit DescriptionChains(size_t slots);
  ~DescriptionChains();
  DescriptionChains(const DescriptionChains&) = delete;
  DescriptionChains& operator=(const DescriptionChains&) = delete;

  // Any thread that makes the slot's revisions (one at a time per slot): `d` becomes the newest.
  // Allocates nothing.
  void publish(size_t slot, std::unique_ptr<DescribedRevision> d) noexcept;
  // Any thread: slot's description at `revision`, null when none was published.
  const BodyStatic* find(size_t slot, uint32_t revision) const noexcept;

 private:
  std::unique_ptr<std::atomic<const DescribedRevision*>[]> newest_;
  size_t slots_;
};

}  // namespace tacta
