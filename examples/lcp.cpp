// Example: solve a small linear complementarity problem with lcprelax::LemkeSolver, check
// the answer independently, and differentiate it.
//
//   find z, w  with  w = M z + q,   0 ≤ z ⊥ w ≥ 0
//
// (docs/conventions.md). In a contact model z holds impulses (N·s) and w the velocities
// (m/s) they must keep nonnegative; the solver itself is unit-agnostic. M is sparse
// (compressed-column) and need not be symmetric: here it is tridiagonal with a positive
// definite symmetric part, so the LCP has exactly one solution and Lemke finds it.
//
// backward(dl/dz) returns ∂ℓ/∂q and ∂ℓ/∂M (on M's pattern) for a loss ℓ(z*) by one
// transposed solve with the final basis; here ℓ = cᵀz*, and ∂ℓ/∂q[2] is compared with a
// central finite difference. Exit status 1 when a check fails.
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/sparse/triplets.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace lcprelax;

namespace {

SparseMatrix make_M() {
  std::vector<Triplet> t;
  for (Index i = 0; i < 4; ++i) {
    t.emplace_back(i, i, 2.0);
    if (i + 1 < 4) t.emplace_back(i, i + 1, 1.0);   // superdiagonal +1
    if (i > 0) t.emplace_back(i, i - 1, -1.0);      // subdiagonal −1
  }
  return from_triplets(4, 4, t);
}

const Vector kC{{1.0, 1.0, 1.0, 1.0}};  // ℓ(z) = cᵀz, so ∂ℓ/∂z = c

// ℓ at the solution for this q (a fresh solver, as a user would check); NaN if unsolved.
double loss(const SparseMatrix& M, const Vector& q) {
  LemkeSolver solver;
  solver.setup(M, q);
  const LcpResult& r = solver.solve();
  return has_solution(r.info.status) ? kC.dot(r.z) : std::nan("");
}

}  // namespace

int main() {
  const SparseMatrix M = make_M();
  const Vector q{{-1.0, 2.0, -3.0, 1.0}};

  LemkeSolver solver;  // default settings: dense basis for n ≤ 32, lexicographic anti-cycling
  solver.setup(M, q);
  const LcpResult& r = solver.solve();
  std::printf("status %s, %ld pivots, reported complementarity %.2e\n", to_string(r.info.status), r.info.pivots,
              r.info.complementarity);
  if (!has_solution(r.info.status)) {
    std::printf("FAILED: %s\n", r.info.message.c_str());
    return 1;
  }

  // Independent check: recompute w from z, then z ≥ 0, w ≥ 0 and min(z_i, w_i) = 0.
  const Vector w = M * r.z + q;
  const double tol = 1e-10;
  bool ok = true;
  for (Index i = 0; i < 4; ++i) {
    std::printf("  i=%d  z=%.6f  w=%.6f  basic=%s\n", i, r.z[i], w[i], r.z_basic[i] ? "z" : "w");
    ok = ok && r.z[i] >= -tol && w[i] >= -tol && std::abs(std::min(r.z[i], w[i])) <= tol;
  }
  std::printf("max |min(z, w)| = %.2e, |w - result.w|_inf = %.2e\n", w.cwiseMin(r.z).cwiseAbs().maxCoeff(),
              (w - r.w).lpNorm<Eigen::Infinity>());
  ok = ok && (w - r.w).lpNorm<Eigen::Infinity>() <= tol;

  // Backward: ∂ℓ/∂q is zero on rows where w is basic (a nonbinding row does not move z).
  const LcpGradient g = solver.backward(kC);
  std::printf("dl/dq = (%.6f, %.6f, %.6f, %.6f), dl/dM(2,3) = %.6f\n", g.dq[0], g.dq[1], g.dq[2], g.dq[3],
              g.dM.coeff(2, 3));

  const double h = 1e-6;
  Vector q_plus = q, q_minus = q;
  q_plus[2] += h;
  q_minus[2] -= h;
  const double fd = (loss(M, q_plus) - loss(M, q_minus)) / (2.0 * h);
  const double err = std::abs(g.dq[2] - fd) / std::max(1.0, std::abs(fd));
  std::printf("dl/dq[2]: backward %.8f, finite difference %.8f, relative error %.1e\n", g.dq[2], fd, err);
  ok = ok && err <= 1e-6;  // the solution is piecewise linear in q: FD is exact up to roundoff

  std::printf("%s\n", ok ? "OK: complementary, gradient agrees" : "FAILED");
  return ok ? 0 : 1;
}
