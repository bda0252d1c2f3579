// The convex loss of one island of one step: both phases by the sparse interior point,
// gradient by QpSolver::backward through phase 2, then phase 1 through κ
// (step_loss_convex.hpp).
#include "elapsed.hpp"
#include "step_loss_convex_qp.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/learn/step_loss_convex.hpp>

#include <memory>

#include <cmath>
#include <limits>
#include <string>

namespace lcprelax::learn {
namespace {

constexpr double kKappaSlack[] = {1e-6, 1e-4, 1e-2};  // as models/src/convex_model.cpp
constexpr double kAdjointResidualTolerance = 1e-6;

using detail::since;

bool all_finite(const Vector& v) { return v.allFinite(); }
bool all_finite(const SparseMatrix& A) {
  for (Index k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (!std::isfinite(it.value())) return false;
  return true;
}

void check_input(const ContactSystem& s, const Vector& target, double dt) {
  const Index nc = s.num_contacts(), nf = s.num_friction(), nv = s.num_dofs();
  auto fail = [](const std::string& what) { throw InputError("convex_step_loss: " + what); };
  if (!(dt > 0.0) || !std::isfinite(dt)) fail("dt: must be finite and > 0");
  if (s.Jn.rows() != nc || s.Jn.cols() != nv) fail("Jn: must be contacts x 3·bodies");
  if (s.Jt.rows() != nf || s.Jt.cols() != nv) fail("Jt: must be friction rows x 3·bodies");
  if (s.phi.size() != nc) fail("phi: must have one entry per contact");
  if (s.mu.size() != nf) fail("mu: must have one entry per friction row");
  if (s.minv.size() != nv) fail("minv: must have 3 entries per body");
  if (s.v_star.size() != nv) fail("v_star: must have 3 entries per body");
  if (target.size() != nv) fail("target: must have 3 entries per body (" + std::to_string(nv) + ")");
  for (Index f = 0; f < nf; ++f)
    if (s.friction_rows[static_cast<std::size_t>(f)] < 0 || s.friction_rows[static_cast<std::size_t>(f)] >= nc)
      fail("friction_rows: entry out of range");
  if (!all_finite(s.Jn)) fail("Jn: must be finite");
  if (!all_finite(s.Jt)) fail("Jt: must be finite");
  if (!all_finite(s.phi)) fail("phi: must be finite");
  if (!all_finite(s.mu) || (nf > 0 && s.mu.minCoeff() < 0.0)) fail("mu: must be finite and >= 0");
  if (!all_finite(s.minv) || (nv > 0 && s.minv.minCoeff() <= 0.0)) fail("minv: must be finite and > 0");
  if (!all_finite(s.v_star)) fail("v_star: must be finite");
  if (!all_finite(target)) fail("target: must be finite");
}

void fail_result(StepLossResult& r, const ContactSystem& s, const std::string& message) {
  r.status = ContactStatus::failed;
  r.message = message;
  r.loss = std::numeric_limits<double>::quiet_NaN();
  r.grad.set_zero(s);
}

}  // namespace

std::string ConvexStepLossSettings::validation_error() const {
  const std::string qp_error = qp.validation_error();
  if (!qp_error.empty()) return "qp." + qp_error;
  if (!(rho >= 0.0) || !std::isfinite(rho)) return "rho: must be finite and >= 0";
  if (!(deviation >= 0.0) || !std::isfinite(deviation)) return "deviation: must be finite and >= 0";
  if (std::string e = softening.validation_error(); !e.empty()) return "softening." + e;
  if (!(phase1_regularization >= 0.0) || !std::isfinite(phase1_regularization))
    return "phase1_regularization: must be finite and >= 0";
  return {};
}

StepLossResult convex_step_loss(const ContactSystem& s, const Vector& target, double dt,
                                const ConvexStepLossSettings& settings, ConvexStepLossTimes* times) {
  const std::string bad = settings.validation_error();
  if (!bad.empty()) throw InputError("ConvexStepLossSettings." + bad);
  check_input(s, target, dt);
  ConvexStepLossTimes local_times;
  ConvexStepLossTimes& t = times ? *times : local_times;
  t = ConvexStepLossTimes{};
  auto t0 = detail::Clock::now();

  const Index nc = s.num_contacts(), nf = s.num_friction();
  const double w = settings.deviation, rho = settings.rho;
  const double w1 = settings.phase1_deviation ? w : 0.0;  // phase 1's deviation weight
  StepLossResult r;
  r.grad.set_zero(s);
  const bool lifted = settings.formulation == ConvexFormulation::lifted ||
                      (settings.formulation == ConvexFormulation::automatic && nc >= kLiftedMinContacts);
  // No contact approaching in either of phase 1's terms: λ = 0 (locally constant).
  const Vector gap = s.phi.cwiseMax(0.0) / dt;
  const Vector bn = s.Jn * s.v_star + gap;
  // The softening's target velocity lowers both phases' λn terms (0 for exp_phi).
  const NormalSofteningTerms soft = normal_softening_terms(settings.softening, rho, dt, s.phi, s.Jn * s.v_star);
  const NormalSofteningTerms soft1 = phase1_softening_terms(soft);  // max(v_ref, 0)
  const Vector q1 = s.Jn * ((1.0 + w1) * s.v_star - w1 * target) + gap - soft1.v_ref;
  if (nc == 0 || (bn.minCoeff() >= 0.0 && q1.minCoeff() >= 0.0 && (bn - soft1.v_ref).minCoeff() >= 0.0)) {
    r.status = ContactStatus::solved;
    r.v_next = s.v_star;
    r.loss = (s.v_star - target).squaredNorm();
    r.grad.v_star = 2.0 * (s.v_star - target);
    t.assembly = detail::since(t0);
    return r;
  }
  const detail::ConvexLossData data(s, target, dt, w, lifted);
  // Phase 1 on its own data when its deviation weight differs (phase1_deviation = false).
  std::unique_ptr<detail::ConvexLossData> data1_own;
  if (w1 != w) data1_own = std::make_unique<detail::ConvexLossData>(s, target, dt, w1, lifted);
  const detail::ConvexLossData& data1 = data1_own ? *data1_own : data;
  const detail::ConvexLossQp p1 = detail::convex_loss_phase1(data1, settings.phase1_regularization, soft1);
  detail::ConvexLossQp p2 = detail::convex_loss_phase2(data, soft);
  t.assembly = detail::since(t0);

  t0 = detail::Clock::now();
  QpSolver s1(settings.qp), s2(settings.qp);
  s1.setup(p1.problem);
  const QpResult& r1 = s1.solve();
  r.work = r1.info.iterations;
  if (!has_solution(r1.info.status)) {
    fail_result(r, s, std::string("convex phase 1: ") + to_string(r1.info.status) + ": " + r1.info.message);
    t.solve = detail::since(t0);
    return r;
  }
  const Vector lambda1 = r1.x.segment(p1.lambda_offset, nc);
  const double kappa = lambda1.cwiseMax(0.0).sum();
  double slack_used = 0.0;
  bool solved2 = false;
  for (double slack : kKappaSlack) {
    p2.problem.u(nc) = kappa * (1.0 + slack) + 1e-12;
    if (slack == kKappaSlack[0])
      s2.setup(p2.problem);
    else
      s2.update(p2.problem);
    const QpResult& r2 = s2.solve();
    r.work += r2.info.iterations;
    if (has_solution(r2.info.status)) {
      solved2 = true;
      slack_used = slack;
      break;
    }
  }
  const QpResult& r2 = s2.result();
  if (!solved2) {
    fail_result(r, s, std::string("convex phase 2: ") + to_string(r2.info.status) + ": " + r2.info.message);
    t.solve = detail::since(t0);
    return r;
  }
  const bool exact = r1.info.status == QpStatus::solved && r2.info.status == QpStatus::solved;
  r.status = exact ? ContactStatus::solved : ContactStatus::solved_inaccurate;
  if (!exact) r.message = "a phase stalled within 1e3·eps (solved_inaccurate)";
  const Vector lambda_n = r2.x.segment(p2.lambda_offset, nc);
  const Vector lambda_t = r2.x.segment(p2.lambda_offset + nc, nf);
  const Vector impulse = s.Jn.transpose() * lambda_n + s.Jt.transpose() * lambda_t;
  r.v_next = s.v_star + s.minv.cwiseProduct(impulse);
  const Vector g = 2.0 * (r.v_next - target);
  r.loss = (r.v_next - target).squaredNorm();
  t.solve = detail::since(t0);

  // Backward. Explicit terms of ℓ = ‖v* + DJᵀλ − v̄‖², then phase 2, then phase 1 via κ.
  t0 = detail::Clock::now();
  const Vector Dg = s.minv.cwiseProduct(g);
  detail::ConvexLossPullback pb(data);
  Vector lambda(nc + nf);
  lambda << lambda_n, lambda_t;
  pb.add_outer(lambda, Dg);
  r.grad.v_star = g;
  r.grad.minv = g.cwiseProduct(impulse);
  Vector dl_dx2 = Vector::Zero(p2.problem.num_variables());
  dl_dx2.segment(p2.lambda_offset, nc) = s.Jn * Dg;
  dl_dx2.segment(p2.lambda_offset + nc, nf) = s.Jt * Dg;
  const QpGradient g2 = s2.backward(dl_dx2);
  const double dl_dkappa = pb.add_phase(2, p2, g2, rho) * (1.0 + slack_used);
  Vector dl_dx1 = Vector::Zero(p1.problem.num_variables());
  for (Index i = 0; i < nc; ++i) dl_dx1(p1.lambda_offset + i) = lambda1(i) > 0.0 ? dl_dkappa : 0.0;
  double adjoint = g2.adjoint_residual;
  if ((dl_dx1.array() != 0.0).any()) {  // else κ's bound is inactive and phase 1 contributes nothing
    const QpGradient g1 = s1.backward(dl_dx1);
    if (data1_own) {
      detail::ConvexLossPullback pb1(data1);
      pb1.add_phase(1, p1, g1, settings.phase1_regularization);
      pb1.finish(r.grad);
    } else {
      pb.add_phase(1, p1, g1, settings.phase1_regularization);
    }
    adjoint = std::max(adjoint, g1.adjoint_residual);
  }
  pb.finish(r.grad);
  if (adjoint > kAdjointResidualTolerance) {
    r.status = ContactStatus::solved_inaccurate;
    r.message = "adjoint residual " + std::to_string(adjoint) +
                " > 1e-6: degenerate solution, the gradient is that of the final interior iterate";
  }
  t.backward = detail::since(t0);
  return r;
}

}  // namespace lcprelax::learn
