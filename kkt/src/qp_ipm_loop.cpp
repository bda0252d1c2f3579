// The Mehrotra predictor-corrector iteration of QpSolver (see qp_solver.hpp).
#include "qp_solver_impl.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace lcprelax {
namespace {

using detail::merit_of;
using detail::within;

constexpr double kInaccurateFactor = 1e3;  // stalled solves within 1e3·eps: solved_inaccurate
constexpr int kFirstInfeasibilityCheck = 3;
constexpr int kStallIterations = 15;  // no 10% gain in the worst scaled residual: stalled
constexpr int kSteadyIterations = 5;  // ... unless the residuals still gain 10% within 5 iterations
constexpr double kDivergence = 1e13;  // scaled iterate norm taken as divergence
constexpr int kDualStalls = 2;  // full steps (α > 0.9) in a row that leave ≥ half the scaled r_d
constexpr double kRefinementFailure = 1e-8;  // relative K0 residual after refinement taken as failure
constexpr double kConservativeSigma = 0.1;   // least centring of the conservative second attempt

void fill_residuals(QpInfo& info, const detail::Residuals& r) {
  info.primal_residual = r.primal;
  info.dual_residual = r.dual;
  info.duality_gap = r.gap;
}

}  // namespace

void QpSolver::Impl::run(QpInfo& info) {
  const detail::StandardForm& f = form;
  rho = settings.reg_primal;
  delta = settings.reg_dual;
  delta_rows = delta;
  may_drop_row_regularization = true;
  primal_reg_dropped = false;
  int dual_stalls = 0;
  double last_alpha = 0.0, last_rd_norm = 0.0;
  const bool no_time = !has_warm_start && out_of_time(predicted_factor_seconds());
  if (no_time || !initial_point(info)) {
    info.status = no_time ? QpStatus::time_limit : QpStatus::numerical_error;
    if (no_time) info.message = "time limit: no time for the first KKT factorization";
    result.x.resize(0);  // no iterate: an empty solution
    result.y.resize(0);
    result.z.resize(0);
    result.z_bounds.resize(0);
    return;
  }
  detail::Workspace& w = work;
  Vector &rd = w.rd, &rp = w.rp, &dx = w.dx, &dy = w.dy, &zg = w.zg, &zb = w.zb;
  Vector &last_dx = w.last_dx, &last_dy = w.last_dy;
  bool have_step = false;
  int tiny_steps = 0;
  double best_merit = std::numeric_limits<double>::infinity();
  int best_iteration = 0;
  double best_residual_merit = std::numeric_limits<double>::infinity();
  int best_residual_iteration = 0;
  detail::Residuals res;
  for (info.iterations = 0;; ++info.iterations) {
    // Residuals of the current iterate (scaled) and termination tests (unscaled).
    it.compute_side_residuals(f);
    it.signed_multipliers(f.mg, f.n, zg, zb);
    rd.noalias() = f.P.selfadjointView<Eigen::Upper>() * it.x;
    rd += f.q;
    rd += zb;
    if (f.me) rd.noalias() += f.Et * it.y;
    if (f.mg) rd.noalias() += f.Gt * zg;
    rp.noalias() = f.E * it.x;
    rp -= f.be;
    {
      // A full step removes the scaled dual residual (r_d ← (1 − α)r_d up to the step's K0
      // residual); where it stays while α ≈ 1, the primal regularization ρ limits the step
      // (QpSettings::primal_reg_drop).
      const double rd_norm = rd.size() ? rd.lpNorm<Eigen::Infinity>() : 0.0;
      dual_stalls = (have_step && last_alpha > 0.9 && rd_norm > 0.5 * last_rd_norm) ? dual_stalls + 1 : 0;
      last_rd_norm = rd_norm;
    }
    detail::unscale_solution(f, problem, it, result, w);
    res = detail::compute_residuals(problem, result, w);
    if (settings.clean_bound_multipliers && have_step && !has_warm_start && !within(res, settings, 1.0)) {
      // Exact multipliers of the variables at a bound (qp_bound_multipliers.cpp), kept
      // only if the recomputed residuals improve. Not before the first step and not in
      // warm-started solves: a warm start at the exact solution has x at its bound but
      // slacks clamped to 1e-2, and ending early there gives backward() the barrier terms
      // z/s of those slacks (tests/qp_backward_warm_start_test.cpp: ∂x/∂u 0.994 instead
      // of 1). Known limitation: backward() differentiates the interior iterate, which the
      // cleanup may certify before its slacks are small.
      w.zb_saved = result.z_bounds;
      if (detail::clean_bound_multipliers(problem, settings.eps_abs, result, w) > 0) {
        const detail::Residuals cleaned = detail::compute_residuals(problem, result, w);
        if (merit_of(cleaned, settings) < merit_of(res, settings))
          res = cleaned;
        else
          result.z_bounds = w.zb_saved;
      }
    }
    fill_residuals(info, res);
    const double mu = it.mu();
    if (settings.verbose)
      std::fprintf(stderr, "ipm %3d  pres %.2e  dres %.2e  gap %.2e  (scales %.1e %.1e %.1e)  mu %.2e  reg %.0e  scaled rd %.2e rp %.2e\n",
                   info.iterations, res.primal, res.dual, res.gap, res.scale_p, res.scale_d, res.scale_g, mu, rho, rd.size() ? rd.lpNorm<Eigen::Infinity>() : 0.0,
                   rp.size() ? rp.lpNorm<Eigen::Infinity>() : 0.0);
    if (within(res, settings, 1.0)) {
      info.status = QpStatus::solved;
      return;
    }
    if (have_step && info.iterations >= kFirstInfeasibilityCheck) {
      // The certificate functions write into result only when they return true.
      if (detail::primal_infeasibility_certificate(f, problem, it.y, it, false, settings.eps_infeasible, result, w) ||
          detail::primal_infeasibility_certificate(f, problem, last_dy, it, true, settings.eps_infeasible, result,
                                                   w)) {
        info.status = QpStatus::primal_infeasible;
        return;
      }
      if (detail::dual_infeasibility_certificate(f, last_dx, settings.eps_infeasible, result, w) ||
          detail::dual_infeasibility_certificate(f, it.x, settings.eps_infeasible, result, w)) {
        info.status = QpStatus::dual_infeasible;
        return;
      }
    }
    // A stalled run within 1e3·eps is solved_inaccurate; a limit is always its own status.
    auto give_up = [&](QpStatus status, const char* why) {
      info.status = within(res, settings, kInaccurateFactor) ? QpStatus::solved_inaccurate : status;
      if (info.message.empty()) info.message = why;
    };
    auto stop_at_limit = [&](QpStatus status, const char* why) {
      info.status = status;
      if (info.message.empty()) info.message = why;
    };
    if (info.iterations >= settings.max_iter) return stop_at_limit(QpStatus::max_iterations, "iteration limit reached");
    // The next step starts with a factorization that cannot be interrupted: stop before it if
    // it would end past the limit (its predicted time: Impl::predicted_factor_seconds).
    if (out_of_time(0.0)) return stop_at_limit(QpStatus::time_limit, "time limit reached");
    if (out_of_time(predicted_factor_seconds()))
      return stop_at_limit(QpStatus::time_limit, "time limit: the next KKT factorization would end past it");
    const double merit = std::max({res.primal / (settings.eps_abs + settings.eps_rel * res.scale_p),
                                   res.dual / (settings.eps_abs + settings.eps_rel * res.scale_d),
                                   res.gap / (settings.eps_abs + settings.eps_rel * res.scale_g)});
    if (merit < 0.9 * best_merit) {
      best_merit = merit;
      best_iteration = info.iterations;
    }
    const double residual_merit = std::max({res.primal / (settings.eps_abs + settings.eps_rel * res.scale_p),
                                            res.dual / (settings.eps_abs + settings.eps_rel * res.scale_d), 1.0});
    if (residual_merit < 0.9 * best_residual_merit) {
      best_residual_merit = residual_merit;
      best_residual_iteration = info.iterations;
    }
    // Stalled only if the worst of the three measures has not improved for 15 iterations AND
    // the worst residual above tolerance has not improved for 5. On LISWET1 (second differences
    // of x ≥ 0, all 10,000 rows active, optimal multipliers up to 3e5 against O(1) at the start)
    // the iterates follow the infeasible central path, whose multipliers only grow to their
    // optimal size as the primal residual shrinks: for ~60 iterations the gap grows (from 2e-3
    // to 4) while both residuals fall ~7% per iteration, then all three converge in 6 steps.
    // Residuals already within tolerance (floor 1) do not count, so roundoff jitter below the
    // tolerance cannot keep a stalled solve alive.
    if (info.iterations - best_iteration >= kStallIterations &&
        info.iterations - best_residual_iteration >= kSteadyIterations)
      return give_up(QpStatus::numerical_error, "no progress in the residuals for 15 iterations");
    if (tiny_steps >= 5) return give_up(QpStatus::numerical_error, "no progress: step lengths below 1e-10");
    double iterate_norm = std::max(it.x.size() ? it.x.lpNorm<Eigen::Infinity>() : 0.0,
                                   it.y.size() ? it.y.lpNorm<Eigen::Infinity>() : 0.0);
    for (const detail::Side* s : it.sides())
      if (s->size()) iterate_norm = std::max(iterate_norm, s->z.lpNorm<Eigen::Infinity>());
    if (!(iterate_norm < kDivergence)) return give_up(QpStatus::numerical_error, "iterates diverge");

    // Factorize the Newton system at this iterate.
    it.barrier_terms(f.mg, f.n, Dg, Db);
    if (!factorize(info)) return give_up(QpStatus::numerical_error, "factorization failed");

    // Predictor (affine scaling) direction.
    for (detail::Side* s : it.sides()) s->rc = s->s.cwiseProduct(s->z);
    info.refinement_steps += newton_step();
    if (f.mg > 0 && delta_rows > 0 && may_drop_row_regularization &&
        kkt.last_relative_residual() > (conservative ? settings.conservative_row_reg_drop : kRefinementFailure)) {
      // The refinement against K0 stalled (above 1e-8; in the conservative second run above
      // QpSettings::conservative_row_reg_drop, 1e-9: LISWET2's refinement sits at 1.0…1.4e-9
      // while its rows' primal residual stalls). The factorized inequality block is −(1/Dg + δ), so
      // on row i refinement contracts by about δ·Dg_i/(1 + δ·Dg_i): it fails once the active
      // rows' s_i/z_i = 1/Dg_i fall below δ and the regularized solution is far from K0's
      // (on LISWET1 the smooth modes of GGᵀ have eigenvalues ~1e-15 ≪ δ). The block −1/Dg is
      // negative definite by itself, so the matrix stays quasi-definite, hence strongly
      // factorizable, without δ there (Vanderbei 1995, "Symmetric quasidefinite matrices",
      // SIAM J. Optim. 5(1)): drop it for the rest of this solve and redo the predictor. On
      // LISWET1 the refinement stalls from iteration 31 at a relative residual 1e-6 (1e-14
      // in the earlier iterations) and the primal residual then cannot go below 1e-7. If the factorization without
      // δ fails, factorize() restores it and the drop is not retried.
      delta_rows = 0.0;
      if (!factorize(info)) return give_up(QpStatus::numerical_error, "factorization failed");
      for (detail::Side* s : it.sides()) s->rc = s->s.cwiseProduct(s->z);
      info.refinement_steps += newton_step();
    }
    if (settings.primal_reg_drop > 0 && !primal_reg_dropped && rho > settings.primal_reg_drop &&
        dual_stalls >= kDualStalls && res.dual > settings.eps_abs + settings.eps_rel * res.scale_d) {
      // The dual residual survived kDualStalls full steps while still above its tolerance:
      // lower ρ once per run (a failed factorization raises it again in factorize()) and
      // redo the predictor. Not once the dual residual is within tolerance: there it only
      // jitters at its roundoff floor, and a lower ρ then lets dual-degenerate LPs' large
      // multipliers drift, which moves the gap's floor above 1e-9 (generated LPs of
      // tests/qp_primal_reg_drop_guard_test.cpp: 3 of 288 lost without this condition).
      primal_reg_dropped = true;
      rho = settings.primal_reg_drop;
      if (!factorize(info)) return give_up(QpStatus::numerical_error, "factorization failed");
      for (detail::Side* s : it.sides()) s->rc = s->s.cwiseProduct(s->z);
      info.refinement_steps += newton_step();
    }
    const double a_aff = it.max_step();
    double mu_aff = 0.0;
    for (const detail::Side* s : it.sides())
      mu_aff += (s->s + a_aff * s->ds).dot(s->z + a_aff * s->dz);
    const Index N = it.num_constraints();
    double sigma = N > 0 && mu > 0 ? std::pow(std::clamp(mu_aff / N / mu, 0.0, 1.0), 3) : 0.0;
    if (conservative) sigma = std::max(sigma, kConservativeSigma);

    // Corrector: s∘z + ds_aff∘dz_aff − σμ (conservative: s∘z − σμ, a plain centred step).
    for (detail::Side* s : it.sides()) {
      if (conservative)
        s->rc = s->s.cwiseProduct(s->z).array() - sigma * mu;
      else
        s->rc = (s->s.cwiseProduct(s->z) + s->ds.cwiseProduct(s->dz)).array() - sigma * mu;
    }
    info.refinement_steps += newton_step();
    double amax = it.max_step();
    if (conservative && settings.centrality_correctors > 0 && amax < 1.0 && N > 0)
      amax = centrality_correctors(amax, sigma * mu, info);
    const double alpha = std::min(1.0, settings.step_fraction * amax);
    tiny_steps = alpha < 1e-10 ? tiny_steps + 1 : 0;
    if (settings.verbose) std::fprintf(stderr, "     alpha %.3e  sigma %.2e  a_aff %.3e\n", alpha, sigma, a_aff);

    last_alpha = alpha;
    it.x += alpha * dx;
    if (f.me) it.y += alpha * dy;
    for (detail::Side* s : it.sides()) {
      s->s += alpha * s->ds;
      s->z += alpha * s->dz;
    }
    last_dx = dx;
    last_dy = dy;
    have_step = true;
  }
}

