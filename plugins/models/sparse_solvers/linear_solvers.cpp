#include "linear_solvers.hpp"

#include <Eigen/LU>
#include <Eigen/OrderingMethods>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "hot_path.hpp"
#include "lanes4.hpp"
#include "ldlt_symbolic.hpp"
#include "tacta/models/state_blob.hpp"

namespace tacta::models::sparse {

namespace {
double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += a[i] * b[i];
  return sum;
}
}  // namespace

ConjugateGradientSolver::ConjugateGradientSolver(const BlockSparseMatrix& pattern,
                                                 Preconditioner preconditioner, int max_iterations,
                                                 double tolerance, int refactor_interval,
                                                 const tacta_host_services* host)
    : preconditioner_(preconditioner),
      max_iterations_(max_iterations),
      tolerance_(tolerance),
      refactor_interval_(std::max(1, refactor_interval)),
      inverse_columns_(12 * static_cast<size_t>(pattern.node_count()), 0.0),
      x_(4 * static_cast<size_t>(pattern.node_count()), 0.0),
      r_(x_.size(), 0.0),
      z_(x_.size(), 0.0),
      p_(x_.size(), 0.0),
      ap_(x_.size(), 0.0),
      padded_(pattern) {
  if (preconditioner_ == Preconditioner::kIncompleteCholesky)
    incomplete_cholesky_ = std::make_unique<BlockIncompleteCholesky>(pattern);
  else
    team_ = RowTeam(host, pattern.node_count(), kMinThreadedNodes);
  if (team_.may_thread()) p_next_.assign(x_.size(), 0.0);
}

void ConjugateGradientSolver::build_preconditioner(const BlockSparseMatrix& a) {
  if (incomplete_cholesky_) {
    if (solves_since_factor_ == 0) replaced_pivots_ = incomplete_cholesky_->factorize(a);
    solves_since_factor_ = (solves_since_factor_ + 1) % refactor_interval_;
    return;
  }
  if (team_.threaded()) {
    team_.run([&](uint32_t, uint32_t begin, uint32_t end) {
      padded_.assign_rows(a.values(), begin, end);
      invert_diagonal(a, begin, end);
    });
    return;
  }
  padded_.assign(a.values());
  invert_diagonal(a, 0, a.node_count());
}

void ConjugateGradientSolver::invert_diagonal(const BlockSparseMatrix& a, uint32_t begin,
                                              uint32_t end) {
  for (uint32_t i = begin; i < end; ++i) {
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> block(
        a.block(a.diagonal_block(i)));
    Eigen::Matrix3d inverse = Eigen::Matrix3d::Zero();
    if (preconditioner_ == Preconditioner::kJacobi)
      inverse.diagonal() = block.diagonal().cwiseInverse();
    else
      inverse = block.inverse();
    double* columns = &inverse_columns_[12 * static_cast<size_t>(i)];
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) columns[4 * c + r] = inverse(r, c);
  }
}

void ConjugateGradientSolver::apply_preconditioner(const double* r, double* z) const {
  if (incomplete_cholesky_) {
    incomplete_cholesky_->apply(r, z);
    return;
  }
  const size_t nodes = r_.size() / 4;
  const double* columns = inverse_columns_.data();
  for (size_t i = 0; i < nodes; ++i) {
    const double* m = columns + 12 * i;
    for (int l = 0; l < 4; ++l)
      z[4 * i + l] = r[4 * i] * m[l] + r[4 * i + 1] * m[4 + l] + r[4 * i + 2] * m[8 + l];
  }
}

TACTA_HOT_PATH std::pair<double, double> ConjugateGradientSolver::update_rows(double alpha,
                                                                              size_t begin,
                                                                              size_t end) {
  const Lanes4 a4 = TACTA_SPLAT4(alpha);
  Lanes4 r_norm2 = TACTA_SPLAT4(0.0), rz = r_norm2;
  for (size_t i = begin; i < end; ++i) {
    Lanes4 x, p, r, ap, c0, c1, c2;
    std::memcpy(&x, &x_[4 * i], sizeof x);
    std::memcpy(&p, &p_[4 * i], sizeof p);
    std::memcpy(&r, &r_[4 * i], sizeof r);
    std::memcpy(&ap, &ap_[4 * i], sizeof ap);
    x += a4 * p;
    r -= a4 * ap;
    std::memcpy(&x_[4 * i], &x, sizeof x);
    std::memcpy(&r_[4 * i], &r, sizeof r);
    const double* m = &inverse_columns_[12 * i];
    std::memcpy(&c0, m, sizeof c0);
    std::memcpy(&c1, m + 4, sizeof c1);
    std::memcpy(&c2, m + 8, sizeof c2);
    const Lanes4 z = TACTA_SPLAT4(r[0]) * c0 + TACTA_SPLAT4(r[1]) * c1 + TACTA_SPLAT4(r[2]) * c2;
    std::memcpy(&z_[4 * i], &z, sizeof z);
    r_norm2 += r * r;
    rz += r * z;
  }
  return {(r_norm2[0] + r_norm2[1]) + (r_norm2[2] + r_norm2[3]), (rz[0] + rz[1]) + (rz[2] + rz[3])};
}

