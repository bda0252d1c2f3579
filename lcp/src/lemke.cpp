// LemkeSolver: setup, the retries of solve() and the factorization of the current basis
// (method, warm start and backward in lemke.hpp; the other steps in the files named in
// lemke_impl.hpp; the basis factorizations in lemke_basis.hpp).
#include "lemke_impl.hpp"

#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lcprelax {

void LemkeSolver::Impl::set_q(const Vector& q_in) {
  q_user = q_in;
  const double qn = q_in.size() ? q_in.lpNorm<Eigen::Infinity>() : 0.0;
  q_norm = qn > 0 ? qn : 1.0;
  q = q_in / q_norm;
  res_tol = settings.residual_tolerance > 0 ? settings.residual_tolerance : 1e-9 * qn;
}

// The basis object and the work arrays for size n (called by setup()).
void LemkeSolver::Impl::allocate() {
  const bool dense = settings.method == LemkeMethod::dense ||
                     (settings.method == LemkeMethod::automatic && n <= settings.dense_max_n);
  method = dense ? LemkeMethod::dense : LemkeMethod::sparse;
  new_basis();
  basic.assign(static_cast<std::size_t>(n), 0);
  factored_basic.assign(static_cast<std::size_t>(n), -1);
  xB.resize(n);
  a.resize(n);
  ratio_col.resize(n);
  refine.resize(n);
  refine_z.resize(n);
  refine_dof.resize(has_lifted && settings.lifted_basis ? lifted_J.cols() : 0);
  d_cover.resize(n);
  z_spare.resize(n);
  w_spare.resize(n);
  z_clip.resize(n);
  w_clip.resize(n);
  result.z.resize(0);
  result.w.resize(0);
  rows.reserve(static_cast<std::size_t>(n));
  keep.reserve(static_cast<std::size_t>(n));
  ties.sparse_rows = settings.sparse_tie_rows;
  ties.reserve(n, dense ? n : std::min<Index>(n, detail::kMaxSchurUpdates));
  warm.reserve(static_cast<std::size_t>(n));
  result.z_basic.reserve(static_cast<std::size_t>(n));
}

// A fresh basis object for `method`: no factorization, and none of the adaptive state of
// earlier solves (the sparse basis' running column density, lemke_basis_sparse.cpp).
void LemkeSolver::Impl::new_basis() {
  detail::LemkeColumns cols{&M, &d, n};
  if (has_lifted && settings.lifted_basis) {
    cols.J = &lifted_J;
    cols.JT = &lifted_JT;
    cols.H = &lifted_H;
    cols.dof_inverse_mass = &lifted_d;
    cols.shift = &lifted_shift;
  }
  basis = method == LemkeMethod::dense
              ? detail::make_dense_lemke_basis(cols, settings.refactor_interval)
              : detail::make_sparse_lemke_basis(cols, settings.refactor_interval, settings.sparse_columns,
                                                shared_lu.get(), settings.lu_pivot_tolerance, settings.lu_ordering);
  factor_current = false;
}

// No z, w, z_basic or residual in the result; z and w become empty, their storage parked
// in z_spare / w_spare.
void LemkeSolver::Impl::discard_solution() {
  if (z_spare.size() == 0) result.z.swap(z_spare);
  if (w_spare.size() == 0) result.w.swap(w_spare);
  result.z.resize(0);
  result.w.resize(0);
  result.z_basic.clear();
  result.info.complementarity = std::numeric_limits<double>::quiet_NaN();
}

// Result fields back to "unsolved", keeping the storage of z, w, z_basic and message.
void LemkeSolver::Impl::reset_result() {
  discard_solution();
  result.info.status = LcpStatus::unsolved;
  result.info.message.clear();
  result.info.pivots = 0;
  result.info.seconds = 0.0;
  result.info.warm_started = false;
  result.info.crash_started = false;
  result.info.crash_pivots = 0;
  result.info.repair_rounds = 0;
  result.info.tie_breaks = 0;
  result.info.method = method;
  result.info.refactorizations = 0;
  result.info.regularization = 0.0;
}

// v of size n, taking the parked storage when v has none.
void LemkeSolver::Impl::take(Vector& v, Vector& spare) const {
  if (v.size() != n && spare.size() == n) v.swap(spare);
  v.resize(n);
}

// Factorizes B for `basic` from scratch (counted, with the refactorization hook around it);
// false if B is singular.
bool LemkeSolver::Impl::factorize_basic() {
  ++result.info.refactorizations;
  factor_current = false;
  if (refactor_hook) refactor_hook(true);
  const bool ok = basis->refactor(basic);
  if (refactor_hook) refactor_hook(false);
  if (!ok) return false;
  factored_basic = basic;
  factor_current = true;
  return true;
}

