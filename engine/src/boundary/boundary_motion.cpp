#include "boundary/boundary_motion.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace tacta {

namespace {

using Mat3 = Eigen::Matrix3d;
using V3 = Eigen::Vector3d;

// A diagonal that bounds the rest stiffness of linear elasticity on the tets (N/m, 3 per node):
// per row, the sum of the absolute entries of that row of every element matrix
// K_ab = V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I), g the shape gradients. With it
// 2D - K is positive definite, the condition for the engine's per-node (Jacobi) updates of the
// managed nodes, and for the sweep between them and the model's solve, to converge.
std::vector<std::array<double, 3>> stiffness_bound(const VolumeMesh& mesh, double lambda,
                                                   double mu) {
  std::vector<std::array<double, 3>> bound(mesh.node_count(), std::array<double, 3>{});
  const auto x = [&](uint32_t i) {
    return V3(mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]);
  };
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const uint32_t* n = &mesh.tets[4 * t];
    Mat3 edges;
    edges << x(n[1]) - x(n[0]), x(n[2]) - x(n[0]), x(n[3]) - x(n[0]);
    const double volume = std::abs(edges.determinant()) / 6.0;
    if (!(volume > 0)) continue;
    const Mat3 inverse = edges.inverse();  // rows: gradients of the barycentric weights 1..3
    const std::array<V3, 4> g{V3(-(inverse.row(0) + inverse.row(1) + inverse.row(2)).transpose()),
                              V3(inverse.row(0).transpose()), V3(inverse.row(1).transpose()),
                              V3(inverse.row(2).transpose())};
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const Mat3 k = volume * (lambda * g[a] * g[b].transpose() + mu * g[b] * g[a].transpose() +
                                 mu * g[a].dot(g[b]) * Mat3::Identity());
        for (int r = 0; r < 3; ++r)
          bound[n[a]][static_cast<size_t>(r)] += k.row(r).cwiseAbs().sum();
      }
  }
  return bound;
}

}  // namespace

std::vector<uint32_t> select_nodes(const FixedRegionDesc& region, const VolumeMesh& mesh,
                                   const SourceLocation& where, const char* what) {
  const auto inside = [&](const double* p) {
    for (size_t a = 0; a < 3; ++a)
      if (p[a] < (*region.box)[0][a] || p[a] > (*region.box)[1][a]) return false;
    return true;
  };
  std::vector<uint32_t> nodes;
  const size_t n = mesh.node_count();
  if (region.box)
    for (size_t i = 0; i < n; ++i)
      if (inside(&mesh.positions[3 * i])) nodes.push_back(static_cast<uint32_t>(i));
  for (uint32_t node : region.indices) {
    if (node >= n)
      throw InputError(where, std::string(what) + ": node " + std::to_string(node) +
                                  " is out of range (the mesh has " + std::to_string(n) +
                                  " nodes)");
    nodes.push_back(node);
  }
  if (nodes.empty())
    throw InputError(
        where, std::string(what) +
                   ": a region holds no node of the mesh (check its box against the mesh bounds)");
  return nodes;
}

size_t TimeSeries::segment(double t) const noexcept {
  const auto it = std::upper_bound(times_.begin(), times_.end(), t);
  return static_cast<size_t>(std::max<std::ptrdiff_t>(it - times_.begin() - 1, 0));
}

Vec3 TimeSeries::value(double t) const noexcept {
  if (t <= times_.front()) return values_.front();
  if (t >= times_.back()) return values_.back();
  const size_t i = segment(t);
  const double s = (t - times_[i]) / (times_[i + 1] - times_[i]);
  Vec3 out;
  for (size_t a = 0; a < 3; ++a) out[a] = values_[i][a] + s * (values_[i + 1][a] - values_[i][a]);
  return out;
}

Vec3 TimeSeries::rate(double t) const noexcept {
  if (t < times_.front() || t >= times_.back()) return {0, 0, 0};
  const size_t i = segment(t);
  const double span = times_[i + 1] - times_[i];
  Vec3 out;
  for (size_t a = 0; a < 3; ++a) out[a] = (values_[i + 1][a] - values_[i][a]) / span;
  return out;
}

