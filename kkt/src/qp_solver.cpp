// QpSolver: lifecycle and the Mehrotra predictor-corrector loop (method in qp_solver.hpp,
// iterate equations in ipm_iterate.hpp).
#include "qp_solver_impl.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/kkt/qp_convexity.hpp>
#include <lcprelax/sparse/dense_ldlt.hpp>

#include <algorithm>
#include <lcprelax/core/stopwatch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace lcprelax {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

QpSolver::QpSolver(QpSettings settings) : impl_(std::make_unique<Impl>()) { set_settings(settings); }
QpSolver::~QpSolver() = default;
QpSolver::QpSolver(QpSolver&&) noexcept = default;
QpSolver& QpSolver::operator=(QpSolver&&) noexcept = default;

void QpSolver::set_settings(const QpSettings& settings) {
  const std::string e = settings.validation_error();
  if (!e.empty()) throw InputError("invalid QpSettings: " + e);
  impl_->settings = settings;
}

const QpSettings& QpSolver::settings() const { return impl_->settings; }
const QpResult& QpSolver::result() const { return impl_->result; }

void QpSolver::Impl::build(const QpProblem& p) {
  problem = p;
  problem.P.makeCompressed();
  problem.A.makeCompressed();
  problem.G.makeCompressed();
  form = detail::build_standard_form(problem, settings.ruiz_iterations);
  work.resize(form, problem);
  warm.x.setZero(problem.num_variables());  // warm_start() copies into these
  warm.y.setZero(problem.num_equalities());
  warm.z.setZero(problem.num_inequalities());
  warm.z_bounds.setZero(problem.num_variables());
}

namespace {

// Copies the values of `from` into `to` (same pattern; `to` compressed).
void copy_values(const SparseMatrix& from, SparseMatrix& to) {
  if (from.isCompressed()) {
    std::copy(from.valuePtr(), from.valuePtr() + from.nonZeros(), to.valuePtr());
    return;
  }
  double* v = to.valuePtr();
  for (Index j = 0; j < from.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(from, j); it; ++it) *v++ = it.value();
}

}  // namespace

bool QpSolver::Impl::refresh(const QpProblem& p) {
  if (!detail::same_signature(form, p)) return false;
  copy_values(p.P, problem.P);
  copy_values(p.A, problem.A);
  copy_values(p.G, problem.G);
  problem.q = p.q;
  problem.r = p.r;
  problem.b = p.b;
  problem.l = p.l;
  problem.u = p.u;
  problem.xl = p.xl;
  problem.xu = p.xu;
  detail::refresh_standard_form(form, problem, settings.ruiz_iterations);
  return true;
}

void QpSolver::setup(const QpProblem& problem) {
  const auto t0 = Clock::now();
  problem.validate();
  if (impl_->settings.check_convexity)  // a nonconvex P would end `solved` at a saddle point
    if (std::string e = psd_error(problem.P); !e.empty()) throw InputError("invalid QP: the QP is nonconvex: " + e);
  impl_->build(problem);
  std::string message;
  if (!impl_->kkt.setup(impl_->form, impl_->settings.kkt_form, impl_->kkt_backend(), message,
                         impl_->settings.kkt_ordering))
    impl_->kkt_setup_failed("QpSolver::setup", message);
  impl_->is_setup = true;
  impl_->has_warm_start = false;
  impl_->result = QpResult{};
  impl_->setup_seconds = seconds_since(t0);
}

void QpSolver::update(const QpProblem& problem) {
  if (!impl_->is_setup) throw std::logic_error("QpSolver::update before setup");
  if (!problem.same_pattern(impl_->problem))
    throw InputError("QpSolver::update: the sparsity pattern or sizes differ from setup(); call setup()");
  problem.validate();
  if (impl_->settings.check_convexity)  // allocation-free necessary condition only (qp_convexity.hpp)
    if (std::string e = psd_minor_error(problem.P); !e.empty()) throw InputError("invalid QP: the QP is nonconvex: " + e);
  const auto t0 = Clock::now();
  if (!impl_->refresh(problem)) {  // rows changed between equality/one/two-sided: new structure
    impl_->build(problem);
    std::string message;
    if (!impl_->kkt.setup(impl_->form, impl_->settings.kkt_form, impl_->kkt_backend(), message,
                         impl_->settings.kkt_ordering))
      impl_->kkt_setup_failed("QpSolver::update", message);
  }
  impl_->result.info = impl_->fresh_info;
  impl_->setup_seconds = seconds_since(t0);
}

bool QpSolver::can_update(const QpProblem& problem) const {
  return impl_->is_setup && problem.same_pattern(impl_->problem);
}