// Factorizes the current basis (unless the factorization already holds it) and sets
// x_B = B⁻¹q with up to two steps of iterative refinement (r = q − B x_B, residual_of_basic; KLU's
// threshold pivoting and ill-conditioned bases of resting-contact problems with
// ‖q‖ ~ 1e-19 need them); false if B is singular.
bool LemkeSolver::Impl::refactor(Vector& x) {
  if ((!factor_current || basic != factored_basic) && !factorize_basic()) return false;
  x = q;
  basis->solve(x);
  if (!x.allFinite()) return false;
  for (int step = 0; step < 2; ++step) {
    residual_of_basic(x, refine);
    if (refine.lpNorm<Eigen::Infinity>() == 0.0) break;
    basis->solve(refine);
    x += refine;
  }
  return x.allFinite();
}

// r = q − B x for the basic variables' values x. B's z columns are −M's: with the lifted
// basis, M z_B = J (d ∘ Jᵀz_B) + (H + σI) z_B (z_B: x at the basic z's rows), O(nnz(J) +
// nnz(H)) work instead of the nonzeros of the basic z's columns of M (J D Jᵀ couples every
// contact of a body with every other, so M's columns are several times denser than J's
// rows), and the residual of the form that the basis factorizes.
void LemkeSolver::Impl::residual_of_basic(const Vector& x, Vector& r) {
  r = q;
  if (refine_dof.size() == 0 || !(has_lifted && settings.lifted_basis)) {
    const detail::LemkeColumns cols{&M, &d, n};
    for (Index k = 0; k < n; ++k) cols.add_to(basic[k], -x(k), r);
    return;
  }
  refine_z.setZero();
  for (Index k = 0; k < n; ++k) {
    const Index var = basic[k];
    if (var < n) r(var) -= x(k);
    else if (var < 2 * n) refine_z(var - n) = x(k);
    else r += x(k) * d;  // z₀'s column is −d
  }
  refine_dof.noalias() = lifted_JT * refine_z;
  refine_dof.array() *= lifted_d.array();
  r.noalias() += lifted_J * refine_dof;
  r.noalias() += lifted_H * refine_z;
  if (lifted_shift != 0.0) r += lifted_shift * refine_z;
}

LemkeSolver::LemkeSolver(LemkeSettings settings) : impl_(std::make_unique<Impl>()) {
  const std::string e = settings.validation_error();
  if (!e.empty()) throw InputError("invalid LemkeSettings: " + e);
  impl_->settings = std::move(settings);
}
LemkeSolver::~LemkeSolver() = default;
LemkeSolver::LemkeSolver(LemkeSolver&&) noexcept = default;
LemkeSolver& LemkeSolver::operator=(LemkeSolver&&) noexcept = default;

// Checks the lifted form against M's size n and stores it (J, Jᵀ, H, d).
void LemkeSolver::Impl::set_lifted(const LcpLiftedForm& lifted, Index n_of_m) {
  const Index dofs = lifted.J.cols();
  if (lifted.J.rows() != n_of_m || lifted.H.rows() != n_of_m || lifted.H.cols() != n_of_m || lifted.d.size() != dofs)
    throw InputError("LCP: lifted form has J " + std::to_string(lifted.J.rows()) + "x" + std::to_string(dofs) +
                     ", d " + std::to_string(lifted.d.size()) + ", H " + std::to_string(lifted.H.rows()) + "x" +
                     std::to_string(lifted.H.cols()) + " for M of size " + std::to_string(n_of_m));
  auto finite = [](const SparseMatrix& A) {
    for (Index k = 0; k < A.nonZeros(); ++k)
      if (!std::isfinite(A.valuePtr()[k])) return false;
    return true;
  };
  if (!finite(lifted.J) || !finite(lifted.H) || !lifted.d.allFinite())
    throw InputError("LCP: lifted form has a NaN or infinite entry");
  if (dofs > 0 && !(lifted.d.minCoeff() > 0)) throw InputError("LCP: lifted form needs d > 0");
  lifted_J = lifted.J;
  lifted_J.makeCompressed();
  lifted_JT = lifted.J.transpose();
  lifted_JT.makeCompressed();
  lifted_H = lifted.H;
  lifted_H.makeCompressed();
  lifted_d = lifted.d;
  lifted_shift = 0.0;
  has_lifted = true;
}

