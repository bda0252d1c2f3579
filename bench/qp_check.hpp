#pragma once
// Independent residuals of a QP solution (header-only helper of the bench runners), with
// the definitions of QpSettings (qpbenchmark's, ∞-norms on the unscaled problem):
//   primal  max(‖Ax − b‖, ‖dist(Gx, [l,u])‖, ‖dist(x, [xl,xu])‖)
//   dual    ‖Px + q + Aᵀy + Gᵀz + z_bounds‖
//   gap     |xᵀPx + qᵀx + bᵀy + σ(z) + σ(z_bounds)|,  σ(z) = Σ u_i z_i⁺ + l_i z_i⁻
// (z⁺ = max(z, 0), z⁻ = min(z, 0); docs/conventions.md sign convention: z > 0 at an active upper
// side). A term of σ whose bound is infinite is skipped: a multiplier pushing against an
// infinite bound is dual infeasibility that the stationarity residual alone does not
// measure (the multiplier sign is reported separately as sign_violation).
// Used to score a peer solver's solution and to cross-check lcprelax's reported residuals.
#include <lcprelax/kkt/qp_problem.hpp>

#include <algorithm>
#include <cmath>

namespace lcprelax::bench {

struct QpResiduals {
  double primal = 0.0;
  double dual = 0.0;
  double gap = 0.0;
  double sign_violation = 0.0;  ///< largest multiplier on an infinite bound's side
};

namespace detail {

/// Distance of v to [lo, hi].
inline double interval_distance(double v, double lo, double hi) {
  if (v < lo) return lo - v;
  if (v > hi) return v - hi;
  return 0.0;
}

/// σ term of one multiplier and the side it pushes against; adds sign violations.
inline double support_term(double zi, double lo, double hi, double& sign_violation) {
  if (zi > 0.0) {
    if (std::isfinite(hi)) return hi * zi;
    sign_violation = std::max(sign_violation, zi);
  } else if (zi < 0.0) {
    if (std::isfinite(lo)) return lo * zi;
    sign_violation = std::max(sign_violation, -zi);
  }
  return 0.0;
}

}  // namespace detail

/// y may be empty when the problem has no equality rows.
inline QpResiduals qp_residuals(const QpProblem& p, const Vector& x, const Vector& y, const Vector& z,
                                const Vector& z_bounds) {
  QpResiduals r;
  const Vector px = p.P.selfadjointView<Eigen::Upper>() * x;
  Vector stationarity = px + p.q + z_bounds;

  if (p.A.rows() > 0) {
    r.primal = std::max(r.primal, (p.A * x - p.b).lpNorm<Eigen::Infinity>());
    stationarity += p.A.transpose() * y;
  }
  double support = p.A.rows() > 0 ? p.b.dot(y) : 0.0;

  if (p.G.rows() > 0) {
    const Vector gx = p.G * x;
    for (Index i = 0; i < gx.size(); ++i) {
      r.primal = std::max(r.primal, detail::interval_distance(gx[i], p.l[i], p.u[i]));
      support += detail::support_term(z[i], p.l[i], p.u[i], r.sign_violation);
    }
    stationarity += p.G.transpose() * z;
  }
  for (Index j = 0; j < x.size(); ++j) {
    r.primal = std::max(r.primal, detail::interval_distance(x[j], p.xl[j], p.xu[j]));
    support += detail::support_term(z_bounds[j], p.xl[j], p.xu[j], r.sign_violation);
  }
  r.dual = stationarity.lpNorm<Eigen::Infinity>();
  r.gap = std::abs(x.dot(px) + p.q.dot(x) + support);
  return r;
}

}  // namespace lcprelax::bench
