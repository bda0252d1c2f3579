// LCP through the interior-point QP (formulation in lcp_ipm.hpp).
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/lcp/lcp_ipm.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>

namespace lcprelax {

LcpResult solve_lcp_ipm(const SparseMatrix& M, const Vector& q, const QpSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  const Index n = static_cast<Index>(q.size());
  if (M.rows() != n || M.cols() != n) throw InputError("LCP: M must be n×n with n = size of q");
  QpProblem p(n);
  const SparseMatrix sym = SparseMatrix(M.transpose()) + M;
  p.P = sym.triangularView<Eigen::Upper>();
  p.q = q;
  p.G = M;
  p.l = -q;
  p.u = Vector::Constant(n, std::numeric_limits<double>::infinity());
  p.xl = Vector::Zero(n);
  for (Index j = 0; j < n; ++j)
    if (sym.coeff(j, j) < 0)
      throw InputError("M + Mᵀ has a negative diagonal entry at " + std::to_string(j) +
                       ": the LCP is not monotone, use Lemke");
  // The LCP residual is a per-component complementarity, the QP's gap their sum: solve the
  // QP two orders tighter than the LCP tolerance.
  QpSettings s = settings;
  s.eps_abs = std::min(settings.eps_abs, 1e-11);
  QpSolver solver(s);
  solver.setup(p);  // NaN / Inf data → InputError
  const QpResult& r = solver.solve();
  LcpResult out;
  out.info.pivots = r.info.iterations;
  out.z = r.x.size() == n ? Vector(r.x.cwiseMax(0.0)) : Vector(Vector::Zero(n));
  out.w = M * out.z + q;
  out.info.complementarity = n ? out.z.cwiseMin(out.w).cwiseAbs().maxCoeff() : 0.0;
  out.z_basic.resize(n);
  for (Index i = 0; i < n; ++i) out.z_basic[i] = out.z(i) > out.w(i);
  const double tol = 1e-9 * std::max(1.0, n ? q.lpNorm<Eigen::Infinity>() : 0.0);
  const bool qp_ok = has_solution(r.info.status);
  if (qp_ok && out.info.complementarity <= tol) {
    out.info.status = LcpStatus::solved;
    out.info.message = "solved by the interior point";
  } else if (r.info.status == QpStatus::primal_infeasible) {
    out.info.status = LcpStatus::ray_termination;
    out.info.message = "no z ≥ 0 with Mz + q ≥ 0 (primal infeasible QP): the LCP has no solution";
  } else if (qp_ok) {
    out.info.status = LcpStatus::numerical_error;
    char buf[160];
    std::snprintf(buf, sizeof buf, "the QP converged but the complementarity residual %.3g exceeds %.3g",
                  out.info.complementarity, tol);
    out.info.message = std::string(buf) + " (degenerate LCPs are solved only to about √eps: use Lemke)";
  } else {
    out.info.status = LcpStatus::numerical_error;
    out.info.message = std::string("interior point ended with ") + to_string(r.info.status) +
                       " (is M + Mᵀ positive semidefinite?), complementarity " +
                       std::to_string(out.info.complementarity);
  }
  out.info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace lcprelax
