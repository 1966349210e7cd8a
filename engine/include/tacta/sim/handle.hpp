// The handles the public API names bodies and devices by (Simulation, Python). `index` is the
// body's or device's index in its Simulation: its row in report().bodies / report().devices, and
// for a body the slot of capacity.bodies it holds (slots are never reused within a Simulation).
// `generation` tells handles of the same index apart: a body's changes when it is removed, so a
// handle kept past the removal is detected as stale instead of reaching another body, and both
// kinds carry their Simulation's own salt, so a handle from another Simulation is refused
// (InputError) instead of reaching that index here. A default handle is never valid.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace tacta {

template <class Tag>
struct Handle {
  static constexpr uint32_t kNoIndex = 0xffffffffu;
  uint32_t index = kNoIndex;
  uint32_t generation = 0;
  friend constexpr bool operator==(Handle, Handle) = default;
};

struct BodyTag {};
struct DeviceTag {};
using BodyHandle = Handle<BodyTag>;
using DeviceHandle = Handle<DeviceTag>;

// "#1 (generation 7)": for messages ("stale body handle #1 (generation 7): ...").
template <class Tag>
std::string to_string(Handle<Tag> h) {
  return "#" + std::to_string(h.index) + " (generation " + std::to_string(h.generation) + ")";
}

}  // namespace tacta

template <class Tag>
struct std::hash<tacta::Handle<Tag>> {
  size_t operator()(tacta::Handle<Tag> h) const noexcept {
    return std::hash<uint64_t>{}((uint64_t{h.generation} << 32) | h.index);
  }
};
