// Unscaling of interior-point iterates and the unscaled residuals used for termination
// (definitions in qp_settings.hpp; the duality gap follows qpbenchmark's definition), on
// the solver's presized work vectors.
#include "qp_solver_impl.hpp"
#include "vector_norms.hpp"

#include <algorithm>
#include <cmath>

namespace lcprelax::detail {
namespace {

long double long_dot(const Vector& a, const Vector& b) {
  long double s = 0.0L;
  for (Index i = 0; i < a.size(); ++i) s += static_cast<long double>(a(i)) * b(i);
  return s;
}

double dist_to_box(double v, double lo, double hi) { return std::max({lo - v, v - hi, 0.0}); }

// u z⁺ + l z⁻, skipping infinite bounds with zero multiplier. The product is a double, as
// in qpbenchmark's float64 evaluation; on dual-degenerate LPs whose multipliers reach 1e9
// it rounds by ~1e-4 per term, so a long-double evaluation of the same gap can differ
// (generated LP of tests/qp_degenerate_lp_test.cpp: 5e-10 here, 3e-7 in long double).
double support(double z, double lo, double hi) {
  if (z > 0) return hi * z;
  if (z < 0) return lo * z;
  return 0.0;
}

}  // namespace

void Workspace::resize(const StandardForm& f, const QpProblem& p) {
  const Index n = f.n, me = f.me, mg = f.mg;
  for (Vector* v : {&rd, &dx, &saved_dx, &last_dx, &zb, &dzb, &xib, &rx, &xc, &rhs_x, &uzb, &cert_zb, &cert_n})
    v->setZero(n);
  for (Vector* v : {&rp, &dy, &saved_dy, &last_dy, &ry, &yi, &cert_me}) v->setZero(me);
  for (Vector* v : {&dz, &saved_dz, &zg, &xig, &rz, &dvg, &gc, &uzg, &cert_zg, &cert_mg}) v->setZero(mg);
  Px.setZero(p.num_variables());
  zb_saved.setZero(p.num_variables());
  Aty.setZero(p.num_variables());
  Gtz.setZero(p.num_variables());
  Ax.setZero(p.num_equalities());
  Gx.setZero(p.num_inequalities());
}

void unscale_solution(const StandardForm& f, const QpProblem& p, const Iterate& it, QpResult& r, Workspace& w) {
  r.x = f.Dx.cwiseProduct(it.x);
  Vector& yi = w.yi;
  yi = (f.Ee.cwiseProduct(it.y)) / f.c;
  it.signed_multipliers(f.mg, f.n, w.uzg, w.uzb);
  const Vector &zg = w.uzg, &zb = w.uzb;
  r.y.resize(p.num_equalities());
  r.z.setZero(p.num_inequalities());
  r.z_bounds = (zb.array() / (f.c * f.Dx.array())).matrix();
  for (Index k = 0; k < f.me; ++k) {
    switch (f.eq_source[k]) {
      case EqSource::a_row: r.y(f.eq_index[k]) = yi(k); break;
      case EqSource::g_row: r.z(f.eq_index[k]) = yi(k); break;
      case EqSource::fixed_variable: r.z_bounds(f.eq_index[k]) = yi(k); break;
    }
  }
  for (Index k = 0; k < f.mg; ++k) r.z(f.g_index[k]) = f.Eg(k) * zg(k) / f.c;
}

Residuals compute_residuals(const QpProblem& p, const QpResult& r, Vector& Px, Vector& Ax, Vector& Gx, Vector& Aty,
                            Vector& Gtz) {
  Residuals out;
  Px.noalias() = p.P.selfadjointView<Eigen::Upper>() * r.x;
  Ax.noalias() = p.A * r.x;
  Gx.noalias() = p.G * r.x;
  Aty.noalias() = p.A.transpose() * r.y;
  Gtz.noalias() = p.G.transpose() * r.z;
  out.primal = inf_norm(Ax - p.b);
  for (Index i = 0; i < Gx.size(); ++i) out.primal = std::max(out.primal, dist_to_box(Gx(i), p.l(i), p.u(i)));
  for (Index j = 0; j < r.x.size(); ++j) out.primal = std::max(out.primal, dist_to_box(r.x(j), p.xl(j), p.xu(j)));
  out.scale_p = std::max({inf_norm(Ax), inf_norm(p.b), inf_norm(Gx), inf_norm(r.x)});

  out.dual = inf_norm(Px + p.q + Aty + Gtz + r.z_bounds);
  out.scale_d = std::max({inf_norm(Px), inf_norm(p.q), inf_norm(Aty), inf_norm(Gtz), inf_norm(r.z_bounds)});

  // The gap is a difference of large terms on badly scaled problems: accumulate in long
  // double so that its own roundoff stays below the tolerance.
  long double sup = 0.0L;
  for (Index i = 0; i < r.z.size(); ++i) sup += support(r.z(i), p.l(i), p.u(i));
  for (Index j = 0; j < r.z_bounds.size(); ++j) sup += support(r.z_bounds(j), p.xl(j), p.xu(j));
  const long double xPx = long_dot(r.x, Px), qx = long_dot(p.q, r.x), by = long_dot(p.b, r.y);
  out.gap = static_cast<double>(std::abs(xPx + qx + by + sup));
  out.scale_g = static_cast<double>(std::max({std::abs(xPx), std::abs(qx), std::abs(by), std::abs(sup)}));
  return out;
}

Residuals compute_residuals(const QpProblem& p, const QpResult& r, Workspace& w) {
  return compute_residuals(p, r, w.Px, w.Ax, w.Gx, w.Aty, w.Gtz);
}

}  // namespace lcprelax::detail
