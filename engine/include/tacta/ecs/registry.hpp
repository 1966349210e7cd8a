// The Registry: creates and destroys entities, owns one dense pool per component type, and hands
// out views. Every access through a handle checks its generation first: a destroyed entity, or an
// old handle to a recycled slot, is reported (valid() false, get() throws std::out_of_range
// naming the index and both generations, try_get() returns nullptr) instead of reaching another
// entity's data. Not thread-safe: the haptic task owns the registry (docs/ARCHITECTURE.md).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

#include "tacta/ecs/entity.hpp"
#include "tacta/ecs/pool.hpp"
#include "tacta/ecs/view.hpp"

namespace tacta::ecs {

namespace detail {
inline uint32_t next_component_id() {
  static std::atomic<uint32_t> counter{0};
  return counter++;
}
// A dense small integer per component type, so pools live in a vector, not a map.
template <class T>
uint32_t component_id() {
  static const uint32_t id = next_component_id();
  return id;
}
}  // namespace detail

class Registry {
 public:
  Registry() = default;
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;
  Registry(Registry&&) noexcept = default;
  Registry& operator=(Registry&&) noexcept = default;

  Entity create() {
    if (!free_.empty()) {
      const uint32_t index = free_.back();
      free_.pop_back();
      alive_[index] = true;
      return {index, generations_[index]};
    }
    if (generations_.size() >= Entity::kNullIndex)
      throw std::length_error("ecs: out of entity slots");
    generations_.push_back(1);
    alive_.push_back(true);
    return {static_cast<uint32_t>(generations_.size() - 1), 1};
  }

  // Removes every component of e and retires the handle; throws std::out_of_range when stale.
  void destroy(Entity e) {
    require_valid(e, "destroy");
    for (auto& pool : pools_)
      if (pool) pool->remove(e.index);
    alive_[e.index] = false;
    // Skip 0 on wrap-around so a default-constructed handle never matches a live slot.
    if (++generations_[e.index] == 0) generations_[e.index] = 1;
    free_.push_back(e.index);
  }

  // Room for `entities` entities and T components on them: create, emplace<T> and destroy then
  // allocate nothing (the haptic task adds and removes bodies at tick boundaries).
  template <class T>
  void reserve(size_t entities) {
    generations_.reserve(entities);
    alive_.reserve(entities);
    free_.reserve(entities);
    pool<T>().reserve(entities, entities);
  }

  bool valid(Entity e) const noexcept {
    return e.index < generations_.size() && alive_[e.index] &&
           generations_[e.index] == e.generation;
  }

  size_t alive_count() const noexcept { return generations_.size() - free_.size(); }

  template <class T, class... Args>
  T& emplace(Entity e, Args&&... args) {
    require_valid(e, "emplace");
    Pool<T>& p = pool<T>();
    if (p.contains(e.index))
      throw std::logic_error(to_string(e) + " already has a component " + typeid(T).name());
    return p.emplace(e, std::forward<Args>(args)...);
  }

  template <class T>
  T& get(Entity e) {
    require_valid(e, "get");
    Pool<T>& p = pool<T>();
    if (!p.contains(e.index))
      throw std::out_of_range(to_string(e) + " has no component " + typeid(T).name());
    return p.at(e.index);
  }
  template <class T>
  const T& get(Entity e) const {
    return const_cast<Registry*>(this)->get<T>(e);
  }

  // nullptr when the handle is stale or the entity has no T.
  template <class T>
  T* try_get(Entity e) noexcept {
    if (!valid(e)) return nullptr;
    Pool<T>* p = existing_pool<T>();
    return p ? p->find(e.index) : nullptr;
  }

  // True when a T was removed; throws std::out_of_range when the handle is stale.
  template <class T>
  bool remove(Entity e) {
    require_valid(e, "remove");
    Pool<T>* p = existing_pool<T>();
    return p != nullptr && p->remove(e.index);
  }

  // False for a stale handle.
  template <class... Ts>
  bool has(Entity e) const noexcept {
    if (!valid(e)) return false;
    return (has_one<Ts>(e.index) && ...);
  }

  // The dense pool of T (created empty if no entity has a T yet).
  template <class T>
  Pool<T>& pool() {
    const uint32_t id = detail::component_id<T>();
    if (id >= pools_.size()) pools_.resize(size_t{id} + 1);
    if (!pools_[id]) pools_[id] = std::make_unique<Pool<T>>();
    return static_cast<Pool<T>&>(*pools_[id]);
  }

  // Entities having every one of Ts; iterates the smallest of their pools.
  template <class... Ts>
  View<Ts...> view() {
    static_assert(sizeof...(Ts) > 0, "a view needs at least one component type");
    return View<Ts...>(pool<Ts>()...);
  }

 private:
  template <class T>
  Pool<T>* existing_pool() const noexcept {
    const uint32_t id = detail::component_id<T>();
    return id < pools_.size() ? static_cast<Pool<T>*>(pools_[id].get()) : nullptr;
  }
  template <class T>
  bool has_one(uint32_t index) const noexcept {
    const Pool<T>* p = existing_pool<T>();
    return p != nullptr && p->contains(index);
  }

  void require_valid(Entity e, const char* operation) const {
    if (valid(e)) return;
    std::string why;
    if (e.index >= generations_.size())
      why = "index " + std::to_string(e.index) + " was never created (" +
            std::to_string(generations_.size()) + " slots)";
    else if (!alive_[e.index])
      why = "stale handle: index " + std::to_string(e.index) + " generation " +
            std::to_string(e.generation) + " was destroyed (slot is free, next generation " +
            std::to_string(generations_[e.index]) + ")";
    else
      why = "stale handle: index " + std::to_string(e.index) + " generation " +
            std::to_string(e.generation) + ", but the slot now holds generation " +
            std::to_string(generations_[e.index]);
    throw std::out_of_range(std::string("ecs::Registry::") + operation + ": " + why);
  }

  std::vector<uint32_t> generations_;  // per slot: generation of the live (or next) entity
  std::vector<bool> alive_;            // per slot
  std::vector<uint32_t> free_;         // destroyed slots, reused last-in first-out
  std::vector<std::unique_ptr<PoolBase>> pools_;  // by detail::component_id<T>()
};

}  // namespace tacta::ecs
