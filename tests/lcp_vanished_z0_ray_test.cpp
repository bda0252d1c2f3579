// A Lemke path that meets a ray with the artificial z₀ already at zero to roundoff (lemke_pivot.cpp,
// drop_vanished_z0): the almost-complementary basis there holds a solution of the LCP to
// the residual tolerance, and z₀ is pivoted out instead of reporting the ray. The case is
// built by hand in 2 unknowns, on a crash start (lemke.hpp) from the basis {z₁, w₂}:
//   M = [1 1; 1 0] (not a P-matrix), q = (−1, −1 − ε).
// The warm basis gives z₁ = 1 and w₂ = −ε < 0, so z₀ enters at w₂'s row with value ε (d = B·1
// reads 1 in B's coordinates); w₂ leaves and z₂ enters, whose column in the new basis,
// (0, −1), has no positive entry: a ray, at z₀ = ε. z = (1, 0) leaves w = (0, −ε): a solution
// to within ε, and the LCP has no exact one (w₂ ≥ 0 needs z₁ ≥ 1 + ε, then w₁ = 0 needs
// z₂ = −ε).
// Expected:
// - ε = 1e-12 (below the residual tolerance 1e-9·‖q‖∞): solved, with the message naming the
//   vanished z₀, complementarity ≤ 1e-9 (recomputed here), z = (1, 0) to 1e-11;
// - ε = 1e-3 (z₀ not small): no solution is claimed (the residual would be 1e-3); the status
//   is not solved and z is empty;
// - ε = 1e-7: the exit is tried and its solution (residual 1e-7) refused: a ray, no z;
// - a cold-started P-matrix LCP never reaches the case (its message is plain "solved").
#include <lcprelax/lcp/lemke.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

struct HandBuiltRay {
  SparseMatrix M;
  Vector q;
};

HandBuiltRay hand_built_ray(double eps) {
  DenseMatrix M(2, 2);
  M << 1, 1,  //
      1, 0;
  HandBuiltRay p;
  p.M = M.sparseView();
  p.q = Vector(2);
  p.q << -1.0, -1.0 - eps;
  return p;
}

// Crash start from {z₁, w₂}, no cold fallback and no retries: only the crash path answers.
LemkeSettings crash_only() {
  LemkeSettings s;
  s.crash_start = true;
  s.crash_cold_fallback = false;
  s.covering_retries = 0;
  s.regularization_retries = 0;
  return s;
}

// The crash-started solve of p from {z₁, w₂}; the result lives in `solver`.
const LcpResult& crash_solve(LemkeSolver& solver, const HandBuiltRay& p) {
  solver.setup(p.M, p.q);
  solver.warm_start({true, false});
  return solver.solve();
}

TEST(VanishedZ0Ray, TinyZ0AtTheRayIsPivotedOutAndSolves) {
  const HandBuiltRay p = hand_built_ray(1e-12);
  LemkeSolver solver(crash_only());
  const LcpResult& r = crash_solve(solver, p);
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  EXPECT_NE(r.info.message.find("z0 vanished"), std::string::npos) << r.info.message;
  EXPECT_TRUE(r.info.crash_started);
  EXPECT_LE(r.info.complementarity, 1e-9);
  EXPECT_NEAR(r.z(0), 1.0, 1e-11);
  EXPECT_NEAR(r.z(1), 0.0, 1e-11);
  EXPECT_GE(r.z.minCoeff(), 0.0);
  // The complementarity residual recomputed here, not read from info.
  const Vector w = p.M * r.z + p.q;
  EXPECT_LE(r.z.cwiseMin(w).cwiseAbs().maxCoeff(), 1e-9);
  ASSERT_EQ(r.z_basic.size(), 2u);
  EXPECT_TRUE(r.z_basic[0]);
}

TEST(VanishedZ0Ray, LargeZ0AtTheRayIsStillARay) {
  const HandBuiltRay p = hand_built_ray(1e-3);
  LemkeSolver solver(crash_only());
  const LcpResult& r = crash_solve(solver, p);
  EXPECT_NE(r.info.status, LcpStatus::solved) << r.info.message;
  EXPECT_EQ(r.info.message.find("z0 vanished"), std::string::npos) << r.info.message;
  EXPECT_EQ(r.z.size(), 0) << "a failed solve returns no z";
}

// ε = 1e-7: small enough for the exit to be tried (|z₀|·‖d‖∞ ≤ 1e-6), but its solution's
// residual, 1e-7, is above the tolerance: the residual check refuses it and the ray stands,
// with no z of the refused exit left in the result.
TEST(VanishedZ0Ray, ExitAboveTheResidualToleranceIsRefused) {
  const HandBuiltRay p = hand_built_ray(1e-7);
  LemkeSolver solver(crash_only());
  const LcpResult& r = crash_solve(solver, p);
  EXPECT_EQ(r.info.status, LcpStatus::ray_termination) << r.info.message;
  EXPECT_EQ(r.z.size(), 0);
  EXPECT_EQ(r.w.size(), 0);
  EXPECT_TRUE(r.z_basic.empty());
  EXPECT_TRUE(std::isnan(r.info.complementarity));
}

TEST(VanishedZ0Ray, ColdPMatrixSolveNeverTakesThisExit) {
  DenseMatrix M(3, 3);
  M << 4, 1, 0,  //
      1, 3, 1,   //
      0, 1, 2;
  Vector q(3);
  q << -1, 2, -3;
  LemkeSolver solver;
  const SparseMatrix S = M.sparseView();
  solver.setup(S, q);
  const LcpResult& r = solver.solve();
  ASSERT_EQ(r.info.status, LcpStatus::solved);
  EXPECT_EQ(r.info.message, "solved");
}

}  // namespace
}  // namespace lcprelax