std::unique_ptr<BoundaryMotion> BoundaryMotion::build(const BodyDesc& desc, const VolumeMesh& mesh,
                                                      const MaterialDesc& material,
                                                      std::span<const double> masses,
                                                      std::vector<uint8_t>& fixed) {
  if (desc.prescribed.empty() && desc.plates.empty()) return nullptr;
  auto motion = std::unique_ptr<BoundaryMotion>(new BoundaryMotion());
  BoundaryMotion& m = *motion;
  m.rest_ = mesh.positions;
  m.alpha_ = material.rayleigh_mass;
  m.beta_ = material.rayleigh_stiffness;
  m.lambda_ = material.lame_lambda;
  m.mu_ = material.lame_mu;
  const size_t n = mesh.node_count();
  // Per node and axis: the series that drives it (-1: free); a later entry wins on its axes,
  // and a `fixed` node stays fixed.
  std::vector<std::array<int32_t, 3>> axis_series(n, {-1, -1, -1});
  std::vector<int32_t> plate_of(n, -1);
  for (const PrescribedDesc& p : desc.prescribed) {
    const auto index = static_cast<int32_t>(m.series_.size());
    m.series_.emplace_back(p.displacement);
    for (uint32_t node : select_nodes(p.region, mesh, p.where, "prescribed"))
      for (size_t a = 0; a < 3; ++a)
        if (p.axes[a]) axis_series[node][a] = index;
  }
  for (const PlateDesc& p : desc.plates) {
    const auto index = static_cast<int32_t>(m.plates_.size());
    m.plates_.push_back({p.point, p.normal, static_cast<int32_t>(m.series_.size()), p.stuck});
    m.series_.emplace_back(p.motion);
    for (uint32_t node : select_nodes(p.region, mesh, p.where, "plates")) plate_of[node] = index;
  }
  std::vector<std::array<double, 3>> stiffness;
  for (uint32_t i = 0; i < n; ++i) {
    if (fixed[i]) continue;
    const std::array<int32_t, 3>& s = axis_series[i];
    const bool all = s[0] >= 0 && s[1] >= 0 && s[2] >= 0;
    const bool some = s[0] >= 0 || s[1] >= 0 || s[2] >= 0;
    if (all) {
      m.held_.push_back({i, s});
    } else if (some || plate_of[i] >= 0) {
      if (mesh.tets.empty())
        throw InputError(
            desc.where,
            "prescribed/plates: nodes with free axes (per-axis constraints, plates) need a "
            "tetrahedral mesh");
      if (stiffness.empty()) stiffness = stiffness_bound(mesh, m.lambda_, m.mu_);
      Managed node;
      node.node = i;
      node.series = s;
      node.plate = plate_of[i];
      node.stiffness = stiffness[i];
      node.mass = masses[i];
      m.managed_.push_back(node);
    } else {
      continue;
    }
    fixed[i] = 1;  // the model holds it; the engine moves it
  }
  m.forces_.assign(3 * n, 0.0);
  return motion;
}

std::unique_ptr<BoundaryMotion> BoundaryMotion::carried(std::span<const uint32_t> node_source,
                                                        const VolumeMesh& mesh,
                                                        std::span<const double> masses) const {
  auto motion = std::unique_ptr<BoundaryMotion>(new BoundaryMotion());
  BoundaryMotion& m = *motion;
  m.rest_ = mesh.positions;
  m.series_ = series_;
  m.plates_ = plates_;
  m.alpha_ = alpha_, m.beta_ = beta_, m.lambda_ = lambda_, m.mu_ = mu_;
  // Per old node: its entry in held_ or managed_ (-1: not moved); both lists are in node order.
  std::vector<int64_t> held_at(rest_.size() / 3, -1), managed_at(rest_.size() / 3, -1);
  for (size_t i = 0; i < held_.size(); ++i) held_at[held_[i].node] = int64_t(i);
  for (size_t i = 0; i < managed_.size(); ++i) managed_at[managed_[i].node] = int64_t(i);
  const std::vector<std::array<double, 3>> stiffness =
      managed_.empty() ? std::vector<std::array<double, 3>>{} : stiffness_bound(mesh, lambda_, mu_);
  for (uint32_t n = 0; n < node_source.size(); ++n) {
    const uint32_t old = node_source[n];
    if (held_at[old] >= 0) {
      m.held_.push_back(held_[size_t(held_at[old])]);
      m.held_.back().node = n;
    } else if (managed_at[old] >= 0) {
      // What the scene set only: the state after_step writes (saved velocity, stuck flag,
      // anchor) may be changing on the haptic thread; carry_state_from takes it.
      const Managed& from = managed_[size_t(managed_at[old])];
      Managed& node = m.managed_.emplace_back();
      node.node = n;
      node.series = from.series;
      node.plate = from.plate;
      node.stiffness = stiffness[n];
      node.mass = masses[n];
      m.managed_source_.push_back(static_cast<uint32_t>(managed_at[old]));
    }
  }
  m.forces_.assign(3 * size_t(mesh.node_count()), 0.0);
  return motion;
}