void LemkeSolver::setup(const SparseMatrix& M, const Vector& q, const LcpLiftedForm& lifted) {
  Impl& m = *impl_;
  const Index n = M.rows();
  m.set_lifted(lifted, n);
  m.setup(M, q);  // validates M and q
  // M r = J (d ∘ Jᵀr) + H r for two probe vectors (one positive, one of alternating sign).
  for (int probe = 0; probe < 2; ++probe) {
    Vector r(n);
    for (Index i = 0; i < n; ++i) r(i) = (probe == 0 ? 1.0 : (i % 2 ? -1.0 : 1.0)) * (1.0 + (i % 7) / 7.0);
    const Vector delassus_part = m.lifted_J * m.lifted_d.cwiseProduct(m.lifted_JT * r);
    const Vector h_part = m.lifted_H * r, m_part = m.M * r;
    const double scale = std::max({m_part.lpNorm<Eigen::Infinity>(), delassus_part.lpNorm<Eigen::Infinity>(),
                                   h_part.lpNorm<Eigen::Infinity>(), std::numeric_limits<double>::min()});
    const double mismatch = (m_part - delassus_part - h_part).lpNorm<Eigen::Infinity>() / scale;
    if (!(mismatch <= 1e-8)) {
      m.has_lifted = false;
      m.is_setup = false;
      throw InputError("LCP: lifted form J diag(d) J^T + H differs from M (relative " + std::to_string(mismatch) +
                       " on a probe vector)");
    }
  }
}

void LemkeSolver::setup(const LcpLiftedForm& lifted, const Vector& q) {
  Impl& m = *impl_;
  const Index n = q.size();
  m.is_setup = false;
  m.set_lifted(lifted, n);
  // ‖M‖∞ ≤ max_i Σ_j (Σ_k |J_ik| d_k |J_jk| + |H_ij|) = ‖|J| (d ∘ |J|ᵀ1) + |H|1‖∞ (the tolerances' scale).
  const Vector abs_dof = m.lifted_d.cwiseProduct(m.lifted_JT.cwiseAbs() * Vector::Ones(n));
  const Vector bound = m.lifted_J.cwiseAbs() * abs_dof + m.lifted_H.cwiseAbs() * Vector::Ones(n);
  m.matrix_formed = false;
  m.M.resize(n, n);
  m.M.setZero();
  m.setup_sizes(q, n ? bound.maxCoeff() : 0.0);
  // The dense method and the basis of M's columns read M at every factorization.
  if (m.method == LemkeMethod::dense || !m.settings.lifted_basis) m.ensure_matrix();
}

// M = J diag(d) Jᵀ + H from the lifted form, when setup(lifted, q) left it unformed.
void LemkeSolver::Impl::ensure_matrix() const {
  if (matrix_formed) return;
  SparseMatrix scaled = lifted_J * lifted_d.asDiagonal();
  SparseMatrix product = scaled * lifted_JT;
  M = product + lifted_H;
  M.makeCompressed();
  matrix_formed = true;
}

// out = M z (z, out of size n; M formed or in its lifted form).
void LemkeSolver::Impl::apply_matrix(const Vector& z, Vector& out) {
  if (matrix_formed) {
    out.noalias() = M * z;
    return;
  }
  refine_dof.noalias() = lifted_JT * z;
  refine_dof.array() *= lifted_d.array();
  out.noalias() = lifted_J * refine_dof;
  out.noalias() += lifted_H * z;
}

void LemkeSolver::setup(const SparseMatrix& M, const Vector& q) {
  impl_->has_lifted = false;
  impl_->setup(M, q);
}

// Validates M and q and sizes everything for them (the lifted form, if any, is set).
void LemkeSolver::Impl::setup(const SparseMatrix& M_in, const Vector& q_in) {
  if (M_in.rows() != M_in.cols()) throw InputError("LCP: M is not square");
  if (q_in.size() != M_in.rows()) throw InputError("LCP: q has size " + std::to_string(q_in.size()) + ", M has " +
                                                   std::to_string(M_in.rows()) + " rows");
  for (Index k = 0; k < M_in.nonZeros(); ++k)
    if (!std::isfinite(M_in.valuePtr()[k])) throw InputError("LCP: M has a NaN or infinite entry");
  is_setup = false;
  M = M_in;
  M.makeCompressed();
  matrix_formed = true;
  const Index n = q_in.size();
  Vector row_sums = Vector::Zero(n);
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(M, j); it; ++it) row_sums(it.row()) += std::abs(it.value());
  setup_sizes(q_in, n ? row_sums.maxCoeff() : 0.0);
}

