// A dense component pool (sparse set): components sit contiguously in `components_`, the entity
// owning each one at the same position in `entities_`, and `sparse_` maps an entity's slot index
// to that position. Removal swaps the last element into the hole, so the pool never has gaps and
// iteration touches only live components. The pool trusts its caller (the Registry) to have
// checked the handle's generation already.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "tacta/ecs/entity.hpp"

namespace tacta::ecs {

// What the Registry needs from every pool without knowing its component type.
class PoolBase {
 public:
  virtual ~PoolBase() = default;
  virtual bool contains(uint32_t index) const noexcept = 0;
  virtual bool remove(uint32_t index) = 0;
  virtual size_t size() const noexcept = 0;
  virtual std::span<const Entity> entities() const noexcept = 0;
};

template <class T>
class Pool final : public PoolBase {
 public:
  static constexpr uint32_t kAbsent = 0xffffffffu;

  bool contains(uint32_t index) const noexcept override {
    return index < sparse_.size() && sparse_[index] != kAbsent;
  }
  size_t size() const noexcept override { return entities_.size(); }
  std::span<const Entity> entities() const noexcept override { return entities_; }
  std::span<T> components() noexcept { return components_; }
  std::span<const T> components() const noexcept { return components_; }

  // Room for `count` components and slot indices below `slots`: emplace then allocates nothing.
  void reserve(size_t count, size_t slots) {
    components_.reserve(count);
    entities_.reserve(count);
    if (sparse_.size() < slots) sparse_.resize(slots, kAbsent);
  }

  template <class... Args>
  T& emplace(Entity e, Args&&... args) {
    if (e.index >= sparse_.size()) sparse_.resize(size_t{e.index} + 1, kAbsent);
    components_.push_back(T{std::forward<Args>(args)...});
    entities_.push_back(e);
    sparse_[e.index] = static_cast<uint32_t>(entities_.size() - 1);
    return components_.back();
  }

  // Caller guarantees contains(index).
  T& at(uint32_t index) noexcept { return components_[sparse_[index]]; }
  const T& at(uint32_t index) const noexcept { return components_[sparse_[index]]; }

  T* find(uint32_t index) noexcept { return contains(index) ? &at(index) : nullptr; }

  bool remove(uint32_t index) override {
    if (!contains(index)) return false;
    const uint32_t hole = sparse_[index];
    const uint32_t last = static_cast<uint32_t>(entities_.size() - 1);
    if (hole != last) {
      components_[hole] = std::move(components_[last]);
      entities_[hole] = entities_[last];
      sparse_[entities_[hole].index] = hole;
    }
    components_.pop_back();
    entities_.pop_back();
    sparse_[index] = kAbsent;
    return true;
  }

 private:
  std::vector<T> components_;     // dense, one per entity that has a T
  std::vector<Entity> entities_;  // packed, same order as components_
  std::vector<uint32_t> sparse_;  // slot index -> position in the dense arrays, or kAbsent
};

}  // namespace tacta::ecs
