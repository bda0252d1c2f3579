// Lexicographic Lemke pivoting on a dense or sparse basis (method, warm start and
// backward in lemke.hpp; the basis factorizations in lemke_basis.hpp).
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/core/errors.hpp>

#include "lemke_basis.hpp"

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
  Vector q_user;     // q as given
  Vector q, d;       // q = q_user / q_norm: the pivoting runs on ‖q‖∞ = 1 (z scales with q)
  double q_norm = 1.0;
  double tol = 0, res_tol = 0;
  double mnorm = 0;  // ‖M‖∞
  long max_pivots = 0;
  bool is_setup = false;
  std::vector<bool> warm;
  LcpResult result;
  std::vector<Index> basic;  // variable per row: [0,n) w, [n,2n) z, 2n z0
  std::unique_ptr<detail::LemkeBasis> basis;

  void set_q(const Vector& q_in) {
    q_user = q_in;
    const double qn = q_in.size() ? q_in.lpNorm<Eigen::Infinity>() : 0.0;
    q_norm = qn > 0 ? qn : 1.0;
    q = q_in / q_norm;
    res_tol = settings.residual_tolerance > 0 ? settings.residual_tolerance : 1e-9 * qn;
  }

  Index z0() const { return 2 * n; }
  static Index complement(Index var, Index n) { return var < n ? var + n : var - n; }

  void make_basis() {
    const bool dense = settings.method == LemkeMethod::dense ||
                       (settings.method == LemkeMethod::automatic && n <= settings.dense_max_n);
    result.info.method = dense ? LemkeMethod::dense : LemkeMethod::sparse;
    const detail::LemkeColumns cols{&M, &d, n};
    basis = dense ? detail::make_dense_lemke_basis(cols, settings.refactor_interval)
                  : detail::make_sparse_lemke_basis(cols, settings.refactor_interval);
  }

  // Factorizes the current basis and sets x_B = B⁻¹q with up to two steps of iterative
  // refinement (r = q − B x_B; KLU's threshold pivoting and ill-conditioned bases of
  // resting-contact problems with ‖q‖ ~ 1e-19 need them); false if B is singular.
  bool refactor(Vector& xB) {
    ++result.info.refactorizations;
    if (!basis->refactor(basic)) return false;
    xB = q;
    basis->solve(xB);
    if (!xB.allFinite()) return false;
    const detail::LemkeColumns cols{&M, &d, n};
    for (int step = 0; step < 2; ++step) {
      Vector r = q;
      for (Index k = 0; k < n; ++k) cols.add_to(basic[k], -xB(k), r);
      if (r.lpNorm<Eigen::Infinity>() == 0.0) break;
      basis->solve(r);
      xB += r;
    }
    return xB.allFinite();
  }

  // Lexicographic minimum ratio over candidate rows (key: rows of [x_B, B⁻¹] / a_i).
  // Ratios of a key column v tie with the minimum θ when v_i/a_i ≤ θ + t, with
  // - for x_B: t = tol·(|θ| + 1/a_max), a_max = max a_i over the rows: relative to θ, plus
  //   the roundoff of x_B seen through the largest pivot. q is normalized to ‖q‖∞ = 1,
  //   so this is scale-free (resting contact has ‖q‖ ~ 1e-19). An absolute ratio
  //   tolerance makes the ratios of size 1e-6 of stiff contact problems (‖M‖ ~ 1e3) ties
  //   and breaks feasibility (granular fc2d problem);
  // - for the B⁻¹ columns: t = tol·(1 + |θ|), absolute: on lcp_tobenna (bases with
  //   pivots up to 4e6) anything tighter misses roundoff ties and cycles into a singular
  //   basis.
  // Rows of B⁻¹ are formed only for rows still tied after x_B (one transposed solve each
  // on the sparse path). Returns −1 when a ratio is not finite (NaN or ∞ in x_B or B⁻¹:
  // the basis has lost all accuracy; measured on a 20-body pile step).
  Index lexicographic_row(std::vector<Index> rows, const Vector& a, const Vector& xB, bool prefer_z0) const {
    double a_max = 0.0;
    for (Index i : rows) a_max = std::max(a_max, a(i));
    bool finite = true;
    auto keep_minimal = [&](auto value, double absolute) {
      double best = std::numeric_limits<double>::infinity();
      for (Index i : rows) {
        const double ratio = value(i) / a(i);
        if (!std::isfinite(ratio)) {
          finite = false;
          return;
        }
        best = std::min(best, ratio);
      }
      const double t = tol * (std::abs(best) + absolute);
      std::vector<Index> keep;
      for (Index i : rows)
        if (value(i) / a(i) <= best + t) keep.push_back(i);
      rows.swap(keep);
    };
    keep_minimal([&](Index i) { return xB(i); }, 1.0 / a_max);
    if (!finite) return -1;
    if (prefer_z0)
      for (Index i : rows)
        if (basic[i] == z0()) return i;
    if (rows.size() == 1) return rows.front();
    DenseMatrix inv_rows;  // column k: row rows[k] of B⁻¹
    basis->inverse_rows(rows, inv_rows);
    std::vector<Index> slot(static_cast<std::size_t>(n), -1);
    for (std::size_t k = 0; k < rows.size(); ++k) slot[rows[k]] = static_cast<Index>(k);
    for (Index col = 0; col < n && rows.size() > 1 && finite; ++col)
      keep_minimal([&](Index i) { return inv_rows(col, slot[i]); }, 1.0);
    return finite ? rows.front() : -1;
  }

  void finish(LcpStatus status, const std::string& message) {
    result.info.status = status;
    result.info.message = message;
  }

  // Fills z, w, z_basic from a fresh factorization of the current basis (kept for
  // backward()); checks the residual.
  void extract_solution() {
    // (res_tol = 0 when q = 0: then z = 0 is exact and the residual is 0.)
    result.z = Vector::Zero(n);
    Vector xB;
    if (!refactor(xB)) return finish(LcpStatus::numerical_error, "final basis is singular");
    result.z_basic.assign(n, false);
    for (Index k = 0; k < n; ++k)
      if (basic[k] >= n && basic[k] < 2 * n) {
        result.z(basic[k] - n) = std::max(xB(k), 0.0) * q_norm;
        result.z_basic[basic[k] - n] = true;
      }
    result.w = M * result.z + q_user;
    result.info.complementarity = n ? result.z.cwiseMin(result.w).cwiseAbs().maxCoeff() : 0.0;
    if (result.info.complementarity <= res_tol) finish(LcpStatus::solved, "solved");
    else finish(LcpStatus::numerical_error, "complementarity residual above tolerance after refactorization");
  }

  bool try_warm_start() {
    for (Index i = 0; i < n; ++i) basic[i] = warm[i] ? n + i : i;
    Vector xB;
    if (!refactor(xB) || xB.minCoeff() < -tol) return false;
    extract_solution();
    result.info.warm_started = has_solution(result.info.status);
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
    make_basis();
    if (!warm.empty() && try_warm_start()) return;
    for (Index i = 0; i < n; ++i) basic[i] = i;
    if (q.minCoeff() >= 0) return extract_solution();  // z = 0 solves it

    Vector xB;
    if (!refactor(xB)) return finish(LcpStatus::numerical_error, "identity basis failed to factorize");
    Vector a(n);
    // z₀ enters at the most negative q_i/d_i (lexicographically on [q, I]/d).
    Index entering = z0();
    basis->solve_column(entering, a);  // = −d
    std::vector<Index> rows(n);
    for (Index i = 0; i < n; ++i) rows[i] = i;
    Index r = lexicographic_row(rows, -a, xB, false);
    for (long pivot = 0;; ++pivot) {
      if (r < 0) return finish(LcpStatus::numerical_error, "non-finite ratio in the minimum-ratio test (basis lost accuracy)");
      // Pivot on (r, entering): update the factorization and x_B.
      const bool updated = basis->replace(r, a);
      const double ar = a(r);
      xB(r) /= ar;
      for (Index i = 0; i < n; ++i)
        if (i != r && a(i) != 0.0) xB(i) -= a(i) * xB(r);
      const Index leaving = basic[r];
      basic[r] = entering;
      result.info.pivots = pivot + 1;
      if (leaving == z0()) return extract_solution();
      if (result.info.pivots >= max_pivots) return finish(LcpStatus::pivot_limit, "pivot limit reached");
      if (!updated && !refactor(xB)) return finish(LcpStatus::numerical_error, "basis became singular");
      entering = complement(leaving, n);
      basis->solve_column(entering, a);
      rows.clear();
      for (Index i = 0; i < n; ++i)
        if (a(i) > tol) rows.push_back(i);
      if (rows.empty()) return finish(LcpStatus::ray_termination, "ray termination: no solution found by Lemke");
      r = lexicographic_row(rows, a, xB, true);
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
  m.set_q(q);
  m.d = m.settings.covering.size() ? m.settings.covering : Vector::Ones(n);
  Vector row_sums = Vector::Zero(n);
  for (Index j = 0; j < m.M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(m.M, j); it; ++it) row_sums(it.row()) += std::abs(it.value());
  const double mnorm = n ? row_sums.maxCoeff() : 0.0;
  m.mnorm = mnorm;
  m.tol = m.settings.pivot_tolerance > 0 ? m.settings.pivot_tolerance
                                         : 10.0 * std::max<Index>(n, 1) * std::numeric_limits<double>::epsilon() *
                                               std::max(1.0, mnorm);
  m.max_pivots = m.settings.max_pivots > 0 ? m.settings.max_pivots
                                           : 50L * (n + 1) + (n < 20 ? (1L << n) : 0L);
  m.max_pivots = std::min(m.max_pivots, 10'000'000L);
  m.is_setup = true;
  m.result = LcpResult{};
}

void LemkeSolver::update_q(const Vector& q) {
  if (!impl_->is_setup) throw std::logic_error("LemkeSolver::update_q before setup");
  if (q.size() != impl_->n || !q.allFinite()) throw InputError("LCP: update_q needs a finite q of size n");
  impl_->set_q(q);
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
  // Retries after a failure (ray termination, singular basis, pivot limit) of degenerate
  // problems, where roundoff sends the pivot path to a secondary ray (lcp_types.hpp):
  // first other covering vectors (another pivot path to the same LCP), then M + εI (as
  // Drake's MobyLCP does), whose z is accepted only if it solves the ORIGINAL LCP to the
  // residual tolerance.
  const LcpStatus first = m.result.info.status;
  const int retries = m.settings.covering_retries + m.settings.regularization_retries;
  if (first != LcpStatus::solved && first != LcpStatus::pivot_limit && retries > 0 && m.n > 0) {
    const SparseMatrix M0 = m.M;
    const Vector d0 = m.d;
    long pivots = m.result.info.pivots, refactorizations = m.result.info.refactorizations;
    const std::string first_message = m.result.info.message;
    SparseMatrix I(m.n, m.n);
    I.setIdentity();
    double eps = m.settings.regularization * std::max(1.0, m.mnorm);
    for (int k = 0; k < retries; ++k) {
      const bool covering = k < m.settings.covering_retries;
      m.d = d0;
      if (covering)
        for (Index i = 0; i < m.n; ++i) m.d(i) *= k % 2 == 0 ? 1.0 + (i % 7) / 7.0 : 1.0 + 1e-3 * i;
      m.M = M0;
      if (!covering) {
        m.M = M0 + eps * I;
        m.M.makeCompressed();
      }
      m.result = LcpResult{};
      m.run();
      pivots += m.result.info.pivots;
      refactorizations += m.result.info.refactorizations;
      const LcpStatus s = m.result.info.status;
      if ((s == LcpStatus::solved || s == LcpStatus::numerical_error) && m.result.z.size() == m.n) {
        m.result.w = M0 * m.result.z + m.q_user;
        m.result.info.complementarity = m.result.z.cwiseMin(m.result.w).cwiseAbs().maxCoeff();
        if (m.result.info.complementarity <= m.res_tol) {
          m.result.info.status = LcpStatus::solved;
          m.result.info.regularization = covering ? 0.0 : eps;
          m.result.info.message = std::string("solved on retry ") + std::to_string(k + 1) +
                                  (covering ? " (other covering vector)" : " (M + εI)") + " after " + to_string(first) +
                                  ": " + first_message;
          break;
        }
      }
      m.result.info.status = first;
      m.result.info.message = std::to_string(k + 1) + " retries failed; first failure: " + first_message;
      if (!covering) eps *= 100.0;
    }
    m.M = M0;  // the basis factorization (for backward) is that of the accepted retry
    m.d = d0;
    m.result.info.pivots = pivots;
    m.result.info.refactorizations = refactorizations;
  }
  m.result.info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return m.result;
}

const LcpResult& LemkeSolver::result() const { return impl_->result; }

LcpGradient LemkeSolver::backward(const Vector& dl_dz) const {
  const Impl& m = *impl_;
  if (!has_solution(m.result.info.status))
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
    m.basis->solve_transposed(gb);  // λ = B⁻ᵀ g, with the final factorization
    g.dq = gb;
  }
  for (Index j = 0; j < g.dM.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(g.dM, j); it; ++it) it.valueRef() = g.dq(it.row()) * m.result.z(j);
  return g;
}

}  // namespace lcprelax
