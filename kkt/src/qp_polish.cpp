// Solution polishing on the guessed active set (method in qp_polish.hpp) and
// QpSolver::Impl::polish, which accepts or rejects the polished point.
#include "qp_polish.hpp"
#include "qp_polish_reduced.hpp"
#include "vector_norms.hpp"

#include <cstdio>

#include <lcprelax/sparse/cholmod_ldlt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace lcprelax {
namespace detail {
namespace {

void mark_side(const Side& side, std::vector<signed char>& out, Vector& zbest) {
  for (Index k = 0; k < side.size(); ++k) {
    const Index q = side.idx[k];
    if (side.s(k) < side.z(k) && side.z(k) > zbest(q)) {
      out[q] = side.upper ? 1 : -1;
      zbest(q) = side.z(k);
    }
  }
}

ActiveSet guess_active_set(const StandardForm& f, const Iterate& it) {
  ActiveSet a;
  a.rows.assign(f.mg, 0);
  a.bounds.assign(f.n, 0);
  Vector zr = Vector::Zero(f.mg), zb = Vector::Zero(f.n);
  mark_side(it.g_lower, a.rows, zr);
  mark_side(it.g_upper, a.rows, zr);
  mark_side(it.b_lower, a.bounds, zb);
  mark_side(it.b_upper, a.bounds, zb);
  return a;
}

// The scaled point of an unscaled candidate (inverse of step 3's map): x̃ = x/Dx,
// ỹ = c·y/Ee (c·z/Ee for a G row, c·z_b/Ee for a fixed variable), ζ = c·z/Eg.
ScaledPoint scaled_point(const StandardForm& f, const QpResult& r) {
  ScaledPoint sp;
  sp.x = r.x.cwiseQuotient(f.Dx);
  sp.y.resize(f.me);
  for (Index k = 0; k < f.me; ++k) {
    const Index i = f.eq_index[k];
    const double w = f.eq_source[k] == EqSource::a_row ? r.y(i) : f.eq_source[k] == EqSource::g_row ? r.z(i) : r.z_bounds(i);
    sp.y(k) = f.c * w / f.Ee(k);
  }
  sp.zg.resize(f.mg);
  for (Index k = 0; k < f.mg; ++k) sp.zg(k) = f.c * r.z(f.g_index[k]) / f.Eg(k);
  return sp;
}

// Step 3 and 4 of qp_polish.hpp: the unscaled candidate of `sp`, with wrong signs up to
// thr_d set to 0; `next` receives the corrected active set. Returns the largest wrong-sign
// magnitude of a multiplier.
double build_candidate(const StandardForm& f, const QpProblem& p, const ActiveSet& a, const ScaledPoint& sp,
                       double thr_p, double thr_d, bool shrink_forcing_rows, QpResult& cand, ActiveSet& next,
                       Workspace& w) {
  const Index n = f.n;
  cand.x = f.Dx.cwiseProduct(sp.x);
  for (Index j = 0; j < n; ++j) {
    if (a.bounds[j] != 0) cand.x(j) = a.bounds[j] < 0 ? p.xl(j) : p.xu(j);
    if (f.fixed_eq_row[j] >= 0) cand.x(j) = p.xl(j);
  }
  cand.y.setZero(p.num_equalities());
  cand.z.setZero(p.num_inequalities());
  cand.z_bounds.setZero(n);
  for (Index k = 0; k < f.me; ++k) {
    const double v = f.Ee(k) * sp.y(k) / f.c;
    if (f.eq_source[k] == EqSource::a_row) cand.y(f.eq_index[k]) = v;
    if (f.eq_source[k] == EqSource::g_row) cand.z(f.eq_index[k]) = v;
  }
  double wrong = 0.0;
  // Rows: multiplier signs at active sides, violations at inactive ones.
  w.Gx.noalias() = p.G * cand.x;
  for (Index k = 0; k < f.mg; ++k) {
    const Index i = f.g_index[k];
    if (a.rows[k] != 0) {
      const double zi = f.Eg(k) * sp.zg(k) / f.c;
      const double bad = a.rows[k] < 0 ? zi : -zi;  // > 0: wrong sign
      cand.z(i) = bad > 0 ? 0.0 : zi;
      wrong = std::max(wrong, bad);
      if (bad > thr_d) next.rows[k] = 0;
    } else if (w.Gx(i) < p.l(i) - thr_p) {
      next.rows[k] = -1;
    } else if (w.Gx(i) > p.u(i) + thr_p) {
      next.rows[k] = 1;
    }
  }
  // Bound multipliers of fixed and bound-active variables from stationarity.
  w.Px.noalias() = p.P.selfadjointView<Eigen::Upper>() * cand.x;
  w.Aty.noalias() = p.A.transpose() * cand.y;
  w.Gtz.noalias() = p.G.transpose() * cand.z;
  Vector targets = -(w.Px + p.q + w.Aty + w.Gtz);
  // A wrong sign below the evaluation floor of its stationarity row (kSignFloorUlps·u·Σ|terms|,
  // with the multipliers before the forcing-row step, whose shifts were decided at that
  // accuracy) is undetermined: set to 0 like one below thr_d. Such signs arise where a
  // forcing row's multiplier moved to the edge of its interval (that z_b is 0 exactly).
  Vector floor_d;
  if (shrink_forcing_rows) {
    floor_d = p.q.cwiseAbs();
    floor_d.noalias() += p.P.cwiseAbs().selfadjointView<Eigen::Upper>() * cand.x.cwiseAbs();
    if (p.A.rows()) floor_d.noalias() += p.A.cwiseAbs().transpose() * cand.y.cwiseAbs();
    if (p.G.rows()) floor_d.noalias() += p.G.cwiseAbs().transpose() * cand.z.cwiseAbs();
    floor_d *= kSignFloorUlps * std::numeric_limits<double>::epsilon();
  }
  if (shrink_forcing_rows && shrink_forcing_row_multipliers(f, p, a.rows, a.bounds, cand, targets) > 0) {
    // Recomputed from the shifted multipliers: t − a·Δ carries the roundoff of the large ω.
    w.Aty.noalias() = p.A.transpose() * cand.y;
    w.Gtz.noalias() = p.G.transpose() * cand.z;
    targets = -(w.Px + p.q + w.Aty + w.Gtz);
  }
  for (Index j = 0; j < n; ++j) {
    const double target = targets(j);
    if (f.fixed_eq_row[j] >= 0) {
      cand.z_bounds(j) = target;
    } else if (a.bounds[j] != 0) {
      const double bad = a.bounds[j] < 0 ? target : -target;
      cand.z_bounds(j) = bad > 0 ? 0.0 : target;
      if (shrink_forcing_rows && bad <= floor_d(j)) continue;
      wrong = std::max(wrong, bad);
      if (bad > thr_d) next.bounds[j] = 0;
    } else if (cand.x(j) < p.xl(j) - thr_p) {
      next.bounds[j] = -1;
    } else if (cand.x(j) > p.xu(j) + thr_p) {
      next.bounds[j] = 1;
    }
  }
  return wrong;
}

// Step 3c of qp_polish.hpp on `best` (a candidate of active set a, signs kept): least-norm
// multipliers, then the reduced system once more from that point. Its refinement's floor is
// the roundoff of the iterate, which the interior point's large multipliers had set; sides
// whose least-norm multiplier is 0 leave the active set there (the refinement would move
// them along the multipliers' null space to either sign). Up to kLeastNormPasses passes
// while the merit falls. False when the first least-norm solve fails (best untouched).
bool least_norm_candidate(const StandardForm& f, const QpProblem& p, const ActiveSet& a, double thr_p, double thr_d,
                          const QpSettings& s, QpResult& best, Workspace& w) {
  double best_merit = std::numeric_limits<double>::infinity();
  bool any = false;
  for (int pass = 0; pass < kLeastNormPasses; ++pass) {
    QpResult trial = best;
    if (!least_norm_multipliers(f, p, a.rows, a.bounds, thr_d, trial)) break;
    ActiveSet a0 = a;
    for (Index k = 0; k < f.mg; ++k)
      if (a0.rows[k] != 0 && trial.z(f.g_index[k]) == 0.0) a0.rows[k] = 0;
    for (Index j = 0; j < f.n; ++j)
      if (a0.bounds[j] != 0 && trial.z_bounds(j) == 0.0) a0.bounds[j] = 0;
    double m = merit_of(compute_residuals(p, trial, w), s);
    ScaledPoint again;
    ActiveSet scratch = a0;
    QpResult resolved;
    if (solve_reduced(f, scaled_point(f, trial), a0, again) &&
        build_candidate(f, p, a0, again, thr_p, thr_d, false, resolved, scratch, w) <= thr_d) {
      const double m1 = merit_of(compute_residuals(p, resolved, w), s);
      if (m1 < m) {
        m = m1;
        trial = std::move(resolved);
      }
    }
    if (any && !(m < best_merit)) break;
    best = std::move(trial);
    best_merit = m;
    any = true;
    if (m <= 1.0) break;
  }
  return any;
}

}  // namespace

PolishOutcome polish_solution(const StandardForm& f, const QpProblem& p, const Iterate& it, const QpSettings& s,
                              const Residuals& before, QpResult& candidate, Workspace& w) {
  PolishOutcome out;
  const double thr_p = kPolishSignFraction * (s.eps_abs + s.eps_rel * before.scale_p);
  const double thr_d = kPolishSignFraction * (s.eps_abs + s.eps_rel * before.scale_d);
  ActiveSet a = guess_active_set(f, it);
  ScaledPoint start;
  start.x = it.x;
  start.y = it.y;
  Vector zb_it;
  it.signed_multipliers(f.mg, f.n, start.zg, zb_it);
  QpResult cand;
  ScaledPoint sp;
  double best_merit = std::numeric_limits<double>::infinity();
  for (int round = 0; round < kPolishRounds; ++round) {
    if (!solve_reduced(f, start, a, sp)) break;
    ++out.rounds;
    ActiveSet next = a;
    // The candidate as it is, and (QpSettings::polish_forcing_rows) the same point with the
    // forcing rows' multipliers shrunk; the better of them counts. The active set's
    // corrections come from the first, so the rounds are those without the step.
    // (QpSettings::polish_least_norm) A third: the best of those with least-norm multipliers.
    bool solved = false;
    double round_merit = std::numeric_limits<double>::infinity();
    QpResult round_best;
    // Keeps c as the polish's answer when it is the best so far; whether it is solved.
    const auto offer = [&](const QpResult& c, const Residuals& r, double m) {
      if (m < best_merit) {
        best_merit = m;
        out.found = true;
        out.residuals = r;
        candidate.x = c.x;
        candidate.y = c.y;
        candidate.z = c.z;
        candidate.z_bounds = c.z_bounds;
      }
      return within(r, s, 1.0);
    };
    for (int variant = 0; variant < (s.polish_forcing_rows ? 2 : 1) && !solved; ++variant) {
      ActiveSet scratch = a;
      const double wrong = build_candidate(f, p, a, sp, thr_p, thr_d, variant == 1, cand, variant == 0 ? next : scratch, w);
      if (wrong > thr_d) continue;
      const Residuals r = compute_residuals(p, cand, w);
      const double m = merit_of(r, s);
      if (m < round_merit) {
        round_merit = m;
        round_best = cand;
      }
      solved = offer(cand, r, m);
    }
    if (!solved && s.polish_least_norm && std::isfinite(round_merit) &&
        least_norm_candidate(f, p, a, thr_p, thr_d, s, round_best, w)) {
      const Residuals r = compute_residuals(p, round_best, w);
      const double m = merit_of(r, s);
      if (s.verbose)
        std::fprintf(stderr, "polish: least-norm multipliers  dres %.2e gap %.2e (merit %.3g -> %.3g)\n", r.dual, r.gap,
                     round_merit, m);
      solved = offer(round_best, r, m);
    }
    if (solved) break;
    if (next == a) break;
    a = std::move(next);
  }
  return out;
}

}  // namespace detail