TACTA_HOT_PATH std::pair<double, double> ConjugateGradientSolver::update(double alpha,
                                                                         double converged_norm2) {
  const size_t nodes = r_.size() / 4;
  if (!incomplete_cholesky_)  // one pass, 4-wide: the (block) Jacobi inverse is local
    return update_rows(alpha, 0, nodes);
  double r_norm2 = 0.0;
  for (size_t i = 0; i < r_.size(); ++i) {  // the fourth entries stay 0
    x_[i] += alpha * p_[i];
    r_[i] -= alpha * ap_[i];
    r_norm2 += r_[i] * r_[i];
  }
  if (r_norm2 <= converged_norm2) return {r_norm2, 0.0};  // z is not needed any more
  apply_preconditioner(r_.data(), z_.data());
  return {r_norm2, dot(r_, z_)};
}

double ConjugateGradientSolver::multiply(const BlockSparseMatrix& a, const double* x,
                                         double* y) const {
  // IC(0) needs few products: copying A to the padded layout would cost more than it saves.
  return incomplete_cholesky_ ? a.multiply(x, y, 4) : padded_.multiply_symmetric(x, y);
}

void ConjugateGradientSolver::state_fields(StateIo& io) {
  io.value(solves_since_factor_, "solves_since_factor");
  io.value(replaced_pivots_, "replaced_pivots");
  if (incomplete_cholesky_) {
    incomplete_cholesky_->state_fields(io);
    return;
  }
  io.vector(inverse_columns_, "jacobi_inverse");
  padded_.state_fields(io);
}

SolveReport ConjugateGradientSolver::solve(const BlockSparseMatrix& a, const double* b, double* x,
                                           bool keep_preconditioner, double residual_floor) {
  if (!keep_preconditioner) build_preconditioner(a);
  residual_floor_ = residual_floor;
  return iterate(a, b, x, max_iterations_);
}

SolveReport ConjugateGradientSolver::iterate(const BlockSparseMatrix& a, const double* b, double* x,
                                             int max_iterations) {
  if (team_.threaded()) return iterate_threaded(b, x, max_iterations);
  const size_t nodes = r_.size() / 4;
  double b_norm2 = 0.0;
  for (size_t i = 0; i < 3 * nodes; ++i) b_norm2 += b[i] * b[i];
  SolveReport report;
  report.replaced_pivots = replaced_pivots_;
  if (b_norm2 == 0.0) {
    std::fill_n(x, 3 * nodes, 0.0);
    return report;
  }
  const double scale2 = std::max(b_norm2, residual_floor_ * residual_floor_);
  const double threshold2 = tolerance_ * tolerance_ * scale2;
  for (size_t i = 0; i < nodes; ++i)
    for (size_t c = 0; c < 3; ++c) x_[4 * i + c] = x[3 * i + c];
  multiply(a, x_.data(), ap_.data());
  for (size_t i = 0; i < nodes; ++i)
    for (size_t c = 0; c < 3; ++c) r_[4 * i + c] = b[3 * i + c] - ap_[4 * i + c];
  auto write_back = [&] {
    for (size_t i = 0; i < nodes; ++i)
      for (size_t c = 0; c < 3; ++c) x[3 * i + c] = x_[4 * i + c];
  };
  double r_norm2 = dot(r_, r_);
  if (!(r_norm2 <= b_norm2)) {  // the guess is worse than none (or not finite): start from zero
    report.warm_start_rejected = true;
    std::fill(x_.begin(), x_.end(), 0.0);
    for (size_t i = 0; i < nodes; ++i)
      for (size_t c = 0; c < 3; ++c) r_[4 * i + c] = b[3 * i + c];
    r_norm2 = b_norm2;
  }
  report.relative_residual = std::sqrt(r_norm2 / scale2);
  if (r_norm2 <= threshold2) {
    write_back();
    return report;
  }
  apply_preconditioner(r_.data(), z_.data());
  p_ = z_;
  double rz = dot(r_, z_);
  for (int k = 0; k < max_iterations; ++k) {
    const double p_ap = multiply(a, p_.data(), ap_.data());
    if (!(p_ap > 0.0)) break;  // not positive definite along p (or NaN): stop, report below
    const auto [r_norm2_next, rz_next] = update(rz / p_ap, threshold2);
    r_norm2 = r_norm2_next;
    report.iterations = k + 1;
    report.relative_residual = std::sqrt(r_norm2 / scale2);
    if (r_norm2 <= threshold2) {
      write_back();
      return report;
    }
    const double beta = rz_next / rz;
    rz = rz_next;
    for (size_t i = 0; i < p_.size(); ++i) p_[i] = z_[i] + beta * p_[i];
  }
  write_back();
  report.converged = false;
  return report;
}

