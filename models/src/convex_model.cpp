// The convex two-phase contact model (contact_step.hpp), solved by the interior-point QP.
#include <lcprelax/models/convex_phase_qp.hpp>

#include <lcprelax/core/errors.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/convex_solver_cache.hpp>

#include <lcprelax/core/stopwatch.hpp>

#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

namespace lcprelax {
namespace {

// Relative loosening of phase 2's bound eᵀλn ≤ κ, tried in turn until the interior point
// solves phase 2. The bound binds while a body slides (more normal impulse would buy more
// friction), so the loosening is an error of up to that fraction of the friction impulse:
// 1e-6 first (exact to the incline test's 1e-5); resting pyramids (tests/
// dynamics_rest_test.cpp: statically indeterminate, W singular, every normal row active)
// leave the interior point "no progress" at 1e-6 and are solved at 1e-4 or 1e-2.
// The slacks: detail::kKappaSlacks (convex_phase_qp.hpp).

// Sets `qp` up for `p`, or updates it in place when its last problem had p's pattern.
void prepare(QpSolver& qp, const QpProblem& p, ConvexSolverCache& cache) {
  const auto t0 = std::chrono::steady_clock::now();
  if (qp.can_update(p)) {
    qp.update(p);
    ++cache.stats.updates;
  } else {
    qp.setup(p);
    ++cache.stats.setups;
  }
  cache.stats.prepare_seconds += seconds_since(t0);
}

// solve() with its wall time and factorization time added to `cache`.
const QpResult& timed_solve(QpSolver& qp, ConvexSolverCache& cache) {
  const auto t0 = std::chrono::steady_clock::now();
  const QpResult& r = qp.solve();
  cache.stats.solve_seconds += seconds_since(t0);
  cache.stats.factor_seconds += r.info.factor_seconds;
  return r;
}

}  // namespace

ContactSolution solve_convex_model(const ContactSystem& s, double dt, const QpSettings& settings, double rho,
                                   ConvexFormulation formulation, const NormalSofteningSettings& softening) {
  return solve_convex_model(s, dt, settings, rho, formulation, softening, nullptr, false);
}

ContactSolution solve_convex_model(const ContactSystem& s, double dt, const QpSettings& settings, double rho,
                                   ConvexFormulation formulation, const NormalSofteningSettings& softening,
                                   ConvexSolverCache* cache, bool release_open_contacts) {
  if (std::string e = softening.validation_error(); !e.empty()) throw InputError("NormalSofteningSettings." + e);
  if (s.lcp_block.enabled)
    throw InputError("the convex model has no LCP: World::lcp_block (the per-contact LCP correction) applies to the lcp "
                     "model only");
  const Index nc = s.num_contacts(), nf = s.num_friction();
  ContactSolution out;

  // No contact is approaching (b ≥ 0, and b − max(v_ref, 0) ≥ 0): λ = 0 solves both
  // phases exactly (phase 1's optimum is 0, then κ = 0 forces λn = 0 and |λt| ≤ μλn forces
  // λt = 0); an interior point has no interior to work in there, so this case is answered
  // directly.
  const Vector vn = s.Jn * s.v_star;
  const Vector bn = vn + s.phi.cwiseMax(0.0) / dt;
  // The softening's target velocity v_ref (normal_softening.hpp) lowers phase 2's linear
  // term on λn, and max(v_ref, 0) phase 1's; 0 for exp_phi.
  NormalSofteningTerms soft = normal_softening_terms(softening, rho, dt, s.phi, vn);
  if (const std::string e = normal_softness_error(s); !e.empty()) throw InputError("convex model: " + e);
  if (has_normal_softness(s)) add_pair_softness(soft, s.phi, s.compliance, s.erp, dt);  // FrictionTable's c, e
  const NormalSofteningTerms soft1 = phase1_softening_terms(soft);
  if (nc == 0 || (bn.minCoeff() >= 0.0 && (bn - soft1.v_ref).minCoeff() >= 0.0)) {
    out.status = ContactStatus::solved;
    out.lambda_n = Vector::Zero(nc);
    out.lambda_t = Vector::Zero(nf);
    out.v_next = s.v_star;
    return out;
  }
  std::optional<ConvexSolverCache> fresh;
  if (!cache) fresh.emplace(settings);
  ConvexSolverCache& c = cache ? *cache : *fresh;
  auto t0 = std::chrono::steady_clock::now();
  const detail::ConvexModelData data(s, bn, formulation);

  // Phase 1: frictionless normal impulses.
  const detail::ConvexPhaseQp p1 = detail::convex_phase1_qp(data, soft1);
  c.stats.assemble_seconds += seconds_since(t0);
  QpSolver& qp1 = c.phase1;
  prepare(qp1, p1.problem, c);
  const QpResult& r1 = timed_solve(qp1, c);
  out.work = r1.info.iterations;
  if (!has_solution(r1.info.status)) {
    out.status = ContactStatus::failed;
    out.message = std::string("phase 1: ") + to_string(r1.info.status) + ": " + r1.info.message;
    return out;
  }
  const Vector lambda1 = r1.x.segment(p1.lambda_offset, nc).cwiseMax(0.0);
  // κ = eᵀλn of phase 1, loosened (detail::kKappaSlacks, plus 1e-12 N·s): with the normal rows
  // active, eᵀλn ≤ κ exactly makes phase 2's feasible set a point in λn, which leaves the
  // interior point no interior (measured: "no progress" failures on 1-2 contact islands).
  const double kappa = lambda1.sum();

  // Phase 2: friction, bounded by κ, with the normal softening term on λn. Where it has no
  // solution with the release of open contacts, it is solved again without it: a guard. No
  // such case is known with release_open_contacts' gap threshold; with the threshold set to
  // 0, a 30-body pile (seed 1, one projection pass) stalled at its 41st step ("no progress"
  // at every κ slack) after a contact left just touching was released.
  const QpResult* r2 = nullptr;
  QpSolver& qp2 = c.phase2;
  detail::ConvexPhaseQp p2;
  for (const bool release : {release_open_contacts, false}) {
    t0 = std::chrono::steady_clock::now();
    p2 = detail::convex_phase2_qp(data, soft);
    if (release) detail::release_open_contacts(data, lambda1, p2.problem, p2.lambda_offset, dt);
    c.stats.assemble_seconds += seconds_since(t0);
    for (double slack : detail::kKappaSlacks) {
      p2.problem.u(nc) = kappa * (1.0 + slack) + 1e-12;
      if (slack == detail::kKappaSlacks[0])
        prepare(qp2, p2.problem, c);
      else
        qp2.update(p2.problem);  // only the bound changed: the symbolic analysis is kept
      r2 = &timed_solve(qp2, c);
      out.work += r2->info.iterations;
      if (has_solution(r2->info.status)) break;
    }
    if (has_solution(r2->info.status) || !release) break;
    out.open_contacts_held = true;
  }
  out.residual = std::max(r2->info.primal_residual, r2->info.dual_residual);
  if (!has_solution(r2->info.status)) {
    // Not solved; phase 1's frictionless answer is returned with it (contact_step.hpp).
    out.status = ContactStatus::failed;
    out.message = std::string("phase 2: ") + to_string(r2->info.status) + ": " + r2->info.message;
    out.lambda_n = lambda1;
    out.lambda_t = Vector::Zero(nf);
    out.v_next = s.v_star + s.minv.cwiseProduct(s.Jn.transpose() * out.lambda_n);
    return out;
  }
  const bool exact = r1.info.status == QpStatus::solved && r2->info.status == QpStatus::solved;
  out.status = exact ? ContactStatus::solved : ContactStatus::solved_inaccurate;
  if (!exact) out.message = "a phase stalled within 1e3·eps (solved_inaccurate)";
  out.lambda_n = r2->x.segment(p2.lambda_offset, nc).cwiseMax(0.0);
  out.lambda_t = r2->x.segment(p2.lambda_offset + nc, nf);
  const Vector impulse = s.Jn.transpose() * out.lambda_n + s.Jt.transpose() * out.lambda_t;
  out.v_next = s.v_star + s.minv.cwiseProduct(impulse);
  return out;
}

}  // namespace lcprelax