void QpSolver::Impl::polish(QpInfo& info) {
  const QpStatus before_status = info.status;
  if (!settings.polish) return;
  if (before_status != QpStatus::solved_inaccurate && before_status != QpStatus::numerical_error &&
      before_status != QpStatus::max_iterations)
    return;
  if (result.x.size() != problem.num_variables() || it.x.size() != form.n) return;
  const auto t0 = std::chrono::steady_clock::now();
  const detail::Residuals before = detail::compute_residuals(problem, result, work);
  QpResult candidate;
  const detail::PolishOutcome o = detail::polish_solution(form, problem, it, settings, before, candidate, work);
  info.polish_attempted = true;
  info.polish_rounds += o.rounds;
  // Accepted if the worst ratio to the tolerance improves and the point is solved; or, when
  // the interior point's was already solved_inaccurate, if besides no residual gets worse by
  // more than 1e-2 of its tolerance (QSCAGR7 with MUMPS: dual 1.46e-11 → 1.73e-11 while the
  // gap fell from 2.7e-8 to 4.9e-10). A limit or a failure becomes solved, never inaccurate.
  const detail::Residuals& r = o.residuals;
  const QpSettings& s = settings;
  const bool solved = o.found && detail::within(r, s, 1.0);
  // A solved point may move a residual within its tolerance (the forcing-row step trades a
  // dual residual of 8e-15 for 1.7e-10 of roundoff to bring QBORE3D's gap from 2.6e-9 to 9e-11).
  const bool no_worse =
      r.primal <= before.primal + detail::kPolishSignFraction * (s.eps_abs + s.eps_rel * r.scale_p) &&
      r.dual <= before.dual + detail::kPolishSignFraction * (s.eps_abs + s.eps_rel * r.scale_d) &&
      r.gap <= before.gap + detail::kPolishSignFraction * (s.eps_abs + s.eps_rel * r.scale_g);
  const bool accept = o.found && detail::merit_of(r, s) < detail::merit_of(before, s) &&
                      (solved || (no_worse && before_status == QpStatus::solved_inaccurate));
  if (settings.verbose)
    std::fprintf(stderr, "polish: rounds %d found %d  pres %.2e dres %.2e gap %.2e (before %.2e %.2e %.2e) accept %d\n",
                 o.rounds, int(o.found), r.primal, r.dual, r.gap, before.primal, before.dual, before.gap, int(accept));
  if (accept) {
    result.x = candidate.x;
    result.y = candidate.y;
    result.z = candidate.z;
    result.z_bounds = candidate.z_bounds;
    info.polish_accepted = true;
    const bool factorized = adopt_polished_point(info);
    info.primal_residual = r.primal;
    info.dual_residual = r.dual;
    info.duality_gap = r.gap;
    info.status = solved ? QpStatus::solved : QpStatus::solved_inaccurate;
    info.message = std::string(to_string(info.status)) + " by polishing on the active set (interior point: " +
                   to_string(before_status) + (info.message.empty() ? "" : ", " + info.message) + ")";
    if (!factorized) info.message += "; the KKT factorization at the polished point failed (backward() inexact)";
  }
  info.polish_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool QpSolver::Impl::adopt_polished_point(QpInfo& info) {
  const detail::StandardForm& f = form;
  load_unscaled_point(result.x, result.y, result.z, result.z_bounds);
  const Vector &zg = work.zg, &zb = work.zb;
  const double mu = detail::kPolishMu, root = std::sqrt(mu);
  for (detail::Side* side : it.sides()) {
    const bool rows = (side == &it.g_lower || side == &it.g_upper);
    for (Index k = 0; k < side->size(); ++k) {
      const Index q = side->idx[k];
      const double v = rows ? it.vg(q) : it.x(q), zeta = rows ? zg(q) : zb(q);
      double slack = std::max(side->upper ? side->bound(k) - v : v - side->bound(k), 0.0);
      double z = std::max(side->upper ? zeta : -zeta, 0.0);
      if (z >= slack) {  // active side (a weakly active one has z = s = √μ)
        z = std::max(z, root);
        slack = mu / z;
      } else {
        slack = std::max(slack, root);
        z = mu / slack;
      }
      side->s(k) = slack;
      side->z(k) = z;
    }
  }
  it.compute_side_residuals(f);
  it.barrier_terms(f.mg, f.n, Dg, Db);
  return factorize(info);
}

}  // namespace lcprelax
