// DenseQpSolver: setup, the Mehrotra predictor-corrector iteration on dense normal
// equations, the unscaled termination test and the hand-over to QpSolver (method and
// conventions: dense_qp_solver.hpp).
#include "dense_qp_impl.hpp"
#include "vector_norms.hpp"

#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace lcprelax {
namespace dense_qp_detail {



// Class of a row or bound: 0 absent, 1 lower, 2 upper, 3 both sides, 4 equality.
char side_class(double lo, double up) {
  if (lo == up) return 4;
  return static_cast<char>((std::isfinite(lo) ? 1 : 0) + (std::isfinite(up) ? 2 : 0));
}

// QpInfo's defaults, keeping the message's storage (no allocation per solve).
void reset_info(QpInfo& i) {
  static const QpInfo fresh = [] {
    QpInfo f;
    f.message = std::string();
    return f;
  }();
  std::string message;
  message.swap(i.message);
  i = fresh;
  message.assign("solve() was not called");
  i.message.swap(message);
}

}  // namespace dense_qp_detail

using namespace dense_qp_detail;

bool DenseQpSolver::Impl::same_classes(const QpProblem& p) const {
  if (row_class.size() != static_cast<std::size_t>(p.num_inequalities()) ||
      var_class.size() != static_cast<std::size_t>(p.num_variables()))
    return false;
  for (Index i = 0; i < p.num_inequalities(); ++i)
    if (row_class[static_cast<std::size_t>(i)] != side_class(p.l(i), p.u(i))) return false;
  for (Index j = 0; j < p.num_variables(); ++j)
    if (var_class[static_cast<std::size_t>(j)] != side_class(p.xl(j), p.xu(j))) return false;
  return true;
}

void DenseQpSolver::Impl::load(const QpProblem& p) {
  problem = p;
  n = p.num_variables();
  eq_rows.clear(), sides.clear(), gi_source.clear(), row_class.clear(), var_class.clear();
  for (Index i = 0; i < p.num_equalities(); ++i) eq_rows.push_back({EqSource::a_row, i});
  for (Index i = 0; i < p.num_inequalities(); ++i) {
    const char c = side_class(p.l(i), p.u(i));
    row_class.push_back(c);
    if (c == 4) {
      eq_rows.push_back({EqSource::g_row, i});
      continue;
    }
    if (c == 0) continue;
    const Index r = static_cast<Index>(gi_source.size());
    gi_source.push_back(i);
    if (c & 1) sides.push_back({true, i, r, 1.0});
    if (c & 2) sides.push_back({true, i, r, -1.0});
  }
  for (Index j = 0; j < n; ++j) {
    const char c = side_class(p.xl(j), p.xu(j));
    var_class.push_back(c);
    if (c == 4) {
      eq_rows.push_back({EqSource::fixed_variable, j});
      continue;
    }
    if (c & 1) sides.push_back({false, j, 0, 1.0});
    if (c & 2) sides.push_back({false, j, 0, -1.0});
  }
  me = static_cast<Index>(eq_rows.size());
  mc = static_cast<Index>(sides.size());
  p_factor_ready = false;
  P.setZero(n, n);
  A.setZero(p.num_equalities(), n);
  G.setZero(p.num_inequalities(), n);
  Ae.setZero(me, n);
  Gi.setZero(static_cast<Index>(gi_source.size()), n);
  be.setZero(me);
  d.setZero(mc);
  size_work();
  fill_values();
}