void QpSolver::warm_start(const Vector& x, const Vector& y, const Vector& z, const Vector& z_bounds) {
  const QpProblem& p = impl_->problem;
  if (x.size() != p.num_variables() || y.size() != p.num_equalities() || z.size() != p.num_inequalities() ||
      z_bounds.size() != p.num_variables())
    throw InputError("QpSolver::warm_start: sizes do not match the problem");
  if (!x.allFinite() || !y.allFinite() || !z.allFinite() || !z_bounds.allFinite())
    throw InputError("QpSolver::warm_start: non-finite value");
  impl_->warm.x = x;
  impl_->warm.y = y;
  impl_->warm.z = z;
  impl_->warm.z_bounds = z_bounds;
  impl_->has_warm_start = true;
}

void QpSolver::Impl::kkt_setup_failed(const char* where, const std::string& message) const {
  // The dense backend chosen explicitly for a KKT system above its size limit is the user's
  // choice that cannot work (an input error, exit 2 in the CLI), not an internal failure.
  if (settings.kkt_backend == KktBackend::dense) {
    const long rows = static_cast<long>(form.n) + form.me + form.mg;
    throw InputError(std::string(where) + ": kkt_backend = dense cannot factorize this problem (KKT dimension " +
                     std::to_string(rows) + ", dense LDLᵀ handles at most " +
                     std::to_string(sparse::DenseLdlt::kMaxDimension) + "): use cholmod or automatic (" + message +
                     ")");
  }
  throw std::runtime_error(std::string(where) + ": " + message);
}

bool QpSolver::Impl::factorize(QpInfo& info) {
  const auto t0 = Clock::now();
  for (;;) {
    const auto tf = Clock::now();
    const sparse::FactorResult r = kkt.factorize(form, Db, Dg, rho, delta, delta_rows);
    last_factor_seconds = seconds_since(tf);
    ++info.factorizations;
    if (r.ok()) break;
    if (delta_rows < delta) {  // first give the inequality block its regularization back
      delta_rows = delta;
      may_drop_row_regularization = false;
      ++info.factor_retries;
      continue;
    }
    if (rho >= settings.reg_max) {
      info.message = "KKT factorization failed at the largest regularization: " + r.message;
      info.factor_seconds += seconds_since(t0);
      return false;
    }
    rho = std::min(rho * 10.0, settings.reg_max);
    delta = std::min(delta * 10.0, settings.reg_max);
    delta_rows = delta;
    ++info.factor_retries;
  }
  info.factor_seconds += seconds_since(t0);
  return true;
}

int QpSolver::Impl::newton_step() {
  detail::Workspace& w = work;
  it.xi_terms(form.mg, form.n, w.xig, w.xib);
  w.rx = -w.rd - w.xib;
  w.ry = -w.rp;
  w.rz = (-w.xig.array() / Dg.array()).matrix();
  const int steps = kkt.solve(form, w.rx, w.ry, w.rz, w.dx, w.dy, w.dz, settings.max_refinement);
  w.dvg.noalias() = form.G * w.dx;
  // dζ_b = −r_d − (P̃dx + Ẽᵀdy + G̃ᵀdζ_g): the first Newton block exactly (ipm_iterate.hpp).
  w.dzb.noalias() = form.P.selfadjointView<Eigen::Upper>() * w.dx;
  if (form.me) w.dzb.noalias() += form.Et * w.dy;
  if (form.mg) w.dzb.noalias() += form.Gt * w.dz;
  w.dzb = -w.rd - w.dzb;
  it.recover_side_steps(w.dx, w.dvg, w.dz, settings.exact_bound_steps ? w.dzb : w.empty);
  return steps;
}

void QpSolver::Impl::load_unscaled_point(const Vector& x, const Vector& y, const Vector& z, const Vector& z_bounds) {
  it.x = x.cwiseQuotient(form.Dx);
  it.y.setZero(form.me);
  for (Index k = 0; k < form.me; ++k) {
    const Index s = form.eq_index[k];
    const double v = form.eq_source[k] == detail::EqSource::a_row   ? y(s)
                     : form.eq_source[k] == detail::EqSource::g_row ? z(s)
                                                                    : z_bounds(s);
    it.y(k) = form.c * v / form.Ee(k);
  }
  for (Index k = 0; k < form.mg; ++k) work.zg(k) = form.c * z(form.g_index[k]) / form.Eg(k);
  work.zb = form.c * z_bounds.cwiseProduct(form.Dx);
  it.compute_side_residuals(form);
}

