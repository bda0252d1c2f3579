// QpSolver::backward after a warm-started solve. Expected: a one-variable box QP
// min ½x² + b·x, −0.3 ≤ x ≤ 0.3, is solved cold, and the same problem is then solved on
// another solver (first used for a different problem, then update()d) warm-started from
// the cold solution. Where the warm start already meets the tolerances the solve takes
// 0 iterations and has no factorization of its own; backward() must still return the
// gradient of THIS problem (∂x/∂q = −1 in the interior, ∂x/∂u = 1 at the active upper
// bound, 0 for the inactive side), equal to the cold solver's to 1e-6 — before the fix it
// returned the previous problem's (dq −1.2e-8 instead of −1). Checked for b in the
// interior case (0.05) and at an active bound (−2); at least one warm solve must take 0
// iterations, or the test would not exercise the case.
#include <lcprelax/kkt/qp_solver.hpp>

#include <gtest/gtest.h>

#include <vector>

namespace {

using namespace lcprelax;

QpProblem box_qp(double b, double bound) {
  QpProblem p(1);
  std::vector<Triplet> t{{0, 0, 1.0}};
  p.P.resize(1, 1);
  p.P.setFromTriplets(t.begin(), t.end());
  p.q(0) = b;
  p.xl(0) = -bound;
  p.xu(0) = bound;
  return p;
}

TEST(QpBackwardWarmStart, ZeroIterationWarmSolveGivesThisProblemsGradient) {
  int zero_iteration_solves = 0;
  for (double b : {0.05, -2.0}) {
    SCOPED_TRACE(b);
    QpSolver cold;
    cold.setup(box_qp(b, 0.3));
    const QpResult rc = cold.solve();
    ASSERT_EQ(rc.info.status, QpStatus::solved);
    const QpGradient gc = cold.backward(Vector::Constant(1, 1.0));

    QpSolver warm;
    warm.setup(box_qp(-1.7, 0.9));
    ASSERT_EQ(warm.solve().info.status, QpStatus::solved);
    warm.update(box_qp(b, 0.3));
    warm.warm_start(rc.x, Vector(), Vector(), rc.z_bounds);
    const QpResult rw = warm.solve();
    ASSERT_EQ(rw.info.status, QpStatus::solved);
    zero_iteration_solves += rw.info.iterations == 0;
    const QpGradient gw = warm.backward(Vector::Constant(1, 1.0));
    EXPECT_NEAR(gw.dq(0), gc.dq(0), 1e-6);
    EXPECT_NEAR(gw.dxu(0), gc.dxu(0), 1e-6);
    EXPECT_NEAR(gw.dxl(0), gc.dxl(0), 1e-6);
    EXPECT_NEAR(warm.result().x(0), rc.x(0), 1e-8);
  }
  EXPECT_GE(zero_iteration_solves, 1);
}

}  // namespace