void DenseQpSolver::Impl::fill_values() {
  const QpProblem& p = problem;
  // P's stored values unchanged since the last fill: the active-set method's factors of P stay.
  const Index nnz_p = p.P.nonZeros();
  if (p_factor_ready && p_values.size() == nnz_p &&
      std::equal(p.P.valuePtr(), p.P.valuePtr() + nnz_p, p_values.data())) {
    // same P
  } else {
    p_factor_ready = false;
    p_values = Eigen::Map<const Vector>(p.P.valuePtr(), nnz_p);
    P.setZero();
    for (Index j = 0; j < p.P.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(p.P, j); it; ++it) {
        P(it.row(), j) += it.value();
        if (it.row() != j) P(j, it.row()) += it.value();
      }
  }
  A = p.A;
  G = p.G;
  for (Index r = 0; r < me; ++r) {
    const EqRow& e = eq_rows[static_cast<std::size_t>(r)];
    switch (e.source) {
      case EqSource::a_row: Ae.row(r) = A.row(e.index), be(r) = p.b(e.index); break;
      case EqSource::g_row: Ae.row(r) = G.row(e.index), be(r) = p.l(e.index); break;
      case EqSource::fixed_variable: Ae.row(r).setZero(), Ae(r, e.index) = 1.0, be(r) = p.xl(e.index); break;
    }
  }
  for (Index r = 0; r < Gi.rows(); ++r) Gi.row(r) = G.row(gi_source[static_cast<std::size_t>(r)]);
  for (Index k = 0; k < mc; ++k) {
    const Side& sd = sides[static_cast<std::size_t>(k)];
    const double lo = sd.on_g_row ? p.l(sd.index) : p.xl(sd.index);
    const double up = sd.on_g_row ? p.u(sd.index) : p.xu(sd.index);
    d(k) = sd.sign > 0 ? lo : -up;
  }
  reg_base = 1e-12 * std::max(1.0, n > 0 ? P.diagonal().cwiseAbs().maxCoeff() : 0.0);
}

void DenseQpSolver::Impl::size_work() {
  for (Vector* v : {&x, &rd, &dx, &f, &tmp_n, &as_u, &as_d, &as_z, &as_r, &as_normal, &rv.Px, &rv.Aty, &rv.Gtz})
    v->setZero(n);
  rv.Ax.setZero(problem.num_equalities());
  rv.Gx.setZero(problem.num_inequalities());
  for (Vector* v : {&y, &re, &dy, &tmp_me}) v->setZero(me);
  for (Vector* v : {&s, &lam, &rp, &rc, &ds, &dlam, &w, &cx, &side_norm1}) v->setZero(mc);
  Gx.setZero(Gi.rows());
  Drow.setZero(Gi.rows());
  K.setZero(n, n);
  E.setZero(me + mc, n);
  WE.setZero(n, me + mc);
  S_adj.setZero(me + mc, me + mc);
  W.setZero(n, me);
  S.setZero(me, me);
  result.x.setZero(n);
  result.y.setZero(problem.num_equalities());
  result.z.setZero(problem.num_inequalities());
  result.z_bounds.setZero(n);
}

void DenseQpSolver::Impl::apply_C(const Vector& v, Vector& out) {
  Gx.noalias() = Gi * v;
  for (Index k = 0; k < mc; ++k) {
    const Side& sd = sides[static_cast<std::size_t>(k)];
    out(k) = sd.sign * (sd.on_g_row ? Gx(sd.gi_row) : v(sd.index));
  }
}

void DenseQpSolver::Impl::apply_Ct(const Vector& v, Vector& out) {
  Drow.setZero();  // scratch: per Gi row, Σ sign·v
  out.setZero();
  for (Index k = 0; k < mc; ++k) {
    const Side& sd = sides[static_cast<std::size_t>(k)];
    if (sd.on_g_row)
      Drow(sd.gi_row) += sd.sign * v(k);
    else
      out(sd.index) += sd.sign * v(k);
  }
  out.noalias() += Gi.transpose() * Drow;
}