bool QpSolver::Impl::initial_point(QpInfo& info) {
  detail::Workspace& w = work;
  it.init_sides(form);
  start_zmax = 0.0;  // no multiplier-scaled third run after a warm start
  if (has_warm_start) {
    load_unscaled_point(warm.x, warm.y, warm.z, warm.z_bounds);
    const Vector &zg = w.zg, &zb = w.zb;
    for (detail::Side* s : it.sides()) {
      const bool rows = (s == &it.g_lower || s == &it.g_upper);
      for (Index k = 0; k < s->size(); ++k) {
        const Index q = s->idx[k];
        const double v = rows ? it.vg(q) : it.x(q);
        const double zz = rows ? zg(q) : zb(q);
        s->s(k) = std::max(s->upper ? s->bound(k) - v : v - s->bound(k), 1e-2);
        s->z(k) = std::max(s->upper ? zz : -zz, 1e-2);
      }
    }
    return true;
  }
  // Cold start: minimize ½x̃ᵀP̃x̃ + q̃ᵀx̃ + ½‖x̃ − x_c‖²_Db + ½‖G̃x̃ − g_c‖² s.t. Ẽx̃ = b̃, with
  // x_c, g_c the projections of 0 on the bounds, then slacks pushed to at least 1.
  Db.setZero(form.n);
  for (Index j = 0; j < form.n; ++j)
    if (std::isfinite(form.xl(j)) || std::isfinite(form.xu(j))) Db(j) = 1.0;
  Dg.setOnes(form.mg);
  if (!factorize(info)) return false;
  w.xc = Vector::Zero(form.n).cwiseMax(form.xl).cwiseMin(form.xu);
  w.gc = Vector::Zero(form.mg).cwiseMax(form.gl).cwiseMin(form.gu);
  w.rhs_x = -form.q + Db.cwiseProduct(w.xc);
  info.refinement_steps += kkt.solve(form, w.rhs_x, form.be, w.gc, it.x, it.y, w.dz, settings.max_refinement);
  if (form.me == 0) it.y.resize(0);
  // Slacks ŝ of the least-squares point and multiplier estimates ẑ = −ŝ (the row
  // multiplier of that solve), shifted into the interior by Mehrotra's heuristic
  // (Mehrotra 1992, §7; the estimate ẑ = −ŝ as in CVXOPT's starting point).
  it.compute_side_residuals(form);
  double min_s = std::numeric_limits<double>::infinity();
  for (detail::Side* s : it.sides()) {
    const bool rows = (s == &it.g_lower || s == &it.g_upper);
    for (Index k = 0; k < s->size(); ++k) {
      const double v = rows ? it.vg(s->idx[k]) : it.x(s->idx[k]);
      s->s(k) = s->upper ? s->bound(k) - v : v - s->bound(k);
      min_s = std::min(min_s, s->s(k));
    }
  }
  if (it.num_constraints() == 0) return true;
  double max_s = -std::numeric_limits<double>::infinity();
  for (detail::Side* s : it.sides())
    if (s->size()) max_s = std::max(max_s, s->s.maxCoeff());
  const double shift_s0 = std::max(-1.5 * min_s, 0.0), shift_z0 = std::max(1.5 * max_s, 0.0);  // ẑ = −ŝ
  double sz = 0.0, sum_s = 0.0, sum_z = 0.0;
  for (detail::Side* s : it.sides()) {
    s->z = (shift_z0 - s->s.array()).matrix();
    s->s.array() += shift_s0;
    sz += s->s.dot(s->z);
    sum_s += s->s.sum();
    sum_z += s->z.sum();
  }
  const double shift_s = sum_z > 0 ? 0.5 * sz / sum_z : 1.0, shift_z = sum_s > 0 ? 0.5 * sz / sum_s : 1.0;
  for (detail::Side* s : it.sides()) {
    s->s.array() += std::max(shift_s, 1e-2);
    s->z.array() += std::max(shift_z, 1e-2);
  }
  start_zmax = 0.0;
  for (detail::Side* s : it.sides()) {
    s->z *= start_multiplier_scale;  // 1 except in the multiplier-scaled third run (qp_solve.cpp)
    if (s->size()) start_zmax = std::max(start_zmax, s->z.maxCoeff());
  }
  return true;
}

double QpSolver::Impl::multiplier_growth(const detail::Iterate& final) const {
  double zmax = 0.0;
  for (const detail::Side* s : final.sides())
    if (s->size()) zmax = std::max(zmax, s->z.maxCoeff());
  return start_zmax > 0 && std::isfinite(zmax) ? zmax / start_zmax : 0.0;
}

int QpSolver::numeric_factorizations() const { return impl_->kkt.numeric_factorizations(); }

}  // namespace lcprelax