// Multiple centrality correctors: Gondzio, "Multiple centrality corrections in a primal-dual
// method for linear programming", Comput. Optim. Appl. 6, 1996; the acceptance test and the
// bound on negative corrections of Colombo & Gondzio, "Further development of multiple
// centrality correctors for interior point methods", Comput. Optim. Appl. 41, 2008.
// At the aspired length α̃ = min(1, α + kGondzioAspiration) of the current step, the
// complementarity products v = (s + α̃ds)∘(z + α̃dz) outside [β_min σμ, β_max σμ] are
// pulled back into it: the correction c (c = β_min σμ − v below, max(β_max σμ − v,
// −β_max σμ) above, 0 inside) is added to the step's complementarity equation
// (s∘dz + z∘ds = −r_c + c) and the system is solved again with the same factorization.
// The corrected step is kept if its largest feasible length is at least
// α + kGondzioAcceptance·(α̃ − α); otherwise the previous one is restored and the
// correctors stop. Used in the conservative second run only (QpSettings::centrality_correctors
// says what was measured): on QSIERRA, Mehrotra's steps shrink below 1e-3 in the last
// iterations and the dual residual rises from 1e-6 to 1e0; with the correctors the second
// run solves it.
namespace {
constexpr double kGondzioAspiration = 0.2;
constexpr double kGondzioAcceptance = 0.1;
constexpr double kGondzioBetaMin = 0.1;
constexpr double kGondzioBetaMax = 10.0;
}  // namespace

