// Lexicographic Lemke pivoting on a dense or sparse basis (method, warm start and
// backward in lemke.hpp; the basis factorizations in lemke_basis.hpp).
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/core/errors.hpp>

#include "lemke_basis.hpp"

#include <lcprelax/sparse/klu_lu.hpp>

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
  LemkeMethod method = LemkeMethod::dense;  // the basis in use (settled at setup)
  std::vector<bool> warm;
  LcpResult result;
  std::vector<Index> basic;  // variable per row: [0,n) w, [n,2n) z, 2n z0
  std::unique_ptr<detail::LemkeBasis> basis;
  void (*refactor_hook)(bool) = nullptr;

  // Which basis the factorization holds: factored_basic, valid while factor_current
  // (cleared by a column replacement and by any change of M or d).
  std::vector<Index> factored_basic;
  bool factor_current = false;

  // Work arrays, sized at setup (the pivot loop allocates nothing).
  Vector xB, a, ratio_col, refine;  // x_B; B⁻¹(entering column); ratio denominators; residual
  Vector z_spare, w_spare;           // storage of result.z / result.w between solves
  Vector z_clip, w_clip;             // z clipped at 0 and its w (extract_solution)
  Vector d_cover;                    // the settings' covering vector during a crash start
  std::vector<Index> rows, keep;     // candidate rows of the ratio test
  std::vector<Index> slot;           // row → column of inv_rows
  DenseMatrix inv_rows;              // rows of B⁻¹ for tie-breaks (n × capacity; grows only
                                     // when more rows tie than ever before on this solver)

  void set_q(const Vector& q_in) {
    q_user = q_in;
    const double qn = q_in.size() ? q_in.lpNorm<Eigen::Infinity>() : 0.0;
    q_norm = qn > 0 ? qn : 1.0;
    q = q_in / q_norm;
    res_tol = settings.residual_tolerance > 0 ? settings.residual_tolerance : 1e-9 * qn;
  }

  Index z0() const { return 2 * n; }
  static Index complement(Index var, Index n) { return var < n ? var + n : var - n; }

  // The basis object and the work arrays for size n (called by setup()).
  void allocate() {
    const bool dense = settings.method == LemkeMethod::dense ||
                       (settings.method == LemkeMethod::automatic && n <= settings.dense_max_n);
    method = dense ? LemkeMethod::dense : LemkeMethod::sparse;
    const detail::LemkeColumns cols{&M, &d, n};
    basis = dense ? detail::make_dense_lemke_basis(cols, settings.refactor_interval)
                  : detail::make_sparse_lemke_basis(cols, settings.refactor_interval);
    factor_current = false;
    basic.assign(static_cast<std::size_t>(n), 0);
    factored_basic.assign(static_cast<std::size_t>(n), -1);
    xB.resize(n);
    a.resize(n);
    ratio_col.resize(n);
    refine.resize(n);
    d_cover.resize(n);
    z_spare.resize(n);
    w_spare.resize(n);
    z_clip.resize(n);
    w_clip.resize(n);
    result.z.resize(0);
    result.w.resize(0);
    rows.reserve(static_cast<std::size_t>(n));
    keep.reserve(static_cast<std::size_t>(n));
    slot.assign(static_cast<std::size_t>(n), 0);
    inv_rows.resize(n, dense ? n : std::min<Index>(n, detail::kMaxSchurUpdates));
    warm.reserve(static_cast<std::size_t>(n));
    result.z_basic.reserve(static_cast<std::size_t>(n));
  }

  // Result fields back to "unsolved", keeping the storage of z, w, z_basic and message
  // (z and w become empty: their storage is parked in z_spare / w_spare).
  void reset_result() {
    if (z_spare.size() == 0) result.z.swap(z_spare);
    if (w_spare.size() == 0) result.w.swap(w_spare);
    result.z.resize(0);
    result.w.resize(0);
    result.z_basic.clear();
    result.info.status = LcpStatus::unsolved;
    result.info.message.clear();
    result.info.pivots = 0;
    result.info.complementarity = std::numeric_limits<double>::quiet_NaN();
    result.info.seconds = 0.0;
    result.info.warm_started = false;
    result.info.crash_started = false;
    result.info.crash_pivots = 0;
    result.info.repair_rounds = 0;
    result.info.method = method;
    result.info.refactorizations = 0;
    result.info.regularization = 0.0;
  }

  // v of size n, taking the parked storage when v has none.
  void take(Vector& v, Vector& spare) const {
    if (v.size() != n && spare.size() == n) v.swap(spare);
    v.resize(n);
  }

  // Factorizes the current basis (unless the factorization already holds it) and sets
  // x_B = B⁻¹q with up to two steps of iterative refinement (r = q − B x_B; KLU's
  // threshold pivoting and ill-conditioned bases of resting-contact problems with
  // ‖q‖ ~ 1e-19 need them); false if B is singular.
  bool refactor(Vector& x) {
    if (!factor_current || basic != factored_basic) {
      ++result.info.refactorizations;
      factor_current = false;
      if (refactor_hook) refactor_hook(true);
      const bool ok = basis->refactor(basic);
      if (refactor_hook) refactor_hook(false);
      if (!ok) return false;
      factored_basic = basic;
      factor_current = true;
    }
    x = q;
    basis->solve(x);
    if (!x.allFinite()) return false;
    const detail::LemkeColumns cols{&M, &d, n};
    for (int step = 0; step < 2; ++step) {
      refine = q;
      for (Index k = 0; k < n; ++k) cols.add_to(basic[k], -x(k), refine);
      if (refine.lpNorm<Eigen::Infinity>() == 0.0) break;
      basis->solve(refine);
      x += refine;
    }
    return x.allFinite();
  }

  // Lexicographic minimum ratio over the candidate rows `rows` (key: rows of [x_B, B⁻¹] /
  // den_i). Ratios of a key column v tie with the minimum θ when v_i/den_i ≤ θ + t, with
  // - for x_B: t = tol·(|θ| + 1/den_max), den_max = max den_i over the rows: relative to
  //   θ, plus the roundoff of x_B seen through the largest pivot. q is normalized to
  //   ‖q‖∞ = 1, so this is scale-free (resting contact has ‖q‖ ~ 1e-19). An absolute
  //   ratio tolerance would make the ratios of size 1e-6 of stiff contact problems
  //   (‖M‖ ~ 1e3) ties and break feasibility (granular fc2d problem);
  // - for the B⁻¹ columns: t = tol·(1 + |θ|), absolute: on lcp_tobenna (bases with
  //   pivots up to 4e6) anything tighter misses roundoff ties and cycles into a singular
  //   basis.
  // Rows of B⁻¹ are formed only for rows still tied after x_B (one transposed solve each
  // on the sparse path). Returns −1 when a ratio is not finite (NaN or ∞ in x_B or B⁻¹:
  // the basis has lost all accuracy).
  Index lexicographic_row(const Vector& den, const Vector& x, bool prefer_z0) {
    double den_max = 0.0;
    for (Index i : rows) den_max = std::max(den_max, den(i));
    bool finite = true;
    auto keep_minimal = [&](auto value, double absolute) {
      double best = std::numeric_limits<double>::infinity();
      for (Index i : rows) {
        const double ratio = value(i) / den(i);
        if (!std::isfinite(ratio)) {
          finite = false;
          return;
        }
        best = std::min(best, ratio);
      }
      const double t = tol * (std::abs(best) + absolute);
      keep.clear();
      for (Index i : rows)
        if (value(i) / den(i) <= best + t) keep.push_back(i);
      rows.swap(keep);
    };
    keep_minimal([&](Index i) { return x(i); }, 1.0 / den_max);
    if (!finite) return -1;
    if (prefer_z0)
      for (Index i : rows)
        if (basic[i] == z0()) return i;
    if (rows.size() == 1) return rows.front();
    const Index m = static_cast<Index>(rows.size());
    if (inv_rows.cols() < m) inv_rows.resize(n, std::max<Index>(m, std::min<Index>(n, 2 * inv_rows.cols())));
    auto inv = inv_rows.leftCols(m);  // column k: row rows[k] of B⁻¹
    basis->inverse_rows(rows, inv);
    for (Index k = 0; k < m; ++k) slot[rows[k]] = k;
    for (Index col = 0; col < n && rows.size() > 1 && finite; ++col)
      keep_minimal([&](Index i) { return inv(col, slot[i]); }, 1.0);
    return finite ? rows.front() : -1;
  }

  void finish(LcpStatus status, const char* message) {
    result.info.status = status;
    result.info.message = message;
  }

  // Fills z, w, z_basic from a fresh factorization of the current basis (kept for
  // backward()); checks the residual.
  void extract_solution() {
    // (res_tol = 0 when q = 0: then z = 0 is exact and the residual is 0.)
    take(result.z, z_spare);
    result.z.setZero();
    if (!refactor(xB)) return finish(LcpStatus::numerical_error, "final basis is singular");
    result.z_basic.assign(static_cast<std::size_t>(n), false);
    for (Index k = 0; k < n; ++k)
      if (basic[k] >= n && basic[k] < 2 * n) {
        result.z(basic[k] - n) = xB(k) * q_norm;
        result.z_basic[basic[k] - n] = true;
      }
    take(result.w, w_spare);
    // z = x_B as computed, and z clipped at 0: a basis that is feasible only to roundoff
    // (x_B,i ~ −1e-11 of a basic z_i; the lexicographic ratio test admits ties within its
    // tolerance) gives w = Mz + q exact in the first, while clipping moves w by ‖M‖·|x_B,i|
    // in other rows (granular fc2d, 2,020 contacts: 2.2e-9 against 4.8e-11). The one with
    // the smaller complementarity residual is returned (the clipped one on a tie).
    refine.noalias() = M * result.z;
    result.w = refine + q_user;
    const double unclipped = n ? result.z.cwiseMin(result.w).cwiseAbs().maxCoeff() : 0.0;
    if (n && result.z.minCoeff() < 0.0) {
      z_clip = result.z.cwiseMax(0.0);
      w_clip.noalias() = M * z_clip;
      w_clip += q_user;
      const double clipped = z_clip.cwiseMin(w_clip).cwiseAbs().maxCoeff();
      if (clipped <= unclipped) {
        result.z = z_clip;
        result.w = w_clip;
      }
      result.info.complementarity = std::min(clipped, unclipped);
    } else {
      result.info.complementarity = unclipped;
    }
    // Overflow (data near 1e308: z = x_B·‖q‖∞ or w = Mz + q beyond the double range) leaves
    // min(z, w) finite or 0 where w = ∞: never `solved` with a non-finite z or w.
    if (!result.z.allFinite() || !result.w.allFinite())
      finish(LcpStatus::numerical_error, "z or w has a non-finite entry (overflow: data too large for doubles)");
    else if (result.info.complementarity <= res_tol) finish(LcpStatus::solved, "solved");
    else finish(LcpStatus::numerical_error, "complementarity residual above tolerance after refactorization");
  }

  // Whether the factorization holds the basis `warm` (in its own column order).
  bool warm_basis_is_factored() const {
    if (!factor_current) return false;
    for (Index k = 0; k < n; ++k) {
      const Index v = factored_basic[k];
      if (v >= 2 * n || (v >= n) != static_cast<bool>(warm[v < n ? v : v - n])) return false;
    }
    return true;
  }

  // Sets the basis to `warm`; true when it factorizes (x_B = B⁻¹q then holds its values).
  bool load_warm_basis() {
    if (warm_basis_is_factored()) basic = factored_basic;
    else
      for (Index i = 0; i < n; ++i) basic[i] = warm[i] ? n + i : i;
    return refactor(xB);
  }

  bool try_warm_start(bool factorized) {
    if (!factorized || xB.minCoeff() < -tol) return false;
    extract_solution();
    result.info.warm_started = has_solution(result.info.status);
    return result.info.warm_started;
  }

  // Basis repair of a singular crash basis (as simplex codes repair a singular crash basis
  // by exchanging dependent columns for slacks, e.g. Bixby, "Implementing the simplex method:
  // the initial basis", ORSA J. Comput. 4, 1992): the z columns that a KLU factorization of
  // B = [e_i (w_i basic) | −M_:j (z_j basic)] leaves with a zero pivot (relative 1e-10)
  // become their complements w_j, for at most kRepairRounds factorizations. A granular
  // pile's approximate solution loads more contacts than the bodies have degrees of
  // freedom, and the basis it suggests is singular. Allocates (a crash start only).
  static constexpr int kRepairRounds = 8;
  bool repair_warm_basis() {
    for (int round = 0; round < kRepairRounds; ++round) {
      std::vector<Triplet> t;
      t.reserve(static_cast<std::size_t>(M.nonZeros() + n));
      for (Index j = 0; j < n; ++j) {
        if (!warm[static_cast<std::size_t>(j)]) {
          t.emplace_back(j, j, 1.0);
          continue;
        }
        for (SparseMatrix::InnerIterator it(M, j); it; ++it) t.emplace_back(it.row(), j, -it.value());
      }
      SparseMatrix B(n, n);
      B.setFromTriplets(t.begin(), t.end());
      B.makeCompressed();
      sparse::KluLu klu;
      if (!klu.analyze(B).ok()) return false;
      const std::vector<Index> dependent = klu.zero_pivot_columns(B, 1e-10);
      if (dependent.empty()) return round > 0;
      bool changed = false;
      for (Index j : dependent)
        if (warm[static_cast<std::size_t>(j)]) {
          warm[static_cast<std::size_t>(j)] = false;
          changed = true;
        }
      if (!changed) return false;
      ++result.info.repair_rounds;
    }
    return false;
  }

  // Lemke from the factorized warm basis B whose basic solution x_B = B⁻¹q has negative
  // entries (a crash start, LemkeSettings::crash_start): with the covering vector d = B·1
  // the artificial z₀'s column −d reads −1 in B's coordinates, so z₀ enters at the most
  // negative x_B,i exactly as it enters at the most negative q_i from the all-w basis, and
  // the pivots that follow are Lemke's method on the principal pivotal transform of the
  // LCP with respect to B (Cottle, Pang & Stone 1992, §4.4 and §2.3). A basis close to the
  // solution's leaves few negative entries and the path is short. d is restored afterwards;
  // true only when the path ends solved.
  bool try_crash_start() {
    d_cover = d;
    d.setZero();
    const detail::LemkeColumns cols{&M, &d, n};
    for (Index k = 0; k < n; ++k) cols.add_to(basic[k], 1.0, d);
    pivot_from_current_basis();
    d = d_cover;
    const bool solved = has_solution(result.info.status);
    result.info.crash_started = true;
    result.info.crash_pivots = result.info.pivots;
    return solved;
  }

  void run() {
    if (n == 0) {
      result.z.resize(0);
      result.w.resize(0);
      result.z_basic.clear();
      result.info.complementarity = 0.0;
      return finish(LcpStatus::solved, "empty problem");
    }
    long crash_pivots = 0;
    if (!warm.empty()) {
      bool factorized = load_warm_basis();
      if (!factorized && settings.crash_start && repair_warm_basis()) factorized = load_warm_basis();
      if (try_warm_start(factorized)) return;
      if (factorized && settings.crash_start) {
        if (try_crash_start()) return;
        crash_pivots = result.info.pivots;  // a failed crash path: cold start, pivots add up
        factor_current = false;
      }
    }
    for (Index i = 0; i < n; ++i) basic[i] = i;
    if (q.minCoeff() >= 0) return extract_solution();  // z = 0 solves it
    if (!refactor(xB)) return finish(LcpStatus::numerical_error, "identity basis failed to factorize");
    pivot_from_current_basis();
    result.info.pivots += crash_pivots;
  }

  // Lemke's pivots from the factorized current basis (without z₀) and x_B = B⁻¹q: z₀
  // enters at the most negative x_B,i/(B⁻¹d)_i (lexicographically on [x_B, B⁻¹]/(B⁻¹d)).
  void pivot_from_current_basis() {
    result.info.pivots = 0;
    Index entering = z0();
    basis->solve_column(entering, a);  // = −d
    ratio_col = -a;
    rows.clear();
    for (Index i = 0; i < n; ++i) rows.push_back(i);
    Index r = lexicographic_row(ratio_col, xB, false);
    for (long pivot = 0;; ++pivot) {
      if (r < 0) return finish(LcpStatus::numerical_error, "non-finite ratio in the minimum-ratio test (basis lost accuracy)");
      // Pivot on (r, entering): update the factorization and x_B.
      const bool updated = basis->replace(r, a);
      factor_current = false;
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
      r = lexicographic_row(a, xB, true);
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
  m.result = LcpResult{};
  m.allocate();
  m.reset_result();
  m.result.info.message = "solve() was not called";
  m.is_setup = true;
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
  m.reset_result();
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
      m.factor_current = false;
      m.reset_result();
      m.run();
      pivots += m.result.info.pivots;
      refactorizations += m.result.info.refactorizations;
      const LcpStatus s = m.result.info.status;
      if ((s == LcpStatus::solved || s == LcpStatus::numerical_error) && m.result.z.size() == m.n) {
        m.result.w = M0 * m.result.z + m.q_user;
        m.result.info.complementarity = m.result.z.cwiseMin(m.result.w).cwiseAbs().maxCoeff();
        if (m.result.info.complementarity <= m.res_tol && m.result.z.allFinite() && m.result.w.allFinite()) {
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
    m.factor_current = false;
    m.result.info.pivots = pivots;
    m.result.info.refactorizations = refactorizations;
  }
  m.result.info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return m.result;
}

const LcpResult& LemkeSolver::result() const { return impl_->result; }

void LemkeSolver::set_refactorization_hook(void (*hook)(bool starting)) { impl_->refactor_hook = hook; }

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
