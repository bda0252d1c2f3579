// Dense lexicographic Lemke (method, warm start and backward in lemke.hpp).
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/sparse/errors.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lcprelax {

struct LemkeSolver::Impl {
  LemkeSettings settings;
  Index n = 0;
  SparseMatrix M;
  DenseMatrix Md;
  Vector q, d;
  double tol = 0, res_tol = 0;
  double q_scale = 1.0;  // min(1, ‖q‖∞): scale of the x_B ratio ties
  long max_pivots = 0;
  bool is_setup = false;
  std::vector<bool> warm;
  LcpResult result;
  std::vector<Index> basic;               // variable per row: [0,n) w, [n,2n) z, 2n z0
  Eigen::PartialPivLU<DenseMatrix> final_lu;  // of the final complementary basis

  Index z0() const { return 2 * n; }
  static Index complement(Index var, Index n) { return var < n ? var + n : var - n; }

  void column(Index var, Eigen::Ref<Vector> out) const {
    if (var < n) {
      out.setZero();
      out(var) = 1.0;
    } else if (var < 2 * n) {
      out = -Md.col(var - n);
    } else {
      out = -d;
    }
  }

  DenseMatrix basis_matrix() const {
    DenseMatrix B(n, n);
    for (Index k = 0; k < n; ++k) column(basic[k], B.col(k));
    return B;
  }

  // Recomputes B⁻¹ and x_B = B⁻¹q from scratch (partial-pivoting LU); false if B is
  // numerically singular (non-finite inverse). Ill-conditioned bases are accepted: the
  // final residual check decides.
  bool refactor(DenseMatrix& Binv, Vector& xB) const {
    const Eigen::PartialPivLU<DenseMatrix> lu(basis_matrix());
    Binv = lu.inverse();
    if (!Binv.allFinite()) return false;
    xB = Binv * q;
    return true;
  }

  // Lexicographic minimum ratio over candidate rows (key: rows of [x_B, B⁻¹] / a_i).
  // Ties: tol·(1 + |best|) on the B⁻¹ columns; on the x_B ratios tol·(q_scale + |best|)
  // with q_scale = min(1, ‖q‖∞), so that problems with tiny q (resting contact, where
  // ‖q‖ ~ 1e-18) are not all ties.
  Index lexicographic_row(std::vector<Index> rows, const Vector& a, const Vector& xB, const DenseMatrix& Binv,
                          bool prefer_z0) const {
    for (Index col = -1; col < n && rows.size() > 1; ++col) {
      auto key = [&](Index i) { return (col < 0 ? xB(i) : Binv(i, col)) / a(i); };
      double best = std::numeric_limits<double>::infinity();
      for (Index i : rows) best = std::min(best, key(i));
      const double t = tol * ((col < 0 ? q_scale : 1.0) + std::abs(best));
      std::vector<Index> keep;
      for (Index i : rows)
        if (key(i) <= best + t) keep.push_back(i);
      rows.swap(keep);
      if (col < 0 && prefer_z0)
        for (Index i : rows)
          if (basic[i] == z0()) return i;
    }
    return rows.front();
  }

  void finish(LcpStatus status, const std::string& message) {
    result.info.status = status;
    result.info.message = message;
  }

  // Fills z, w, z_basic from the current basis; checks the residual.
  void extract_solution() {
    // (res_tol = 0 when q = 0: then z = 0 is exact and the residual is 0.)
    result.z = Vector::Zero(n);
    DenseMatrix Binv;
    Vector xB;
    if (!refactor(Binv, xB)) return finish(LcpStatus::numerical_error, "final basis is singular");
    result.z_basic.assign(n, false);
    for (Index k = 0; k < n; ++k)
      if (basic[k] >= n && basic[k] < 2 * n) {
        result.z(basic[k] - n) = std::max(xB(k), 0.0);
        result.z_basic[basic[k] - n] = true;
      }
    result.w = M * result.z + q;
    result.info.complementarity = n ? result.z.cwiseMin(result.w).cwiseAbs().maxCoeff() : 0.0;
    final_lu.compute(basis_matrix());
    if (result.info.complementarity <= res_tol) finish(LcpStatus::solved, "solved");
    else finish(LcpStatus::numerical_error, "complementarity residual above tolerance after refactorization");
  }

  bool try_warm_start() {
    for (Index i = 0; i < n; ++i) basic[i] = warm[i] ? n + i : i;
    DenseMatrix Binv;
    Vector xB;
    if (!refactor(Binv, xB) || xB.minCoeff() < -tol) return false;
    extract_solution();
    result.info.warm_started = result.info.status == LcpStatus::solved;
    return result.info.warm_started;
  }

  void run() {
    basic.resize(n);
    if (n == 0) {
      result.z = result.w = Vector(0);
      result.z_basic.clear();
      result.info.complementarity = 0.0;
      return finish(LcpStatus::solved, "empty problem");
    }
    if (!warm.empty() && try_warm_start()) return;
    for (Index i = 0; i < n; ++i) basic[i] = i;
    if (q.minCoeff() >= 0) return extract_solution();  // z = 0 solves it

    DenseMatrix Binv = DenseMatrix::Identity(n, n);
    Vector xB = q, a(n);
    // z₀ enters at the most negative q_i/d_i (lexicographically on [q, I]/d).
    Index entering = z0();
    column(entering, a);
    std::vector<Index> rows(n);
    for (Index i = 0; i < n; ++i) rows[i] = i;
    const Vector neg_a = -a;
    Index r = lexicographic_row(rows, neg_a, xB, Binv, false);
    for (long pivot = 0;; ++pivot) {
      // Pivot on (r, entering): product-form update of B⁻¹ and x_B.
      const double ar = a(r);
      Binv.row(r) /= ar;
      xB(r) /= ar;
      for (Index i = 0; i < n; ++i)
        if (i != r && a(i) != 0.0) {
          Binv.row(i) -= a(i) * Binv.row(r);
          xB(i) -= a(i) * xB(r);
        }
      const Index leaving = basic[r];
      basic[r] = entering;
      result.info.pivots = pivot + 1;
      if (leaving == z0()) return extract_solution();
      if (result.info.pivots >= max_pivots) return finish(LcpStatus::pivot_limit, "pivot limit reached");
      if (result.info.pivots % settings.refactor_interval == 0 && !refactor(Binv, xB))
        return finish(LcpStatus::numerical_error, "basis became singular");
      entering = complement(leaving, n);
      column(entering, a);
      a = Binv * a;
      rows.clear();
      for (Index i = 0; i < n; ++i)
        if (a(i) > tol) rows.push_back(i);
      if (rows.empty()) return finish(LcpStatus::ray_termination, "ray termination: no solution found by Lemke");
      r = lexicographic_row(rows, a, xB, Binv, true);
    }
  }
};

LemkeSolver::LemkeSolver(LemkeSettings settings) : impl_(std::make_unique<Impl>()) {
  const std::string e = settings.validation_error();
  if (!e.empty()) throw InputError("invalid LemkeSettings: " + e);
  impl_->settings = std::move(settings);
}
LemkeSolver::~LemkeSolver() = default;
LemkeSolver::LemkeSolver(LemkeSolver&&) noexcept = default;
LemkeSolver& LemkeSolver::operator=(LemkeSolver&&) noexcept = default;

void LemkeSolver::setup(const SparseMatrix& M, const Vector& q) {
  Impl& m = *impl_;
  if (M.rows() != M.cols()) throw InputError("LCP: M is not square");
  if (q.size() != M.rows()) throw InputError("LCP: q has size " + std::to_string(q.size()) + ", M has " +
                                             std::to_string(M.rows()) + " rows");
  for (Index k = 0; k < M.nonZeros(); ++k)
    if (!std::isfinite(M.valuePtr()[k])) throw InputError("LCP: M has a NaN or infinite entry");
  if (!q.allFinite()) throw InputError("LCP: q has a NaN or infinite entry");
  const Index n = static_cast<Index>(q.size());
  if (m.settings.covering.size() != 0 && m.settings.covering.size() != n)
    throw InputError("LCP: covering vector has the wrong size");
  m.n = n;
  m.M = M;
  m.M.makeCompressed();
  m.Md = DenseMatrix(M);
  m.q = q;
  m.d = m.settings.covering.size() ? m.settings.covering : Vector::Ones(n);
  const double mnorm = n ? m.Md.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  m.tol = m.settings.pivot_tolerance > 0 ? m.settings.pivot_tolerance
                                         : 10.0 * std::max<Index>(n, 1) * std::numeric_limits<double>::epsilon() *
                                               std::max(1.0, mnorm);
  const double qnorm = n ? q.lpNorm<Eigen::Infinity>() : 0.0;
  m.q_scale = std::min(1.0, qnorm);
  m.res_tol = m.settings.residual_tolerance > 0 ? m.settings.residual_tolerance : 1e-9 * qnorm;
  m.max_pivots = m.settings.max_pivots > 0 ? m.settings.max_pivots
                                           : 50L * (n + 1) + (n < 23 ? (1L << n) : 10'000'000L);
  m.max_pivots = std::min(m.max_pivots, 10'000'000L);
  m.is_setup = true;
  m.result = LcpResult{};
}

void LemkeSolver::update_q(const Vector& q) {
  if (!impl_->is_setup) throw std::logic_error("LemkeSolver::update_q before setup");
  if (q.size() != impl_->n || !q.allFinite()) throw InputError("LCP: update_q needs a finite q of size n");
  impl_->q = q;
}

void LemkeSolver::warm_start(const std::vector<bool>& z_basic) {
  if (static_cast<Index>(z_basic.size()) != impl_->n) throw InputError("LCP: warm-start basis has the wrong size");
  impl_->warm = z_basic;
}

const LcpResult& LemkeSolver::solve() {
  Impl& m = *impl_;
  if (!m.is_setup) throw std::logic_error("LemkeSolver::solve before setup");
  const auto t0 = std::chrono::steady_clock::now();
  m.result = LcpResult{};
  m.run();
  m.warm.clear();
  m.result.info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return m.result;
}

const LcpResult& LemkeSolver::result() const { return impl_->result; }

LcpGradient LemkeSolver::backward(const Vector& dl_dz) const {
  const Impl& m = *impl_;
  if (m.result.info.status != LcpStatus::solved)
    throw std::logic_error(std::string("LemkeSolver::backward needs status solved, status is ") +
                           to_string(m.result.info.status));
  if (dl_dz.size() != m.n || !dl_dz.allFinite()) throw InputError("LCP backward: dl_dz must be finite, size n");
  LcpGradient g;
  g.dq = Vector::Zero(m.n);
  g.dM = m.M;
  if (m.n > 0) {
    Vector gb = Vector::Zero(m.n);
    for (Index k = 0; k < m.n; ++k)
      if (m.basic[k] >= m.n && m.basic[k] < 2 * m.n) gb(k) = dl_dz(m.basic[k] - m.n);
    g.dq = m.final_lu.transpose().solve(gb);  // λ = B⁻ᵀ g
  }
  for (Index j = 0; j < g.dM.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(g.dM, j); it; ++it) it.valueRef() = g.dq(it.row()) * m.result.z(j);
  return g;
}

}  // namespace lcprelax