void BoundaryMotion::carry_state_from(const BoundaryMotion& source) noexcept {
  for (size_t i = 0; i < managed_source_.size(); ++i) {
    const Managed& from = source.managed_[managed_source_[i]];
    managed_[i].saved_velocity = from.saved_velocity;
    managed_[i].stuck = from.stuck;
    managed_[i].anchor = from.anchor;
  }
}

void BoundaryMotion::place(std::span<double> x, std::span<double> v, double time) const noexcept {
  for (const Held& h : held_)
    for (size_t a = 0; a < 3; ++a) {
      const size_t k = 3 * size_t{h.node} + a;
      const int32_t s = h.series[a];
      x[k] = rest_[k] + (s >= 0 ? series_[static_cast<size_t>(s)].value(time)[a] : 0.0);
      v[k] = s >= 0 ? series_[static_cast<size_t>(s)].rate(time)[a] : 0.0;
    }
  for (const Managed& node : managed_)
    for (size_t a = 0; a < 3; ++a) {
      const int32_t s = node.series[a];
      if (s < 0) continue;
      const size_t k = 3 * size_t{node.node} + a;
      x[k] = rest_[k] + series_[static_cast<size_t>(s)].value(time)[a];
      v[k] = series_[static_cast<size_t>(s)].rate(time)[a];
    }
}

void BoundaryMotion::before_step(std::span<double> x, std::span<double> v, double time) noexcept {
  place(x, v, time);
  for (Managed& node : managed_)
    for (size_t a = 0; a < 3; ++a) node.saved_velocity[a] = v[3 * size_t{node.node} + a];
}

void BoundaryMotion::after_step(ModelInstance& model, std::span<double> x, std::span<double> v,
                                std::span<const double> external, double time, double dt) noexcept {
  place(x, v, time + dt);
  if (managed_.empty()) return;
  // Internal forces at the new positions of the free nodes (the managed ones where they were).
  // A model without internal forces (swapped in at run time; the loader refuses one in the
  // scene): the managed nodes stay held where they are rather than move on external forces alone.
  if (!model.internal_forces(x.data(), forces_.data())) {
    for (const Managed& node : managed_)
      for (size_t a = 0; a < 3; ++a) v[3 * size_t{node.node} + a] = 0.0;
    return;
  }
  for (Managed& node : managed_) {
    const size_t b = 3 * size_t{node.node};
    double force[3];
    for (size_t a = 0; a < 3; ++a) force[a] = forces_[b + a] + external[b + a];
    advance(node, force, &x[b], &v[b], time, dt);
  }
}

