// The convex two-phase contact model (contact_step.hpp), solved by the interior-point QP.
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/models/contact_step.hpp>

#include <cmath>
#include <limits>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Relative loosening of phase 2's bound eᵀλn ≤ κ, tried in turn until the interior point
// solves phase 2. The bound binds while a body slides (more normal impulse would buy more
// friction), so the loosening is an error of up to that fraction of the friction impulse:
// 1e-6 first (exact to the incline test's 1e-5); resting pyramids (tests/
// dynamics_rest_test.cpp: statically indeterminate, W singular, every normal row active)
// leave the interior point "no progress" at 1e-6 and are solved at 1e-4 or 1e-2.
constexpr double kKappaSlack[] = {1e-6, 1e-4, 1e-2};

bool accepted(QpStatus s) { return s == QpStatus::solved || s == QpStatus::solved_inaccurate; }

SparseMatrix upper(const SparseMatrix& A) {
  SparseMatrix U = A.triangularView<Eigen::Upper>();
  U.makeCompressed();
  return U;
}

}  // namespace

ContactSolution solve_convex_model(const ContactSystem& s, double dt, const QpSettings& settings, double rho) {
  const Index nc = s.num_contacts(), nf = s.num_friction(), n = nc + nf;
  const SparseMatrix W = delassus(s);
  const Vector bn = s.Jn * s.v_star + s.phi.cwiseMax(0.0) / dt;
  ContactSolution out;

  // No contact is approaching (b ≥ 0): λ = 0 solves both phases exactly (phase 1's optimum
  // is 0, then κ = 0 forces λn = 0 and |λt| ≤ μλn forces λt = 0); an interior point has no
  // interior to work in there, so this case is answered directly.
  if (nc == 0 || bn.minCoeff() >= 0.0) {
    out.ok = true;
    out.lambda_n = Vector::Zero(nc);
    out.lambda_t = Vector::Zero(nf);
    out.v_next = s.v_star;
    return out;
  }

  // Phase 1: frictionless normal impulses.
  QpProblem p1(nc);
  p1.P = upper(W.topLeftCorner(nc, nc));
  p1.q = bn;
  p1.xl.setZero();
  QpSolver qp1(settings);
  qp1.setup(p1);
  const QpResult& r1 = qp1.solve();
  out.work = r1.info.iterations;
  if (!accepted(r1.info.status)) {
    out.message = std::string("phase 1: ") + to_string(r1.info.status) + ": " + r1.info.message;
    return out;
  }
  // κ = eᵀλn of phase 1, loosened (kKappaSlack, plus 1e-12 N·s): with the normal rows
  // active, eᵀλn ≤ κ exactly makes phase 2's feasible set a point in λn, which leaves the
  // interior point no interior (measured: "no progress" failures on 1-2 contact islands).
  const double kappa = r1.x.cwiseMax(0.0).sum();

  // Phase 2: friction, bounded by κ, with the ρ·diag(exp(φ))·diag(Wnn) term on λn.
  QpProblem p2(n);
  SparseMatrix P = W;
  for (Index i = 0; i < nc; ++i) P.coeffRef(i, i) += 2.0 * rho * std::exp(s.phi(i)) * W.coeff(i, i);
  p2.P = upper(P);
  p2.q.head(nc) = s.Jn * s.v_star;
  p2.q.tail(nf) = s.Jt * s.v_star;
  std::vector<Triplet> t;
  for (Index c = 0; c < n; ++c)  // rows 0..nc: Jn v⁺ + max(φ,0)/Δt = W(0:nc, :) λ + bn ≥ 0
    for (SparseMatrix::InnerIterator it(W, c); it; ++it)
      if (it.row() < nc) t.emplace_back(it.row(), c, it.value());
  for (Index i = 0; i < nc; ++i) t.emplace_back(nc, i, 1.0);  // eᵀλn ≤ κ
  for (Index f = 0; f < nf; ++f) {  // λt − μλn ≤ 0 and λt + μλn ≥ 0
    t.emplace_back(nc + 1 + 2 * f, nc + f, 1.0);
    t.emplace_back(nc + 1 + 2 * f, s.friction_rows[f], -s.mu(f));
    t.emplace_back(nc + 2 + 2 * f, nc + f, 1.0);
    t.emplace_back(nc + 2 + 2 * f, s.friction_rows[f], s.mu(f));
  }
  const Index m = nc + 1 + 2 * nf;
  p2.G.resize(m, n);
  p2.G.setFromTriplets(t.begin(), t.end());
  p2.G.makeCompressed();
  p2.l = Vector::Constant(m, -kInf);
  p2.u = Vector::Constant(m, kInf);
  p2.l.head(nc) = -bn;
  for (Index f = 0; f < nf; ++f) {
    p2.u(nc + 1 + 2 * f) = 0.0;
    p2.l(nc + 2 + 2 * f) = 0.0;
  }
  p2.xl.head(nc).setZero();
  QpResult r2;
  for (double slack : kKappaSlack) {
    p2.u(nc) = kappa * (1.0 + slack) + 1e-12;
    QpSolver qp2(settings);
    qp2.setup(p2);
    r2 = qp2.solve();
    out.work += r2.info.iterations;
    if (accepted(r2.info.status)) break;
  }
  out.residual = std::max(r2.info.primal_residual, r2.info.dual_residual);
  if (!accepted(r2.info.status)) {
    // Not solved; phase 1's frictionless answer is returned with it (contact_step.hpp).
    out.message = std::string("phase 2: ") + to_string(r2.info.status) + ": " + r2.info.message;
    out.lambda_n = r1.x.cwiseMax(0.0);
    out.lambda_t = Vector::Zero(nf);
    out.v_next = s.v_star + s.minv.cwiseProduct(s.Jn.transpose() * out.lambda_n);
    return out;
  }
  out.ok = true;
  out.lambda_n = r2.x.head(nc).cwiseMax(0.0);
  out.lambda_t = r2.x.tail(nf);
  const Vector impulse = s.Jn.transpose() * out.lambda_n + s.Jt.transpose() * out.lambda_t;
  out.v_next = s.v_star + s.minv.cwiseProduct(impulse);
  return out;
}

}  // namespace lcprelax
