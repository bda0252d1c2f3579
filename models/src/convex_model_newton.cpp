// The convex two-phase contact model solved by the warm-started active-set Newton method
// (contact_step.hpp: solve_convex_model_newton; active_set_qp.hpp), with the interior point
// (convex_model.cpp) as the fallback.
#include <lcprelax/models/active_set_qp.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/convex_phase_qp.hpp>

#include <lcprelax/core/errors.hpp>

#include <string>
#include <vector>

namespace lcprelax {
namespace {

ContactSolution fallback(const ContactSystem& s, double dt, const QpSettings& settings, double rho,
                         ConvexFormulation formulation, const NormalSofteningSettings& softening,
                         ConvexSolverCache* cache, bool release_open_contacts, long newton_work,
                         const std::string& why) {
  ContactSolution out = solve_convex_model(s, dt, settings, rho, formulation, softening, cache, release_open_contacts);
  out.work += newton_work;
  out.newton_fallback = true;
  if (out.message.empty())
    out.message = "active-set Newton: " + why + "; interior point used";
  else
    out.message = "active-set Newton: " + why + "; interior point: " + out.message;
  return out;
}

}  // namespace

ContactSolution solve_convex_model_newton(const ContactSystem& s, double dt, const QpSettings& settings, double rho,
                                          ConvexFormulation formulation, const NormalSofteningSettings& softening,
                                          ConvexSolverCache* cache, const std::vector<signed char>& warm,
                                          int max_iterations, bool release_open_contacts) {
  if (std::string e = softening.validation_error(); !e.empty()) throw InputError("NormalSofteningSettings." + e);
  if (s.lcp_block.enabled)
    throw InputError("the convex model has no LCP: World::lcp_block (the per-contact LCP correction) applies to the lcp "
                     "model only");
  const Index nc = s.num_contacts(), nf = s.num_friction();
  if (!warm.empty() && static_cast<Index>(warm.size()) != nc + nf)
    throw InputError("solve_convex_model_newton: warm needs nc + nf entries");
  const Vector vn = s.Jn * s.v_star;
  const Vector bn = vn + s.phi.cwiseMax(0.0) / dt;
  NormalSofteningTerms soft = normal_softening_terms(softening, rho, dt, s.phi, vn);
  if (const std::string e = normal_softness_error(s); !e.empty()) throw InputError("convex model: " + e);
  if (has_normal_softness(s)) add_pair_softness(soft, s.phi, s.compliance, s.erp, dt);  // FrictionTable's c, e
  const NormalSofteningTerms soft1 = phase1_softening_terms(soft);
  if (nc == 0 || (bn.minCoeff() >= 0.0 && (bn - soft1.v_ref).minCoeff() >= 0.0))
    return solve_convex_model(s, dt, settings, rho, formulation, softening, cache,
                              release_open_contacts);  // λ = 0, no solve

  detail::ActiveSetSettings as;
  as.eps_abs = settings.eps_abs;
  as.max_iterations = max_iterations > 0 ? max_iterations : kConvexNewtonMaxIterations;
  const detail::ConvexModelData data(s, bn, formulation);

  // Phase 1: λn ≥ 0 bounds; a contact starts active (bound free) where its λn was
  // positive last step, or, unknown, where it approaches (bn < 0).
  const detail::ConvexPhaseQp p1 = detail::convex_phase1_qp(data, soft1);
  const Index o1 = p1.lambda_offset;
  std::vector<detail::ActiveState> b1(static_cast<std::size_t>(p1.problem.num_variables()), 0);
  for (Index c = 0; c < nc; ++c) {
    const bool active = warm.empty() || warm[c] < 0 ? bn(c) < 0.0 : warm[c] > 0;
    b1[o1 + c] = active ? 0 : -1;
  }
  const Vector zero1 = Vector::Zero(p1.problem.num_variables());  // λn = 0 (and w = 0): feasible
  const detail::ActiveSetResult r1 = detail::solve_active_set_qp(
      p1.problem, std::vector<detail::ActiveState>(p1.problem.num_inequalities(), 0), b1, as, &zero1);
  long work = r1.iterations;
  if (!r1.converged) return fallback(s, dt, settings, rho, formulation, softening, cache, release_open_contacts, work, "phase 1: " + r1.message);
  const Vector lambda1 = r1.x.segment(o1, nc).cwiseMax(0.0);
  const double kappa = lambda1.sum();

  // Phase 2: contact rows active and λn free where phase 1 ended active; friction rows from
  // the previous step (stick unless it slid); an inactive contact pins λt = μλn = 0.
  detail::ConvexPhaseQp p2 = detail::convex_phase2_qp(data, soft);
  // The interior point's first loosening, so that both methods solve the same QP.
  p2.problem.u(nc) = kappa * (1.0 + detail::kKappaSlacks[0]) + 1e-12;
  if (release_open_contacts) detail::release_open_contacts(data, lambda1, p2.problem, p2.lambda_offset, dt);
  const Index o2 = p2.lambda_offset;
  std::vector<detail::ActiveState> rows2(static_cast<std::size_t>(p2.problem.num_inequalities()), 0);
  std::vector<detail::ActiveState> b2(static_cast<std::size_t>(p2.problem.num_variables()), 0);
  std::vector<bool> contact_active(static_cast<std::size_t>(nc));
  for (Index c = 0; c < nc; ++c) {
    contact_active[c] = r1.bounds[o1 + c] == 0;
    rows2[c] = contact_active[c] ? -1 : 0;
    b2[o2 + c] = contact_active[c] ? 0 : -1;
  }
  for (Index f = 0; f < nf; ++f) {
    const signed char w = warm.empty() ? 0 : warm[nc + f];
    if (!contact_active[s.friction_rows[f]] || w > 0)
      rows2[nc + 1 + 2 * f] = 1;  // λt − μλn ≤ 0 at its bound
    else if (w < 0)
      rows2[nc + 2 + 2 * f] = -1;  // λt + μλn ≥ 0 at its bound
  }
  // Phase 1's answer with λt = 0 is feasible for phase 2 (contact_step.hpp).
  Vector start2 = Vector::Zero(p2.problem.num_variables());
  start2.segment(o2, nc) = lambda1;
  if (data.lifted()) start2.head(s.num_dofs()) = s.minv.cwiseProduct(s.Jn.transpose() * lambda1);
  const detail::ActiveSetResult r2 = detail::solve_active_set_qp(p2.problem, rows2, b2, as, &start2);
  work += r2.iterations;
  if (!r2.converged) return fallback(s, dt, settings, rho, formulation, softening, cache, release_open_contacts, work, "phase 2: " + r2.message);

  ContactSolution out;
  out.status = ContactStatus::solved;
  out.work = work;
  out.residual = std::max(r2.primal_residual, r2.dual_residual);
  out.lambda_n = r2.x.segment(o2, nc).cwiseMax(0.0);
  out.lambda_t = r2.x.segment(o2 + nc, nf);
  const Vector impulse = s.Jn.transpose() * out.lambda_n + s.Jt.transpose() * out.lambda_t;
  out.v_next = s.v_star + s.minv.cwiseProduct(impulse);
  out.z_basic.assign(static_cast<std::size_t>(nc + 3 * nf), false);
  for (Index c = 0; c < nc; ++c) out.z_basic[c] = out.lambda_n(c) > 0.0;
  for (Index f = 0; f < nf; ++f) {
    out.z_basic[nc + f] = r2.rows[nc + 1 + 2 * f] != 0 && out.lambda_n(s.friction_rows[f]) > 0.0;
    out.z_basic[nc + nf + f] = r2.rows[nc + 2 + 2 * f] != 0;
  }
  return out;
}

}  // namespace lcprelax