// One linearly implicit Euler step of a node with the rest of the body frozen, its stiffness
// replaced by the bound D (convergent, and over-damped in motion):
// (m (1 + h alpha) I + h (h + beta) D) dv = h (f - alpha m v - (h + beta) D v), then the node's
// constraints (prescribed axes, a plate it touches) fix their components of the new state.
void BoundaryMotion::advance(Managed& node, const double* force, double* x, double* v, double time,
                             double dt) const noexcept {
  const double h = dt;
  const Mat3 k = V3(node.stiffness[0], node.stiffness[1], node.stiffness[2]).asDiagonal();
  const V3 v0(node.saved_velocity[0], node.saved_velocity[1], node.saved_velocity[2]);
  const V3 x0(x[0], x[1], x[2]);
  const Mat3 a = node.mass * (1.0 + h * alpha_) * Mat3::Identity() + h * (h + beta_) * k;
  const V3 rhs =
      h * (V3(force[0], force[1], force[2]) - alpha_ * node.mass * v0 - (h + beta_) * (k * v0));

  // Constraints at time + dt: rows d . x = s, d . v = w (at most 3 independent rows).
  Mat3 d = Mat3::Zero();
  V3 s = V3::Zero(), w = V3::Zero();
  int rows = 0;
  const auto add = [&](const V3& dir, double position, double velocity) {
    V3 rest_part = dir;
    for (int r = 0; r < rows; ++r)
      rest_part -= d.row(r).dot(dir) / d.row(r).squaredNorm() * d.row(r).transpose();
    if (rows >= 3 || rest_part.norm() < 1e-9) return;  // implied by the rows already there
    d.row(rows) = dir.transpose();
    s[rows] = position;
    w[rows] = velocity;
    ++rows;
  };
  for (size_t ax = 0; ax < 3; ++ax) {
    const int32_t series = node.series[ax];
    if (series < 0) continue;
    const size_t k3 = 3 * size_t{node.node} + ax;
    add(V3::Unit(static_cast<Eigen::Index>(ax)),
        rest_[k3] + series_[static_cast<size_t>(series)].value(time + h)[ax],
        series_[static_cast<size_t>(series)].rate(time + h)[ax]);
  }
  // Solves for the new velocity with the current rows: free components from the implicit
  // update, constrained ones from the targets (the constrained subspace P_c, free P_f).
  const auto row_gram = [&]() {  // d d^T, with identity on the unused rows (zero targets)
    Mat3 dd = d * d.transpose();
    for (int r = rows; r < 3; ++r) dd(r, r) = 1.0;
    return dd;
  };
  const auto solve = [&]() -> V3 {
    if (rows == 0) return v0 + a.ldlt().solve(rhs);
    const V3 target_v =
        d.transpose() * row_gram().ldlt().solve(w);  // in span(d), satisfies d v = w
    Mat3 q = Mat3::Zero();                           // orthonormal basis of the rows, as columns
    Eigen::HouseholderQR<Mat3> qr(d.transpose());
    const Mat3 full_q = qr.householderQ();
    q.leftCols(rows) = full_q.leftCols(rows);
    const Mat3 pc = q * q.transpose(), pf = Mat3::Identity() - pc;
    const V3 dc = target_v - pc * v0;
    const V3 df = (pf * a * pf + pc).ldlt().solve(pf * (rhs - a * dc));
    return v0 + dc + pf * df;
  };
  V3 v1 = solve();
  if (node.plate >= 0) {
    const Plate& plate = plates_[static_cast<size_t>(node.plate)];
    const TimeSeries& motion = series_[static_cast<size_t>(plate.motion)];
    const V3 n(plate.normal[0], plate.normal[1], plate.normal[2]);
    const Vec3 shift = motion.value(time + h), shift_rate = motion.rate(time + h);
    const V3 p(plate.point[0] + shift[0], plate.point[1] + shift[1], plate.point[2] + shift[2]);
    const V3 pv(shift_rate[0], shift_rate[1], shift_rate[2]);
    const double gap = n.dot(x0 + h * v1 - p);  // < 0: the free motion would pass the plate
    if (plate.stuck && !node.stuck && gap < 0) {
      node.stuck = true;
      const V3 on_plate = x0 + h * v1 - gap * n - V3(shift[0], shift[1], shift[2]);
      node.anchor = {on_plate[0], on_plate[1], on_plate[2]};
    }
    if (node.stuck) {
      rows = 0;
      for (int ax = 0; ax < 3; ++ax)
        add(V3::Unit(ax), node.anchor[static_cast<size_t>(ax)] + shift[static_cast<size_t>(ax)],
            pv[ax]);
      v1 = solve();
    } else if (gap < 0) {
      add(n, n.dot(p), n.dot(pv));
      v1 = solve();
    }
  }
  // Free components move by h v; constrained ones sit on their targets.
  V3 x1 = x0 + h * v1;
  if (rows > 0)
    x1 += d.transpose() * row_gram().ldlt().solve(s - d * x1);  // nearest point with d x = s
  for (int ax = 0; ax < 3; ++ax) {
    x[ax] = x1[ax];
    v[ax] = v1[ax];
  }
}

std::vector<double> BoundaryMotion::save_state() const {
  std::vector<double> state;
  state.reserve(7 * managed_.size());
  for (const Managed& m : managed_) {
    for (size_t k = 0; k < 3; ++k) state.push_back(m.saved_velocity[k]);
    state.push_back(m.stuck ? 1.0 : 0.0);
    for (size_t k = 0; k < 3; ++k) state.push_back(m.anchor[k]);
  }
  return state;
}

bool BoundaryMotion::load_state(const std::vector<double>& state) noexcept {
  if (state.size() != 7 * managed_.size()) return false;
  const double* s = state.data();
  for (Managed& m : managed_) {
    for (size_t k = 0; k < 3; ++k) m.saved_velocity[k] = *s++;
    m.stuck = *s++ != 0.0;
    for (size_t k = 0; k < 3; ++k) m.anchor[k] = *s++;
  }
  return true;
}

}  // namespace tacta
