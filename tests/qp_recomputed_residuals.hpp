#pragma once
// qpbenchmark's residuals of a QP answer recomputed from the data (tests only): primal
// max(dist(Ax, b), dist(Gx, [l, u]), dist(x, [xl, xu])), dual ‖Px + q + Aᵀy + Gᵀz + z_b‖∞
// and gap |xᵀPx + qᵀx + bᵀy + σ(z) + σ(z_b)| with σ the support function of the bounds
// (u·z where z > 0, l·z where z < 0), plus 64·u·Σ|terms| of the gap, the size its
// evaluation error can reach in double.
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/kkt/qp_result.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcprelax::test_support {

struct Recomputed {
  double primal = 0, dual = 0, gap = 0;
  double gap_floor = 0;  ///< 64·u·Σ|terms| of the gap
};

inline double distance_to(double v, double lo, double hi) { return std::max({lo - v, v - hi, 0.0}); }
inline double support_term(double z, double lo, double hi) { return z > 0 ? hi * z : (z < 0 ? lo * z : 0.0); }

inline Recomputed recompute(const QpProblem& p, const QpResult& r) {
  Recomputed c;
  const Vector Px = p.P.selfadjointView<Eigen::Upper>() * r.x, Gx = p.G * r.x;
  Vector dual = Px + p.q + r.z_bounds;
  if (p.G.rows()) dual += p.G.transpose() * r.z;
  double gap = r.x.dot(Px) + p.q.dot(r.x);
  double terms = std::fabs(r.x.dot(Px)) + std::fabs(p.q.dot(r.x));
  if (p.A.rows()) {
    const Vector Ax = p.A * r.x;
    for (Index i = 0; i < Ax.size(); ++i) c.primal = std::max(c.primal, std::fabs(Ax(i) - p.b(i)));
    dual += p.A.transpose() * r.y;
    gap += p.b.dot(r.y);
    terms += std::fabs(p.b.dot(r.y));
  }
  for (Index i = 0; i < Gx.size(); ++i) {
    c.primal = std::max(c.primal, distance_to(Gx(i), p.l(i), p.u(i)));
    const double t = support_term(r.z(i), p.l(i), p.u(i));
    gap += t;
    terms += std::fabs(t);
  }
  for (Index j = 0; j < r.x.size(); ++j) {
    c.primal = std::max(c.primal, distance_to(r.x(j), p.xl(j), p.xu(j)));
    const double t = support_term(r.z_bounds(j), p.xl(j), p.xu(j));
    gap += t;
    terms += std::fabs(t);
  }
  c.dual = dual.lpNorm<Eigen::Infinity>();
  c.gap = std::fabs(gap);
  c.gap_floor = 64.0 * std::numeric_limits<double>::epsilon() * terms;
  return c;
}

}  // namespace lcprelax::test_support