SolveReport ConjugateGradientSolver::iterate_threaded(const double* b, double* x,
                                                      int max_iterations) {
  const RowTeam& team = team_;
  SolveReport report;
  report.replaced_pivots = replaced_pivots_;
  // z = M^-1 r and p = z for rows [begin, end); returns their r . z.
  const auto precondition_rows = [&](size_t begin, size_t end) {
    double rz = 0.0;
    for (size_t i = begin; i < end; ++i) {
      const double* m = &inverse_columns_[12 * i];
      for (int l = 0; l < 4; ++l)
        z_[4 * i + l] = r_[4 * i] * m[l] + r_[4 * i + 1] * m[4 + l] + r_[4 * i + 2] * m[8 + l];
      for (int l = 0; l < 4; ++l) p_[4 * i + l] = z_[4 * i + l];
      rz += r_[4 * i] * z_[4 * i] + r_[4 * i + 1] * z_[4 * i + 1] + r_[4 * i + 2] * z_[4 * i + 2];
    }
    return rz;
  };
  const auto write_back = [&] {
    team.run([&](uint32_t, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i)
        for (size_t c = 0; c < 3; ++c) x[3 * i + c] = x_[4 * i + c];
    });
  };
  // x in the 4-per-node layout, and |b|^2.
  team.run([&](uint32_t chunk, size_t begin, size_t end) {
    double b_norm2 = 0.0;
    for (size_t i = begin; i < end; ++i)
      for (size_t c = 0; c < 3; ++c) {
        x_[4 * i + c] = x[3 * i + c];
        b_norm2 += b[3 * i + c] * b[3 * i + c];
      }
    team.sums(chunk).s[0] = b_norm2;
  });
  const double b_norm2 = team.total(0);
  if (b_norm2 == 0.0) {
    std::fill_n(x, 3 * (r_.size() / 4), 0.0);
    return report;
  }
  const double scale2 = std::max(b_norm2, residual_floor_ * residual_floor_);
  const double threshold2 = tolerance_ * tolerance_ * scale2;
  // r = b - A x, z = M^-1 r, p = z.
  team.run([&](uint32_t chunk, uint32_t begin, uint32_t end) {
    padded_.multiply_rows(x_.data(), ap_.data(), begin, end);
    double r_norm2 = 0.0;
    for (size_t i = begin; i < end; ++i)
      for (size_t c = 0; c < 3; ++c) {
        r_[4 * i + c] = b[3 * i + c] - ap_[4 * i + c];
        r_norm2 += r_[4 * i + c] * r_[4 * i + c];
      }
    team.sums(chunk).s[0] = r_norm2;
    team.sums(chunk).s[1] = precondition_rows(begin, end);
  });
  double r_norm2 = team.total(0), rz = team.total(1);
  if (!(r_norm2 <= b_norm2)) {  // the guess is worse than none (or not finite): start from zero
    report.warm_start_rejected = true;
    team.run([&](uint32_t chunk, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i)
        for (size_t c = 0; c < 3; ++c) {
          x_[4 * i + c] = 0.0;
          r_[4 * i + c] = b[3 * i + c];
        }
      team.sums(chunk).s[1] = precondition_rows(begin, end);
    });
    r_norm2 = b_norm2;
    rz = team.total(1);
  }
  report.relative_residual = std::sqrt(r_norm2 / scale2);
  if (r_norm2 <= threshold2) {
    write_back();
    return report;
  }
  double beta = 0.0;
  bool fused = false;  // from the second iteration: p = z + beta p formed inside the product
  for (int k = 0; k < max_iterations; ++k) {
    team.run([&](uint32_t chunk, uint32_t begin, uint32_t end) {
      team.sums(chunk).s[0] = fused ? padded_.multiply_rows(p_.data(), ap_.data(), begin, end,
                                                            z_.data(), beta, p_next_.data())
                                    : padded_.multiply_rows(p_.data(), ap_.data(), begin, end);
    });
    if (fused) std::swap(p_, p_next_);
    const double p_ap = team.total(0);
    if (!(p_ap > 0.0)) break;  // not positive definite along p (or NaN): stop, report below
    const double alpha = rz / p_ap;
    team.run([&](uint32_t chunk, size_t begin, size_t end) {
      const auto [rr, rzc] = update_rows(alpha, begin, end);
      team.sums(chunk).s[0] = rr;
      team.sums(chunk).s[1] = rzc;
    });
    r_norm2 = team.total(0);
    const double rz_next = team.total(1);
    report.iterations = k + 1;
    report.relative_residual = std::sqrt(r_norm2 / scale2);
    if (r_norm2 <= threshold2) {
      write_back();
      return report;
    }
    beta = rz_next / rz;
    rz = rz_next;
    fused = true;
  }
  write_back();
  report.converged = false;
  return report;
}

using ColumnMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using EigenLdlt = Eigen::SimplicialLDLT<ColumnMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>>;

// Exposes Eigen's numeric factorisation of an already ordered upper-triangular matrix, which
// skips the copy that SimplicialLDLT::factorize() makes on every call.
struct CholeskySolver::Ldlt : public EigenLdlt {
  // The symbolic analysis of the upper triangle as it is (no permutation): the state Eigen's
  // analyzePattern() leaves, with the tree and column counts from ldlt_symbolic (the same
  // numbers, in time near linear in a's entries instead of in L's).
  void analyze_preordered_upper(const ColumnMatrix& a) {
    const int n = static_cast<int>(a.rows());
    const auto count = static_cast<size_t>(n);
    this->m_P.resize(0);
    this->m_Pinv.resize(0);
    this->m_parent.resize(n);
    this->m_nonZerosPerCol.resize(n);
    ldlt_symbolic(n, a.outerIndexPtr(), a.innerIndexPtr(), {this->m_parent.data(), count},
                  {this->m_nonZerosPerCol.data(), count});
    this->m_matrix.resize(n, n);
    int* starts = this->m_matrix.outerIndexPtr();
    starts[0] = 0;
    for (int k = 0; k < n; ++k) starts[k + 1] = starts[k] + this->m_nonZerosPerCol[k];
    this->m_matrix.resizeNonZeros(starts[n]);
    // SimplicialCholeskyBase makes this flag private: named through the base that declares it.
    this->Eigen::SparseSolverBase<EigenLdlt>::m_isInitialized = true;
    this->m_info = Eigen::Success;
    this->m_analysisIsOk = true;
    this->m_factorizationIsOk = false;
  }
  void factorize_preordered_upper(const ColumnMatrix& a) {
    this->template factorize_preordered<true>(a);
  }
  // factorize_preordered resizes the diagonal to the matrix's size (a no-op once it has it):
  // sized here, a step's factorisation allocates nothing for it.
  void size_diagonal(Eigen::Index n) { this->m_diag.resize(n); }
};

namespace {

// The scalar pattern (3 unknowns per node) of the full symmetric matrix whose upper block
// triangle is `pattern`, built in compressed columns with ascending rows: what setFromTriplets
// makes of every entry and its mirror. The values are left unset: the ordering reads the pattern.
ColumnMatrix full_scalar_pattern(const BlockSparseMatrix& pattern) {
  const uint32_t nodes = pattern.node_count();
  const auto starts = pattern.row_starts(), columns = pattern.columns();
  const auto lower_starts = pattern.lower_starts(), lower_rows = pattern.lower_rows();
  ColumnMatrix full(3 * static_cast<int>(nodes), 3 * static_cast<int>(nodes));
  int* outer = full.outerIndexPtr();
  outer[0] = 0;
  for (uint32_t j = 0; j < nodes; ++j) {
    const int neighbours =
        static_cast<int>(lower_starts[j + 1] - lower_starts[j] + starts[j + 1] - starts[j]);
    for (uint32_t c = 0; c < 3; ++c) outer[3 * j + c + 1] = outer[3 * j + c] + 3 * neighbours;
  }
  // Eigen's minimum-degree ordering first grows the storage to this for its workspace: reserved
  // now, it is not moved to fresh memory there.
  const int entries = outer[3 * nodes];
  full.data().reserve(entries + entries / 5 + 2 * full.cols());
  full.resizeNonZeros(entries);
  int* inner = full.innerIndexPtr();
  for (uint32_t j = 0; j < nodes; ++j)
    for (uint32_t c = 0; c < 3; ++c) {
      // Node j's neighbours ascending: the lower triangle's (i < j), then its row (i >= j).
      int* at = inner + outer[3 * j + c];
      for (uint32_t k = lower_starts[j]; k < lower_starts[j + 1]; ++k)
        for (int r = 0; r < 3; ++r) *at++ = 3 * static_cast<int>(lower_rows[k]) + r;
      for (uint32_t k = starts[j]; k < starts[j + 1]; ++k)
        for (int r = 0; r < 3; ++r) *at++ = 3 * static_cast<int>(columns[k]) + r;
    }
  return full;
}

}  // namespace

