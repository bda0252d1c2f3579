// LCP through the interior-point QP (formulation in lcp_ipm.hpp).
#include <lcprelax/kkt/qp_convexity.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/lcp/lcp_ipm.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace lcprelax {

LcpResult solve_lcp_ipm(const SparseMatrix& M, const Vector& q, const QpSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  const Index n = static_cast<Index>(q.size());
  if (M.rows() != n || M.cols() != n) throw InputError("LCP: M must be n×n with n = size of q");
  // Input errors in the LCP's terms (M, q), not the QP's (P, G, l) that the user never gave.
  for (Index k = 0; k < M.nonZeros(); ++k)
    if (!std::isfinite(M.valuePtr()[k])) throw InputError("LCP: M has a NaN or infinite entry");
  for (Index i = 0; i < n; ++i)
    if (!std::isfinite(q(i))) throw InputError("LCP: q(" + std::to_string(i) + ") is not finite");
  QpProblem p(n);
  const SparseMatrix sym = SparseMatrix(M.transpose()) + M;
  for (Index k = 0; k < sym.nonZeros(); ++k)
    if (!std::isfinite(sym.valuePtr()[k]))
      throw InputError("LCP: M + Mᵀ overflows (entries near the largest double): scale M");
  p.P = sym.triangularView<Eigen::Upper>();
  p.q = q;
  p.G = M;
  p.l = -q;
  p.u = Vector::Constant(n, std::numeric_limits<double>::infinity());
  p.xl = Vector::Zero(n);
  if (std::string e = psd_error(p.P, "(M + Mᵀ)"); !e.empty())
    throw InputError("LCP: M is not monotone, which the interior point needs (Lemke does not): " + e);
  // The LCP residual is a per-component complementarity, the QP's gap their sum: solve the
  // QP two orders tighter than the LCP tolerance.
  QpSettings s = settings;
  s.eps_abs = std::min(settings.eps_abs, 1e-11);
  s.check_convexity = false;  // done above, in the LCP's terms
  QpSolver solver(s);
  solver.setup(p);
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
  if (!out.z.allFinite() || !out.w.allFinite()) {  // overflow: never `solved` (w = ∞ has min(z, w) = 0)
    out.info.status = LcpStatus::numerical_error;
    out.info.message = "z or w has a non-finite entry (overflow: data too large for doubles)";
  } else if (qp_ok && out.info.complementarity <= tol) {
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
    char buf[96];
    std::snprintf(buf, sizeof buf, ", complementarity %.3g", out.info.complementarity);
    out.info.message = std::string("interior point ended with ") + to_string(r.info.status) + ": " +
                       r.info.message + buf;
  }
  out.info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace lcprelax
