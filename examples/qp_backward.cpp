// Example: solve a small sparse QP with lcprelax::QpSolver and differentiate its solution.
//
//   minimize    ½ xᵀPx + qᵀx
//   subject to  x0 + x1 + x2 = 1                (A x = b)
//               x0 − x1 ≤ 0,  0.5 ≤ x0 + 2x2 ≤ 2  (l ≤ G x ≤ u)
//               x ≥ 0                            (xl ≤ x ≤ xu)
//
// Conventions (docs/conventions.md): P is given as its UPPER triangle (a stored
// off-diagonal p at (i,j) means P(i,j) = P(j,i) = p). The multipliers satisfy
//   P x + q + Aᵀy + Gᵀz + z_bounds = 0,
// with z > 0 where the upper side of a row (or bound) is active and z < 0 where the lower
// side is. The solver is unit-agnostic: x, q, b, ... carry whatever units the model has.
//
// Then backward() gives the gradient of a loss ℓ(x*) = wᵀx* with respect to every datum
// (q, b, l, u, xl, xu, P, A, G), from ∂ℓ/∂x = w; two entries are checked against central
// finite differences of re-solved problems. Exit status 1 when a check fails.
#include <lcprelax/core/math_constants.hpp>  // kInf
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/sparse/triplets.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

using namespace lcprelax;

namespace {

QpProblem make_problem() {
  QpProblem p(3);  // 3 free variables, no rows yet
  p.P = from_triplets(3, 3, {{0, 0, 4.0}, {0, 1, 1.0}, {1, 1, 2.0}, {2, 2, 1.0}});  // upper triangle
  p.q = Vector{{-1.0, -2.0, 1.5}};
  p.A = from_triplets(1, 3, {{0, 0, 1.0}, {0, 1, 1.0}, {0, 2, 1.0}});
  p.b = Vector{{1.0}};
  p.G = from_triplets(2, 3, {{0, 0, 1.0}, {0, 1, -1.0}, {1, 0, 1.0}, {1, 2, 2.0}});
  p.l = Vector{{-kInf, 0.5}};  // row 0 is one-sided (upper only)
  p.u = Vector{{0.0, 2.0}};
  p.xl = Vector::Zero(3);
  p.xu = Vector::Constant(3, kInf);
  return p;
}

const Vector kW{{1.0, 2.0, -1.0}};  // the loss ℓ(x) = wᵀx, so ∂ℓ/∂x = w

// ℓ at the solution of `p` (a fresh solver each time, as a user would check).
double loss(const QpProblem& p, const QpSettings& settings) {
  QpSolver solver(settings);
  solver.setup(p);
  const QpResult& r = solver.solve();
  if (r.info.status != QpStatus::solved) std::printf("  FD solve: %s\n", to_string(r.info.status));
  return kW.dot(r.x);
}

}  // namespace

int main() {
  QpSettings settings;
  settings.eps_abs = 1e-11;  // tight, so that the finite differences below are accurate
  const QpProblem problem = make_problem();

  QpSolver solver(settings);
  solver.setup(problem);
  const QpResult& r = solver.solve();
  std::printf("status %s (%s), %d iterations\n", to_string(r.info.status), r.info.message.c_str(),
              r.info.iterations);
  if (!has_solution(r.info.status)) return 1;
  std::printf("objective %.10g; residuals: primal %.2e, dual %.2e, gap %.2e\n", r.info.objective,
              r.info.primal_residual, r.info.dual_residual, r.info.duality_gap);
  std::printf("x = (%.6f, %.6f, %.6f)\n", r.x[0], r.x[1], r.x[2]);
  // Expected: row 1 on its lower side l = 0.5 (z[1] < 0); row 0 (x0 − x1 ≤ 0) and the
  // bounds x ≥ 0 inactive (z[0], z_bounds ≈ 0); y is the equality row's multiplier.
  std::printf("y = %.6f, z = (%.6f, %.6f), z_bounds = (%.6f, %.6f, %.6f)\n", r.y[0], r.z[0], r.z[1],
              r.z_bounds[0], r.z_bounds[1], r.z_bounds[2]);

  // The sign convention made explicit: the stationarity residual with the full symmetric P.
  const SparseMatrix P_full = problem.P.selfadjointView<Eigen::Upper>();
  const Vector stationarity = P_full * r.x + problem.q + problem.A.transpose() * r.y +
                              problem.G.transpose() * r.z + r.z_bounds;
  std::printf("|Px + q + A'y + G'z + z_bounds|_inf = %.2e\n", stationarity.lpNorm<Eigen::Infinity>());

  // Backward: one solve with the final KKT factorization (no new factorization).
  const QpGradient g = solver.backward(kW);
  // Inactive sides (row 0, l[0] = −∞, the bounds) get a zero (roundoff) gradient.
  std::printf("dl/dq = (%.6f, %.6f, %.6f), dl/db = %.6f, dl/dl = (%g, %.6f), dl/du = (%g, %g)\n", g.dq[0],
              g.dq[1], g.dq[2], g.db[0], g.dl[0], g.dl[1], g.du[0], g.du[1]);
  // The adjoint residual is at roundoff for a well-posed gradient; far above 1e-9 it says
  // the KKT matrix is singular at the optimum and the gradient does not exist.
  std::printf("adjoint residual %.2e\n", g.adjoint_residual);

  // Central finite differences, step h, of two data that move the solution: q[0] and the
  // active lower side l[1] of row 1.
  const double h = 1e-6;
  auto central = [&](auto perturb) {
    QpProblem plus = problem, minus = problem;
    perturb(plus, +h);
    perturb(minus, -h);
    return (loss(plus, settings) - loss(minus, settings)) / (2.0 * h);
  };
  const double fd_q0 = central([](QpProblem& p, double d) { p.q[0] += d; });
  const double fd_l1 = central([](QpProblem& p, double d) { p.l[1] += d; });
  const double tol = 1e-5;  // relative to max(1, |fd|): the QP is solved to 1e-11, h = 1e-6
  bool ok = g.adjoint_residual < 1e-9;
  for (const auto& [name, adjoint, fd] : {std::tuple{"q[0]", g.dq[0], fd_q0}, std::tuple{"l[1]", g.dl[1], fd_l1}}) {
    const double err = std::abs(adjoint - fd) / std::max(1.0, std::abs(fd));
    std::printf("dl/d%s: backward %.8f, finite difference %.8f, relative error %.1e\n", name, adjoint, fd, err);
    ok = ok && err <= tol;
  }
  std::printf("%s\n", ok ? "OK: gradients agree" : "FAILED: gradient check");
  return ok ? 0 : 1;
}
