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

namespace {

// Both phases solved for one island, kept with their solvers so that the backward pass
// (linear in the cotangent of v⁺) can run once for the loss's gradient or once per row of
// ∂v⁺/∂data (convex_step_jacobian).
class ConvexStepSolve {
 public:
  ConvexStepSolve(const ContactSystem& s, const Vector& target, double dt, const ConvexStepLossSettings& settings,
                  ConvexStepLossTimes& t)
      : s_(s), settings_(settings) {
    auto t0 = detail::Clock::now();
    const Index nc = s.num_contacts(), nf = s.num_friction();
    const double w = settings.deviation, rho = settings.rho;
    const double w1 = settings.phase1_deviation ? w : 0.0;  // phase 1's deviation weight
    result.grad.set_zero(s);
    const bool lifted = settings.formulation == ConvexFormulation::lifted ||
                        (settings.formulation == ConvexFormulation::automatic && nc >= kLiftedMinContacts);
    // No contact approaching in either of phase 1's terms: λ = 0 (locally constant).
    const Vector gap = s.phi.cwiseMax(0.0) / dt;
    const Vector bn = s.Jn * s.v_star + gap;
    // The softening's target velocity lowers both phases' λn terms (0 for exp_phi).
    NormalSofteningTerms soft = normal_softening_terms(settings.softening, rho, dt, s.phi, s.Jn * s.v_star);
    if (const std::string e = normal_softness_error(s); !e.empty()) throw InputError("convex step loss: " + e);
    // FrictionTable's c, e; also at c = e = 0, for the terms' derivatives in e (∂v_ref/∂e).
    add_pair_softness(soft, s.phi, s.compliance, s.erp, dt);
    const NormalSofteningTerms soft1 = phase1_softening_terms(soft);  // max(v_ref, 0)
    const Vector q1 = s.Jn * ((1.0 + w1) * s.v_star - w1 * target) + gap - soft1.v_ref;
    if (nc == 0 || (bn.minCoeff() >= 0.0 && q1.minCoeff() >= 0.0 && (bn - soft1.v_ref).minCoeff() >= 0.0)) {
      trivial_ = true;
      result.status = ContactStatus::solved;
      result.v_next = s.v_star;
      t.assembly = detail::since(t0);
      return;
    }
    data_ = std::make_unique<detail::ConvexLossData>(s, target, dt, w, lifted);
    // Phase 1 on its own data when its deviation weight differs (phase1_deviation = false).
    if (w1 != w) data1_own_ = std::make_unique<detail::ConvexLossData>(s, target, dt, w1, lifted);
    const detail::ConvexLossData& data1 = data1_own_ ? *data1_own_ : *data_;
    p1_ = detail::convex_loss_phase1(data1, settings.phase1_regularization, soft1);
    p2_ = detail::convex_loss_phase2(*data_, soft);
    t.assembly = detail::since(t0);

    t0 = detail::Clock::now();
    s1_ = std::make_unique<QpSolver>(settings.qp);
    s2_ = std::make_unique<QpSolver>(settings.qp);
    s1_->setup(p1_.problem);
    const QpResult& r1 = s1_->solve();
    result.work = r1.info.iterations;
    if (!has_solution(r1.info.status)) {
      fail(std::string("convex phase 1: ") + to_string(r1.info.status) + ": " + r1.info.message);
      t.solve = detail::since(t0);
      return;
    }
    lambda1_ = r1.x.segment(p1_.lambda_offset, nc);
    const double kappa = lambda1_.cwiseMax(0.0).sum();
    // As the simulator (models/src/convex_model.cpp): where phase 2 has no solution with the
    // release of open contacts, it is solved again without it.
    bool solved2 = false;
    for (const bool release : {settings.release_open_contacts, false}) {
      if (release)
        lcprelax::detail::release_open_contacts(data_->model, lambda1_.cwiseMax(0.0), p2_.problem, p2_.lambda_offset, dt);
      for (double slack : kKappaSlack) {
        p2_.problem.u(nc) = kappa * (1.0 + slack) + 1e-12;
        if (slack == kKappaSlack[0])
          s2_->setup(p2_.problem);
        else
          s2_->update(p2_.problem);
        const QpResult& r2 = s2_->solve();
        result.work += r2.info.iterations;
        if (has_solution(r2.info.status)) {
          solved2 = true;
          slack_used_ = slack;
          break;
        }
      }
      if (solved2 || !release) break;
      p2_ = detail::convex_loss_phase2(*data_, soft);  // without the release
    }
    const QpResult& r2 = s2_->result();
    if (!solved2) {
      fail(std::string("convex phase 2: ") + to_string(r2.info.status) + ": " + r2.info.message);
      t.solve = detail::since(t0);
      return;
    }
    const bool exact = r1.info.status == QpStatus::solved && r2.info.status == QpStatus::solved;
    result.status = exact ? ContactStatus::solved : ContactStatus::solved_inaccurate;
    if (!exact) result.message = "a phase stalled within 1e3·eps (solved_inaccurate)";
    lambda_.resize(nc + nf);
    lambda_ << r2.x.segment(p2_.lambda_offset, nc), r2.x.segment(p2_.lambda_offset + nc, nf);
    impulse_ = s.Jn.transpose() * lambda_.head(nc) + s.Jt.transpose() * lambda_.tail(nf);
    result.v_next = s.v_star + s.minv.cwiseProduct(impulse_);
    t.solve = detail::since(t0);
  }

  bool solved() const { return has_solution(result.status); }

