// QpSolver::update() (new values, same pattern) and warm_start().
//
// Problems: min ½xᵀPx + qᵀx s.t. Ax = b, l ≤ Gx ≤ u, xl ≤ x ≤ xu with P = BᵀB + 0.1·I ≻ 0
// (so the optimum is unique and exists whenever the constraints are feasible) and all
// constraints built around a point x0 (b = A x0, l ≤ G x0 ≤ u, xl ≤ x0 ≤ xu), so feasible.
// A second problem with the same pattern is derived by value changes that keep it feasible:
//   P' = 2P (still ≻ 0), q' new, A' = diag(d)A, b' = d∘b (same affine set),
//   G' = diag(c)G with c > 0 and bounds c∘l − ½, c∘u + ½ (a superset of the old rows),
//   except equality rows (l = u), which become c∘l = c∘u so that no row changes type.
// The unique optimum of each problem is compared between solvers to 1e-7.
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/core/errors.hpp>

#include "random_qp_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

QpProblem make_problem(unsigned seed, Index n = 60) { return testing_support::make_random_qp(seed, n, true); }

// Same pattern, new values, still feasible (see the header comment).
QpProblem perturb(const QpProblem& p, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> sym(-1.0, 1.0), pos(0.5, 2.0);
  QpProblem r = p;
  r.P *= 2.0;
  r.q = Vector::NullaryExpr(p.q.size(), [&](Index) { return 3 * sym(rng); });
  const Vector d = Vector::NullaryExpr(p.b.size(), [&](Index) { return pos(rng); });
  const Vector c = Vector::NullaryExpr(p.l.size(), [&](Index) { return pos(rng); });
  r.A = d.asDiagonal() * p.A;
  r.b = d.cwiseProduct(p.b);
  r.G = c.asDiagonal() * p.G;
  for (Index i = 0; i < c.size(); ++i) {
    const bool eq = p.l(i) == p.u(i);
    r.l(i) = c(i) * p.l(i) - (eq ? 0.0 : 0.5);
    r.u(i) = c(i) * p.u(i) + (eq ? 0.0 : 0.5);
  }
  return r;
}

QpResult solve_fresh(const QpProblem& p) {
  QpSolver s;
  s.setup(p);
  return s.solve();
}

double max_diff(const Vector& a, const Vector& b) { return (a - b).lpNorm<Eigen::Infinity>(); }

TEST(QpUpdate, SameAnswerAsFreshSolver) {
  const QpProblem p1 = make_problem(7);
  const QpProblem p2 = perturb(p1, 8);
  ASSERT_TRUE(p1.same_pattern(p2));
  QpSolver solver;
  solver.setup(p1);
  const int after_setup = solver.numeric_factorizations();
  const QpResult r1 = solver.solve();
  ASSERT_EQ(r1.info.status, QpStatus::solved) << r1.info.message;
  EXPECT_GT(r1.info.setup_seconds, 0.0);
  EXPECT_GT(r1.info.factorizations, 0);
  const int after_first = solver.numeric_factorizations();
  EXPECT_EQ(after_first, after_setup + r1.info.factorizations);

  // backward() reuses the last factorization: the counter does not move.
  solver.backward(Vector::Ones(p1.num_variables()));
  EXPECT_EQ(solver.numeric_factorizations(), after_first);

  solver.update(p2);
  // update() keeps the analysis: the count "since setup()" is not reset and update()
  // itself does not factorize.
  EXPECT_EQ(solver.numeric_factorizations(), after_first);
  const QpResult r2 = solver.solve();
  ASSERT_EQ(r2.info.status, QpStatus::solved) << r2.info.message;
  EXPECT_GT(r2.info.setup_seconds, 0.0);  // the update's own time is reported
  EXPECT_TRUE(std::isfinite(r2.info.setup_seconds));
  EXPECT_EQ(solver.numeric_factorizations(), after_first + r2.info.factorizations);

  const QpResult fresh = solve_fresh(p2);
  ASSERT_EQ(fresh.info.status, QpStatus::solved);
  EXPECT_LE(max_diff(r2.x, fresh.x), 1e-7);
  EXPECT_NEAR(r2.info.objective, fresh.info.objective, 1e-7 * std::max(1.0, std::fabs(fresh.info.objective)));
  EXPECT_GT(max_diff(r1.x, r2.x), 1e-3) << "the perturbation should move the solution";

  // Updating back to p1 reproduces the first solution.
  solver.update(p1);
  const QpResult r3 = solver.solve();
  ASSERT_EQ(r3.info.status, QpStatus::solved);
  EXPECT_LE(max_diff(r3.x, r1.x), 1e-7);
}