bool DenseQpSolver::Impl::fill_result_and_check() {
  const QpProblem& p = problem;
  QpResult& r = result;
  r.x = x;
  r.z.setZero(), r.z_bounds.setZero();
  for (Index k = 0; k < me; ++k) {
    const EqRow& e = eq_rows[static_cast<std::size_t>(k)];
    switch (e.source) {
      case EqSource::a_row: r.y(e.index) = -y(k); break;
      case EqSource::g_row: r.z(e.index) = -y(k); break;
      case EqSource::fixed_variable: r.z_bounds(e.index) = -y(k); break;
    }
  }
  for (Index k = 0; k < mc; ++k) {
    const Side& sd = sides[static_cast<std::size_t>(k)];
    (sd.on_g_row ? r.z(sd.index) : r.z_bounds(sd.index)) -= sd.sign * lam(k);
  }
  // The unscaled residuals and test of QpSolver (qp_settings.hpp, qp_solution.cpp).
  const detail::Residuals res = detail::compute_residuals(p, r, rv.Px, rv.Ax, rv.Gx, rv.Aty, rv.Gtz);
  r.info.primal_residual = res.primal, r.info.dual_residual = res.dual, r.info.duality_gap = res.gap;
  r.info.objective = 0.5 * x.dot(rv.Px) + p.q.dot(x) + p.r;
  return detail::within(res, settings, 1.0);
}

void DenseQpSolver::Impl::run_fallback(const char* why) {
  if (!fallback) fallback = std::make_unique<QpSolver>(settings);
  if (fallback_ready && fallback->can_update(problem)) {
    fallback->update(problem);
  } else {
    fallback->setup(problem);
    fallback_ready = true;
  }
  const int dense_iterations = result.info.iterations;
  result = fallback->solve();
  result.info.iterations += dense_iterations;
  result.info.message = std::string("dense interior point ") + why + "; solved by QpSolver: " + result.info.message;
  used_fallback = true;
}

DenseQpSolver::DenseQpSolver(QpSettings settings, DenseQpMethod method) : impl_(std::make_unique<Impl>()) {
  if (std::string e = settings.validation_error(); !e.empty()) throw InputError("QpSettings: " + e);
  impl_->settings = settings;
  impl_->use_active_set = method == DenseQpMethod::active_set_first;
}
DenseQpSolver::~DenseQpSolver() = default;
DenseQpSolver::DenseQpSolver(DenseQpSolver&&) noexcept = default;
DenseQpSolver& DenseQpSolver::operator=(DenseQpSolver&&) noexcept = default;

bool DenseQpSolver::suits(const QpProblem& p) {
  return 3 * p.num_variables() + p.num_equalities() + 2 * p.num_inequalities() <= kMaxDimension;
}

void DenseQpSolver::setup(const QpProblem& problem) {
  problem.validate();
  impl_->load(problem);
  impl_->has_setup = true;
  impl_->result.info = QpInfo{};
}

void DenseQpSolver::update(const QpProblem& problem) {
  if (!impl_->has_setup) throw InputError("DenseQpSolver::update() before setup()");
  if (!impl_->problem.same_pattern(problem))
    throw InputError("DenseQpSolver::update(): the sizes or sparsity pattern differ from setup()'s");
  problem.validate();
  if (impl_->same_classes(problem)) {
    impl_->problem = problem;
    impl_->fill_values();
  } else {
    impl_->load(problem);
  }
  impl_->result.info = QpInfo{};
}

const QpResult& DenseQpSolver::solve() {
  Impl& m = *impl_;
  if (!m.has_setup) throw InputError("DenseQpSolver::solve() before setup()");
  const auto t0 = std::chrono::steady_clock::now();
  m.used_fallback = false;
  reset_info(m.result.info);
  m.result.info.kkt_backend = KktBackend::dense;
  m.exact_active_set = false;
  if (m.use_active_set && m.run_active_set() && m.fill_result_and_check()) {
    m.exact_active_set = true;
    m.factorized_at_final = m.factorize_adjoint();
    ++m.result.info.factorizations;
    m.result.info.status = QpStatus::solved;
    m.result.info.message = "solved by the dense active-set method";
  } else if (m.run_dense()) {
    m.result.info.status = QpStatus::solved;
    m.result.info.message = "solved by the dense interior point";
  } else {
    m.run_fallback(m.result.info.iterations >= m.max_interior_point_iterations() ? "did not converge" : "failed");
  }
  m.result.info.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return m.result;
}

const QpResult& DenseQpSolver::result() const { return impl_->result; }
bool DenseQpSolver::used_fallback() const { return impl_->used_fallback; }

}  // namespace lcprelax