double QpSolver::Impl::centrality_correctors(double amax, double mu_target, QpInfo& info) {
  detail::Workspace& w = work;
  // Exchanges the step (dx, dy, dz, the sides' ds, dz, rc) with the saved one (O(1) swaps:
  // newton_step overwrites every step vector, so the kept step need not be copied).
  const auto swap_step = [&] {
    w.dx.swap(w.saved_dx);
    w.dy.swap(w.saved_dy);
    w.dz.swap(w.saved_dz);
    for (detail::Side* s : it.sides()) {
      s->ds.swap(s->ds_saved);
      s->dz.swap(s->dz_saved);
      s->rc.swap(s->rc_saved);
    }
  };
  const double lo = kGondzioBetaMin * mu_target, hi = kGondzioBetaMax * mu_target;
  for (int k = 0; k < settings.centrality_correctors && amax < 1.0; ++k) {
    const double aspired = std::min(1.0, amax + kGondzioAspiration);
    swap_step();  // the current step becomes the saved one
    for (detail::Side* s : it.sides()) {
      s->rc = s->rc_saved;
      for (Index i = 0; i < s->size(); ++i) {
        const double v = (s->s(i) + aspired * s->ds_saved(i)) * (s->z(i) + aspired * s->dz_saved(i));
        double c = 0.0;
        if (v < lo)
          c = lo - v;
        else if (v > hi)
          c = std::max(hi - v, -hi);
        s->rc(i) -= c;
      }
    }
    info.refinement_steps += newton_step();
    const double corrected = it.max_step();
    if (corrected < amax + kGondzioAcceptance * (aspired - amax)) {
      swap_step();  // back to the saved step
      break;
    }
    amax = corrected;
    ++info.centrality_correctors;
  }
  return amax;
}

}  // namespace lcprelax
