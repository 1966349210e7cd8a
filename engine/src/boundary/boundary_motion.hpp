// Boundary motion the engine applies to a body around every model step, so that every model gets
// it through the plain fixed-node mask of the model ABI:
// - nodes prescribed on all three axes are held by the model; the engine moves them (position
//   rest + u(t), velocity u'(t)) before and after each step;
// - nodes with some axes free (per-axis constraints, sliding) and nodes a plate may touch are
//   also held by the model, and the engine advances their free components itself after the step:
//   one linearly implicit Euler update per node against the model's internal forces at the new
//   positions, with a diagonal bound of the node's rest stiffness (a Jacobi sweep over those
//   nodes after the model's solve of the others; the bound makes the sweep converge). At
//   equilibrium this is exact (the free components carry zero net force); in motion those nodes
//   lag the body by a step and are over-damped, and a static state takes more steps to reach.
// Built at load time; before_step/after_step allocate nothing and throw nothing (1 kHz path).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "plugin/plugin_instance.hpp"
#include "tacta/mesh.hpp"
#include "tacta/scene.hpp"

namespace tacta {

// The nodes a region ({box} or {nodes}) selects. Throws InputError naming `what` for an index
// out of range or a region that holds no node.
std::vector<uint32_t> select_nodes(const FixedRegionDesc& region, const VolumeMesh& mesh,
                                   const SourceLocation& where, const char* what);

// A vector series evaluated without allocation: piecewise linear, held outside its points.
class TimeSeries {
 public:
  explicit TimeSeries(const TimeSeriesDesc& desc) : times_(desc.times_s), values_(desc.values) {}
  Vec3 value(double t) const noexcept;
  Vec3 rate(double t) const noexcept;  // d value / dt; 0 outside the points

 private:
  size_t segment(double t) const noexcept;  // i with times_[i] <= t < times_[i+1]
  std::vector<double> times_;
  std::vector<Vec3> values_;
};

class BoundaryMotion {
 public:
  // nullptr when the body has no prescribed motion and no plate. Marks every node the engine
  // moves in `fixed` (the model's held-node mask). Throws InputError (a region holding no node,
  // managed nodes on a mesh without tetrahedra).
  static std::unique_ptr<BoundaryMotion> build(const BodyDesc& desc, const VolumeMesh& mesh,
                                               const MaterialDesc& material,
                                               std::span<const double> masses,
                                               std::vector<uint8_t>& fixed);

  // The same motion on a cut body's mesh (topology/cut_mesh.hpp's TopologyEdit): each copy of a
  // moved node is moved as it was (its series and plate; its saved velocity and stuck anchor come
  // with carry_state_from), a removed node's motion goes; the managed nodes' masses are `masses`
  // and their stiffness bound is computed again on `mesh`. Reads nothing after_step writes, so it
  // may run off the tick. Allocates.
  std::unique_ptr<BoundaryMotion> carried(std::span<const uint32_t> node_source,
                                          const VolumeMesh& mesh,
                                          std::span<const double> masses) const;
  // A carried motion takes the state `source` (the motion it was carried from) has now: the
  // managed nodes' saved velocities, stuck flags and anchors. For a cut prepared off the tick and
  // installed ticks later. Allocates nothing.
  void carry_state_from(const BoundaryMotion& source) noexcept;
  // Whether after_step needs the model's internal forces (some node has free components).
  bool needs_internal_forces() const noexcept { return !managed_.empty(); }
  size_t held_count() const noexcept { return held_.size(); }
  size_t managed_count() const noexcept { return managed_.size(); }

  // Puts the moved nodes where their motion says at `time` (positions, velocities: 3 per node).
  void place(std::span<double> positions, std::span<double> velocities, double time) const noexcept;
  // Before the model step at `time`: places the held nodes, keeps the managed nodes' velocities
  // (the model zeroes a held node's velocity).
  void before_step(std::span<double> positions, std::span<double> velocities, double time) noexcept;
  // After the model step from `time` by `dt`: held nodes to time + dt, managed nodes advanced.
  // `external` is the step's external force (gravity + contact), N per node.
  void after_step(ModelInstance& model, std::span<double> positions, std::span<double> velocities,
                  std::span<const double> external, double time, double dt) noexcept;
  // Checkpoints: what after_step carries between steps (managed nodes' saved velocities, stuck
  // flags and anchors), 7 numbers per managed node. load_state: false when the count differs.
  std::vector<double> save_state() const;
  bool load_state(const std::vector<double>& state) noexcept;

 private:
  struct Held {  // every axis prescribed
    uint32_t node;
    std::array<int32_t, 3> series;  // per axis: index into series_, -1 = at rest
  };
  struct Managed {  // some axes free
    uint32_t node;
    std::array<int32_t, 3> series;      // per axis: index into series_, -1 = free
    int32_t plate = -1;                 // index into plates_, -1 = none
    std::array<double, 3> stiffness{};  // diagonal bound of the rest stiffness, N/m
    double mass = 0;                    // kg
    Vec3 saved_velocity{};              // m/s, before the model zeroed it
    bool stuck = false;                 // glued to its stuck plate
    Vec3 anchor{};  // stuck: position in the plate's frame (minus its motion), m
  };
  struct Plate {
    Vec3 point, normal;
    int32_t motion;  // index into series_
    bool stuck;
  };

  void advance(Managed& node, const double* force, double* x, double* v, double time,
               double dt) const noexcept;

  std::vector<double> rest_;  // 3 per node, m
  std::vector<TimeSeries> series_;
  std::vector<Held> held_;
  std::vector<Managed> managed_;
  std::vector<Plate> plates_;
  std::vector<uint32_t> managed_source_;  // carried: per managed node, its source's entry
  std::vector<double> forces_;   // 3 per node, N: the model's internal forces (sized at load)
  double alpha_ = 0, beta_ = 0;  // Rayleigh damping of the body's material
  double lambda_ = 0, mu_ = 0;   // its Lame parameters, Pa (the managed nodes' stiffness bound)
};

}  // namespace tacta
