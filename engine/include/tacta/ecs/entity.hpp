// Entity handles: a 32-bit slot index plus a 32-bit generation. Destroying an entity bumps the
// generation of its slot, so every handle still held to it (or to an older user of a recycled
// slot) compares unequal to the live one and is detected as stale.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace tacta::ecs {

struct Entity {
  static constexpr uint32_t kNullIndex = 0xffffffffu;

  uint32_t index = kNullIndex;
  uint32_t generation = 0;  // 0 is never handed out, so a default Entity is never valid

  // Both halves packed into one integer, e.g. for hashing or a report.
  constexpr uint64_t id() const { return (uint64_t{generation} << 32) | index; }
  constexpr bool is_null() const { return index == kNullIndex; }
  friend constexpr bool operator==(Entity, Entity) = default;
};

inline constexpr Entity null_entity{};

inline std::string to_string(Entity e) {
  return "entity(index " + std::to_string(e.index) + ", generation " +
         std::to_string(e.generation) + ")";
}

}  // namespace tacta::ecs

template <>
struct std::hash<tacta::ecs::Entity> {
  size_t operator()(tacta::ecs::Entity e) const noexcept { return std::hash<uint64_t>{}(e.id()); }
};