CholeskySolver::CholeskySolver(const BlockSparseMatrix& pattern) : ldlt_(std::make_unique<Ldlt>()) {
  const int n = 3 * static_cast<int>(pattern.node_count());
  const auto starts = pattern.row_starts();
  const auto columns = pattern.columns();
  // The fill-reducing order. The pattern is already symmetric with its diagonal: AMDOrdering()
  // would first form A^T + A, the same pattern, so its minimum-degree step is called directly.
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  {
    ColumnMatrix full = full_scalar_pattern(pattern);
    Eigen::internal::minimum_degree_ordering(full, order);
  }
  new_index_.resize(n);
  for (int p = 0; p < n; ++p) new_index_[order.indices()[p]] = p;
  // Upper triangle in the new numbering, built in compressed columns with ascending rows (what
  // setFromTriplets would make), with the index of each entry's source in the block values. A
  // diagonal block holds both (r, c) and (c, r): take one of them. The entries are gathered by
  // row, then dealt to their columns row by row: each column's rows come out ascending.
  struct Entry {
    int col;
    uint32_t source;
  };
  const auto for_each_entry = [&](auto&& take) {
    for (uint32_t i = 0; i < pattern.node_count(); ++i)
      for (uint32_t k = starts[i]; k < starts[i + 1]; ++k)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) {
            const int row = new_index_[3 * i + r];
            const int col = new_index_[3 * columns[k] + c];
            if (columns[k] == i && row > col) continue;
            take(std::min(row, col), Entry{std::max(row, col), 9 * k + 3 * r + c});
          }
  };
  permuted_upper_.resize(n, n);
  int* outer = permuted_upper_.outerIndexPtr();
  std::fill_n(outer, n + 1, 0);
  std::vector<int> row_start(static_cast<size_t>(n) + 1, 0);
  for_each_entry([&](int row, const Entry& e) {
    ++row_start[row + 1];
    ++outer[e.col + 1];
  });
  for (int i = 0; i < n; ++i) {
    row_start[i + 1] += row_start[i];
    outer[i + 1] += outer[i];
  }
  std::vector<Entry> by_row(static_cast<size_t>(row_start[n]));
  {
    std::vector<int> fill(row_start.begin(), row_start.end() - 1);
    for_each_entry([&](int row, const Entry& e) { by_row[fill[row]++] = e; });
  }
  permuted_upper_.resizeNonZeros(outer[n]);
  std::fill_n(permuted_upper_.valuePtr(), outer[n], 0.0);
  value_source_.resize(by_row.size());
  std::vector<int> fill(outer, outer + n);
  for (int row = 0; row < n; ++row)
    for (int s = row_start[row]; s < row_start[row + 1]; ++s) {
      const int at = fill[by_row[s].col]++;
      permuted_upper_.innerIndexPtr()[at] = row;
      value_source_[at] = by_row[s].source;
    }
  ldlt_->analyze_preordered_upper(permuted_upper_);
  rhs_.resize(n);
  solution_.resize(n);
  ldlt_->size_diagonal(n);
}

CholeskySolver::~CholeskySolver() = default;

bool CholeskySolver::solve(const BlockSparseMatrix& a, const double* b, double* x,
                           bool keep_factor) {
  if (!keep_factor) {
    const auto values = a.values();
    double* target = permuted_upper_.valuePtr();
    for (size_t s = 0; s < value_source_.size(); ++s) target[s] = values[value_source_[s]];
    ldlt_->factorize_preordered_upper(permuted_upper_);
    if (ldlt_->info() != Eigen::Success) return false;
  }
  const size_t n = new_index_.size();
  for (size_t i = 0; i < n; ++i) rhs_[new_index_[i]] = b[i];
  solution_ = ldlt_->solve(rhs_);
  for (size_t i = 0; i < n; ++i) x[i] = solution_[new_index_[i]];
  return true;
}

}  // namespace tacta::models::sparse
