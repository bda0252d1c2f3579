// Infeasibility certificates from interior-point iterates and steps (Farkas' lemma).
//
// Primal: y and z_lower, z_upper ≥ 0 with  Ẽᵀy + G̃ᵀ(z_u − z_l) + (zb_u − zb_l) = 0  and
//     b̃ᵀy + g̃uᵀz_u − g̃lᵀz_l + x̃uᵀzb_u − x̃lᵀzb_l < 0
// prove that no x satisfies the constraints (for a feasible x the left side would be ≥ 0).
// Dual: a direction d with P̃d = 0, Ẽd = 0, G̃d and d in the recession cone of the row
// and variable bounds, and q̃ᵀd < 0 proves the objective unbounded below.
// Both are tested after normalization to ∞-norm 1 with tolerance eps (residual) and
// max(eps, 1e-6) (strict sign of the support term), in the scaled space, where the
// diverging iterates of an infeasible problem approach such certificates.
#include "qp_solver_impl.hpp"
#include "vector_norms.hpp"

#include <algorithm>
#include <cmath>

namespace lcprelax::detail {
bool primal_infeasibility_certificate(const StandardForm& f, const QpProblem& p, const Vector& y, const Iterate& it,
                                      bool use_steps, double eps, QpResult& r, Workspace& w) {
  // The norm and the support term first, from the sides as they are (no copies: this runs
  // every iteration); the candidate iterate and the residual only when the sign test passes.
  double nrm = inf_norm(y);
  double supp = f.me ? f.be.dot(y) : 0.0;
  for (const Side* s : it.sides()) {
    const Vector& z = use_steps ? s->dz : s->z;
    for (Index k = 0; k < s->size(); ++k) {
      const double zk = std::max(z(k), 0.0);
      nrm = std::max(nrm, zk);
      supp += s->upper ? s->bound(k) * zk : -s->bound(k) * zk;
    }
  }
  if (!(nrm > 0) || !std::isfinite(nrm)) return false;
  if (!(supp < -std::max(eps, 1e-6) * nrm)) return false;
  Vector &zg = w.cert_zg, &res = w.cert_n;
  it.signed_positive_parts(f.mg, f.n, use_steps, zg, w.cert_zb);
  res = w.cert_zb;
  if (f.me) res.noalias() += f.Et * y;
  if (f.mg) res.noalias() += f.Gt * zg;
  if (!(inf_norm(res) <= eps * nrm)) return false;
  // A certificate: the candidate iterate (the only copy, made once per solve at most).
  Iterate cand = it;
  cand.y = y;
  for (Side* s : cand.sides()) s->z = (use_steps ? s->dz : s->z).cwiseMax(0.0);
  unscale_solution(f, p, cand, r, w);
  double un = std::max({inf_norm(r.y), inf_norm(r.z), inf_norm(r.z_bounds)});
  if (un > 0) {
    r.y /= un;
    r.z /= un;
    r.z_bounds /= un;
  }
  return true;
}

bool dual_infeasibility_certificate(const StandardForm& f, const Vector& d, double eps, QpResult& r, Workspace& w) {
  const double nrm = inf_norm(d);
  if (!(nrm > 0) || !std::isfinite(nrm)) return false;
  const double tol = eps * nrm;
  if (!(f.q.dot(d) < -std::max(eps, 1e-6) * nrm)) return false;
  Vector &Pd = w.cert_n, &Ed = w.cert_me, &Gd = w.cert_mg;
  Pd.noalias() = f.P.selfadjointView<Eigen::Upper>() * d;
  if (!(inf_norm(Pd) <= tol)) return false;
  if (f.me) {
    Ed.noalias() = f.E * d;
    if (!(inf_norm(Ed) <= tol)) return false;
  }
  Gd.noalias() = f.G * d;
  for (Index i = 0; i < f.mg; ++i) {
    if (std::isfinite(f.gu(i)) && Gd(i) > tol) return false;
    if (std::isfinite(f.gl(i)) && Gd(i) < -tol) return false;
  }
  for (Index j = 0; j < f.n; ++j) {
    if (std::isfinite(f.xu(j)) && d(j) > tol) return false;
    if (std::isfinite(f.xl(j)) && d(j) < -tol) return false;
  }
  r.x = f.Dx.cwiseProduct(d);
  r.x /= inf_norm(r.x);
  return true;
}

}  // namespace lcprelax::detail
