// A ray found with an updated basis factorization is rechecked with a fresh one before
// Lemke reports it (lemke_pivot.cpp): a genuine ray is still reported, after the recheck,
// and a solvable LCP never triggers one.
#include <lcprelax/lcp/lemke.hpp>

#include <gtest/gtest.h>

namespace lcprelax {
namespace {

SparseMatrix sparse(const DenseMatrix& M) { return M.sparseView(); }

LemkeSettings without_retries(LemkeMethod method) {
  LemkeSettings s;
  s.method = method;
  s.covering_retries = 0;
  s.regularization_retries = 0;
  return s;
}

// w₃ = −z₁ − z₂ − 1 < 0 for every z ≥ 0: infeasible, and Lemke reaches the ray only after
// z₀ and z₁ or z₂ have entered the basis (so its factorization has been updated).
TEST(LemkeRayRecheck, InfeasibleLcpStillEndsInRayAfterTheRecheck) {
  const DenseMatrix M = (DenseMatrix(3, 3) << 1, 0, 0, 0, 1, 0, -1, -1, 0).finished();
  const Vector q = (Vector(3) << -1, -1, -1).finished();
  for (LemkeMethod method : {LemkeMethod::sparse, LemkeMethod::dense}) {
    LemkeSolver solver(without_retries(method));
    solver.setup(sparse(M), q);
    const LcpResult& r = solver.solve();
    EXPECT_EQ(r.info.status, LcpStatus::ray_termination) << r.info.message;
    EXPECT_GE(r.info.pivots, 1);
    EXPECT_LE(r.info.ray_rechecks, 1);  // one recheck at most: the ray ends the path
    if (method == LemkeMethod::sparse) {
      EXPECT_EQ(r.info.ray_rechecks, 1);
    }
  }
}

// A P-matrix LCP (unique solution, no ray) on the sparse path: no recheck.
TEST(LemkeRayRecheck, SolvableLcpNeedsNoRecheck) {
  const int n = 40;
  DenseMatrix M = DenseMatrix::Identity(n, n) * 4.0;
  for (int i = 0; i + 1 < n; ++i) M(i, i + 1) = M(i + 1, i) = -1.0;
  Vector q(n);
  for (int i = 0; i < n; ++i) q(i) = (i % 3 == 0) ? 1.0 : -1.0 - 0.01 * i;
  LemkeSolver solver(without_retries(LemkeMethod::sparse));
  solver.setup(sparse(M), q);
  const LcpResult& r = solver.solve();
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  EXPECT_EQ(r.info.ray_rechecks, 0);
  const Vector w = M * r.z + q;
  EXPECT_LE(r.z.cwiseMin(w).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace lcprelax