// Validates q and the settings against n = q.size(), sets the tolerances from mnorm (‖M‖∞,
// or a bound on it) and sizes everything.
void LemkeSolver::Impl::setup_sizes(const Vector& q_in, double m_norm) {
  Impl& m = *this;
  if (!q_in.allFinite()) throw InputError("LCP: q has a NaN or infinite entry");
  const Index n = static_cast<Index>(q_in.size());
  if (m.settings.covering.size() != 0 && m.settings.covering.size() != n)
    throw InputError("LCP: covering vector has the wrong size");
  m.n = n;
  m.set_q(q_in);
  m.d = m.settings.covering.size() ? m.settings.covering : Vector::Ones(n);
  m.mnorm = m_norm;
  m.tol = m.settings.pivot_tolerance > 0 ? m.settings.pivot_tolerance
                                         : 10.0 * std::max<Index>(n, 1) * std::numeric_limits<double>::epsilon() *
                                               std::max(1.0, m_norm);
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

std::shared_ptr<LemkeSharedFactorization> make_lemke_shared_factorization() {
  return std::make_shared<LemkeSharedFactorization>();
}

void LemkeSolver::share_factorization(std::shared_ptr<LemkeSharedFactorization> shared) {
  impl_->shared_lu = std::move(shared);
}

void LemkeSolver::warm_start(const std::vector<bool>& z_basic) {
  if (static_cast<Index>(z_basic.size()) != impl_->n) throw InputError("LCP: warm-start basis has the wrong size");
  impl_->warm = z_basic;
  impl_->warm_point.resize(0);
  impl_->warm_fallback.clear();
}

void LemkeSolver::warm_start_point(const Vector& z, const std::vector<bool>& fallback) {
  if (!impl_->is_setup) throw std::logic_error("LemkeSolver::warm_start_point before setup");
  if (z.size() != impl_->n) throw InputError("LCP: warm-start point has the wrong size");
  if (!z.allFinite()) throw InputError("LCP: warm-start point has a NaN or infinite entry");
  if (!fallback.empty() && static_cast<Index>(fallback.size()) != impl_->n)
    throw InputError("LCP: fallback basis of the warm-start point has the wrong size");
  impl_->warm_point = z;
  impl_->warm_fallback = fallback;
  impl_->warm.clear();
}

const LcpResult& LemkeSolver::solve() {
  Impl& m = *impl_;
  if (!m.is_setup) throw std::logic_error("LemkeSolver::solve before setup");
  const auto t0 = std::chrono::steady_clock::now();
  m.reset_result();
  // Counted over the whole solve (its retries included), so reset here and not per retry.
  m.result.info.ray_rechecks = 0;
  m.result.info.purification_steps = 0;
  m.run();
  m.warm.clear();
  m.warm_point.resize(0);
  m.warm_fallback.clear();
  // Retries after a failure (ray termination, singular basis, pivot limit) of degenerate
  // problems, where roundoff sends the pivot path to a secondary ray (lcp_types.hpp):
  // first other covering vectors (another pivot path to the same LCP), then M + εI (as
  // Drake's MobyLCP does), whose z is accepted only if it solves the ORIGINAL LCP to the
  // residual tolerance.
  const LcpStatus first = m.result.info.status;
  const int retries = m.settings.covering_retries + m.settings.regularization_retries;
  if (first != LcpStatus::solved && first != LcpStatus::pivot_limit && retries > 0 && m.n > 0) {
    m.ensure_matrix();
    const SparseMatrix M0 = m.M;
    const Vector d0 = m.d;
    long pivots = m.result.info.pivots, refactorizations = m.result.info.refactorizations;
    long tie_breaks = m.result.info.tie_breaks;
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
      m.lifted_shift = covering ? 0.0 : eps;
      if (!covering) {
        m.M = M0 + eps * I;
        m.M.makeCompressed();
      }
      m.factor_current = false;
      m.reset_result();
      m.run();
      pivots += m.result.info.pivots;
      refactorizations += m.result.info.refactorizations;
      tie_breaks += m.result.info.tie_breaks;
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
    m.lifted_shift = 0.0;
    m.d = d0;
    m.factor_current = false;
    m.result.info.pivots = pivots;
    m.result.info.refactorizations = refactorizations;
    m.result.info.tie_breaks = tie_breaks;
  }
  m.result.info.matrix_formed = m.matrix_formed;
  m.result.info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return m.result;
}

const LcpResult& LemkeSolver::result() const { return impl_->result; }

void LemkeSolver::set_refactorization_hook(void (*hook)(bool starting)) { impl_->refactor_hook = hook; }

void LemkeSolver::set_pivot_trace(std::vector<Index>* trace, long max_pivots) {
  impl_->pivot_trace = trace;
  impl_->pivot_trace_limit = max_pivots;
}

}  // namespace lcprelax