  /// out = ∂⟨g, v⁺⟩/∂(island data) (overwritten); returns the largest adjoint residual of
  /// the phases' backward passes (0 without a solve).
  double backward(const Vector& g, ContactSystemCotangent& out) {
    out.set_zero(s_);
    out.v_star = g;
    if (trivial_) return 0.0;
    const Index nc = s_.num_contacts(), nf = s_.num_friction();
    // Explicit terms of v⁺ = v* + DJᵀλ, then phase 2, then phase 1 via κ.
    const Vector Dg = s_.minv.cwiseProduct(g);
    detail::ConvexLossPullback pb(*data_);
    pb.add_outer(lambda_, Dg);
    out.minv = g.cwiseProduct(impulse_);
    Vector dl_dx2 = Vector::Zero(p2_.problem.num_variables());
    dl_dx2.segment(p2_.lambda_offset, nc) = s_.Jn * Dg;
    dl_dx2.segment(p2_.lambda_offset + nc, nf) = s_.Jt * Dg;
    const QpGradient g2 = s2_->backward(dl_dx2);
    const double dl_dkappa = pb.add_phase(2, p2_, g2, settings_.rho) * (1.0 + slack_used_);
    Vector dl_dx1 = Vector::Zero(p1_.problem.num_variables());
    for (Index i = 0; i < nc; ++i) dl_dx1(p1_.lambda_offset + i) = lambda1_(i) > 0.0 ? dl_dkappa : 0.0;
    double adjoint = g2.adjoint_residual;
    if ((dl_dx1.array() != 0.0).any()) {  // else κ's bound is inactive and phase 1 contributes nothing
      const QpGradient g1 = s1_->backward(dl_dx1);
      if (data1_own_) {
        detail::ConvexLossPullback pb1(*data1_own_);
        pb1.add_phase(1, p1_, g1, settings_.phase1_regularization);
        pb1.finish(out);
      } else {
        pb.add_phase(1, p1_, g1, settings_.phase1_regularization);
      }
      adjoint = std::max(adjoint, g1.adjoint_residual);
    }
    pb.finish(out);
    return adjoint;
  }

  StepLossResult result;  ///< status, message, v_next, work (loss and grad are the caller's)

 private:
  void fail(const std::string& message) {
    result.status = ContactStatus::failed;
    result.message = message;
    result.loss = std::numeric_limits<double>::quiet_NaN();
  }

  const ContactSystem& s_;
  const ConvexStepLossSettings& settings_;
  bool trivial_ = false;
  std::unique_ptr<detail::ConvexLossData> data_, data1_own_;
  detail::ConvexLossQp p1_, p2_;
  std::unique_ptr<QpSolver> s1_, s2_;
  Vector lambda1_, lambda_, impulse_;
  double slack_used_ = 0.0;
};

void check_call(const ContactSystem& s, const Vector& target, double dt, const ConvexStepLossSettings& settings) {
  const std::string bad = settings.validation_error();
  if (!bad.empty()) throw InputError("ConvexStepLossSettings." + bad);
  check_input(s, target, dt);
  if (s.lcp_block.enabled)
    throw InputError("the convex step loss has no LCP: World::lcp_block (the per-contact LCP correction) is learned "
                     "with the hard loss");
}

void mark_inaccurate_adjoint(ContactStatus& status, std::string& message, double adjoint) {
  if (adjoint <= kAdjointResidualTolerance) return;
  status = ContactStatus::solved_inaccurate;
  message = "adjoint residual " + std::to_string(adjoint) +
              " > 1e-6: degenerate solution, the gradient is that of the final interior iterate";
}

}  // namespace

StepLossResult convex_step_loss(const ContactSystem& s, const Vector& target, double dt,
                                const ConvexStepLossSettings& settings, ConvexStepLossTimes* times) {
  check_call(s, target, dt, settings);
  ConvexStepLossTimes local_times;
  ConvexStepLossTimes& t = times ? *times : local_times;
  t = ConvexStepLossTimes{};
  ConvexStepSolve solve(s, target, dt, settings, t);
  StepLossResult r = std::move(solve.result);
  if (!has_solution(r.status)) return r;
  const auto t0 = detail::Clock::now();
  r.loss = (r.v_next - target).squaredNorm();
  const double adjoint = solve.backward(2.0 * (r.v_next - target), r.grad);
  mark_inaccurate_adjoint(r.status, r.message, adjoint);
  t.backward = detail::since(t0);
  return r;
}

StepJacobianResult convex_step_jacobian(const ContactSystem& s, const Vector& target, double dt,
                                        const ConvexStepLossSettings& settings) {
  check_call(s, target, dt, settings);
  ConvexStepLossTimes t;
  ConvexStepSolve solve(s, target, dt, settings, t);
  StepJacobianResult out;
  StepLossResult& r = solve.result;
  out.status = r.status;
  out.message = r.message;
  out.work = r.work;
  if (!has_solution(r.status)) return out;
  out.v_next = r.v_next;
  const Index nv = s.num_dofs();
  out.rows.resize(static_cast<std::size_t>(nv));
  Vector e = Vector::Zero(nv);
  double adjoint = 0.0;
  for (Index k = 0; k < nv; ++k) {
    e(k) = 1.0;
    adjoint = std::max(adjoint, solve.backward(e, out.rows[static_cast<std::size_t>(k)]));
    e(k) = 0.0;
  }
  mark_inaccurate_adjoint(out.status, out.message, adjoint);
  return out;
}

}  // namespace lcprelax::learn
