// Views: the entities that have every one of Ts. Iteration walks the packed entity list of the
// smallest pool and skips entities missing from the others, so its cost follows the rarest
// component. Adding or removing Ts components while iterating a view is not allowed; collect the
// entities first.
#pragma once

#include <array>
#include <cstddef>
#include <tuple>

#include "tacta/ecs/pool.hpp"

namespace tacta::ecs {

template <class... Ts>
class View {
 public:
  explicit View(Pool<Ts>&... pools) : pools_(&pools...) {
    const std::array<const PoolBase*, sizeof...(Ts)> all{&pools...};
    driver_ = all[0];
    for (const PoolBase* p : all)
      if (p->size() < driver_->size()) driver_ = p;
  }

  // f(Entity, Ts&...) for each entity having all of Ts, in the smallest pool's dense order.
  template <class Fn>
  void each(Fn&& fn) {
    for (const Entity e : driver_->entities())
      if (contains_all(e.index)) fn(e, std::get<Pool<Ts>*>(pools_)->at(e.index)...);
  }

  // Number of entities matched (walks the driving pool).
  size_t count() const {
    size_t n = 0;
    for (const Entity e : driver_->entities()) n += contains_all(e.index) ? 1 : 0;
    return n;
  }

  // Upper bound on the matches: the size of the smallest pool, which drives iteration.
  size_t size_hint() const noexcept { return driver_->size(); }

  template <class T>
  T& get(Entity e) {
    return std::get<Pool<T>*>(pools_)->at(e.index);
  }

 private:
  bool contains_all(uint32_t index) const noexcept {
    return (std::get<Pool<Ts>*>(pools_)->contains(index) && ...);
  }
  std::tuple<Pool<Ts>*...> pools_;
  const PoolBase* driver_ = nullptr;
};

}  // namespace tacta::ecs