// A row changing type (equality row l = u becomes two-sided) is still a valid update.
TEST(QpUpdate, RowTypeChange) {
  const QpProblem p1 = make_problem(21);
  QpProblem p2 = p1;
  Index changed = 0;
  for (Index i = 0; i < p2.l.size(); ++i)
    if (p2.l(i) == p2.u(i)) { p2.u(i) += 1.0; ++changed; }
  ASSERT_GT(changed, 0);
  QpSolver solver;
  solver.setup(p1);
  ASSERT_EQ(solver.solve().info.status, QpStatus::solved);
  solver.update(p2);
  const QpResult r = solver.solve();
  const QpResult fresh = solve_fresh(p2);
  ASSERT_EQ(r.info.status, QpStatus::solved) << r.info.message;
  ASSERT_EQ(fresh.info.status, QpStatus::solved);
  EXPECT_LE(max_diff(r.x, fresh.x), 1e-7);
}

TEST(QpWarmStart, FromPreviousSolution) {
  const QpProblem p1 = make_problem(31);
  const QpProblem p2 = perturb(p1, 32);
  QpSolver solver;
  solver.setup(p1);
  const QpResult cold = solver.solve();
  ASSERT_EQ(cold.info.status, QpStatus::solved);

  // Same problem, started at its own solution.
  solver.warm_start(cold.x, cold.y, cold.z, cold.z_bounds);
  const QpResult warm = solver.solve();
  ASSERT_EQ(warm.info.status, QpStatus::solved) << warm.info.message;
  EXPECT_LE(max_diff(warm.x, cold.x), 1e-7);
  RecordProperty("cold_iterations", cold.info.iterations);
  RecordProperty("warm_iterations", warm.info.iterations);

  // Perturbed problem, started at the old solution.
  solver.update(p2);
  solver.warm_start(cold.x, cold.y, cold.z, cold.z_bounds);
  const QpResult warm2 = solver.solve();
  const QpResult fresh = solve_fresh(p2);
  ASSERT_EQ(warm2.info.status, QpStatus::solved) << warm2.info.message;
  EXPECT_LE(max_diff(warm2.x, fresh.x), 1e-7);
}

// "A poor guess is pushed into the interior, so any finite values are safe."
TEST(QpWarmStart, PoorGuessIsSafe) {
  const QpProblem p = make_problem(41);
  const QpResult ref = solve_fresh(p);
  ASSERT_EQ(ref.info.status, QpStatus::solved);
  QpSolver solver;
  solver.setup(p);
  const Index n = p.num_variables(), me = p.num_equalities(), mi = p.num_inequalities();
  for (double v : {0.0, 1e3, -1e3}) {
    SCOPED_TRACE("guess value " + std::to_string(v));
    solver.warm_start(Vector::Constant(n, v), Vector::Constant(me, v), Vector::Constant(mi, v),
                      Vector::Constant(n, v));
    const QpResult r = solver.solve();
    ASSERT_EQ(r.info.status, QpStatus::solved) << r.info.message;
    EXPECT_LE(max_diff(r.x, ref.x), 1e-7);
  }
}

TEST(QpWarmStart, WrongSizesThrow) {
  const QpProblem p = make_problem(51);
  QpSolver solver;
  solver.setup(p);
  const Index n = p.num_variables(), me = p.num_equalities(), mi = p.num_inequalities();
  const Vector x = Vector::Zero(n), y = Vector::Zero(me), z = Vector::Zero(mi);
  EXPECT_THROW(solver.warm_start(Vector::Zero(n + 1), y, z, x), InputError);
  EXPECT_THROW(solver.warm_start(x, Vector::Zero(me + 1), z, x), InputError);
  EXPECT_THROW(solver.warm_start(x, y, Vector::Zero(mi - 1), x), InputError);
  EXPECT_THROW(solver.warm_start(x, y, z, Vector::Zero(n - 1)), InputError);
  Vector bad = x;
  bad(0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solver.warm_start(bad, y, z, x), InputError);
  // The solver is still usable afterwards.
  EXPECT_EQ(solver.solve().info.status, QpStatus::solved);
}

}  // namespace
}  // namespace lcprelax
