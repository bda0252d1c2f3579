// solve_qp_batch / solve_qp_batch_backward on 40 random problems of two sparsity patterns.
//
// Problems: min ½xᵀPx + qᵀx s.t. Ax = b, l ≤ Gx ≤ u, xl ≤ x ≤ xu, P = s·(BᵀB + 0.1·I) ≻ 0,
// constraints built around a point x0 (b = A x0, l ≤ G x0 ≤ u, xl ≤ x0 ≤ xu), so each problem
// is feasible with a unique optimum. The problems of one pattern share B, A, G structurally;
// values vary by scaling P by s > 0, rows of A and G by positive factors (with b, l, u scaled
// alike, so x0 stays feasible) and drawing a new q.
//
// Checks:
// - qp_batch.hpp promises results independent of the thread count: 1 vs 2 threads must give
//   bitwise-identical x, y, z, z_bounds (compared with ==). Problems come in runs of 3 of a
//   pattern, so problem 20 (the first of thread 1 when threads = 2, set up from scratch) is an
//   update() of problem 19 when threads = 1: this compares the update and setup paths too.
// - Against independent QpSolver solves only closeness (1e-9) is asserted: a thread's
//   workspace reuses its analysis through update(), which need not be bitwise identical.
// - Batch backward: dq equals a single solver's backward dq to 1e-9 (relative to ‖dq‖∞ ∨ 1).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/kkt/qp_batch.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include "random_qp_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kProblems = 40;

// The base problem of a pattern (structure and reference values).
QpProblem make_base(unsigned seed, Index n) { return testing_support::make_random_qp(seed, n, false); }

// New values on the base's pattern; x0 stays feasible (see the header comment).
QpProblem vary(const QpProblem& base, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> sym(-1.0, 1.0), pos(0.5, 2.0);
  QpProblem p = base;
  p.P *= pos(rng);
  p.q = Vector::NullaryExpr(base.q.size(), [&](Index) { return 3 * sym(rng); });
  const Vector d = Vector::NullaryExpr(base.b.size(), [&](Index) { return pos(rng); });
  const Vector c = Vector::NullaryExpr(base.l.size(), [&](Index) { return pos(rng); });
  p.A = d.asDiagonal() * base.A;
  p.b = d.cwiseProduct(base.b);
  p.G = c.asDiagonal() * base.G;
  p.l = c.cwiseProduct(base.l);  // c > 0 keeps ±∞ infinite
  p.u = c.cwiseProduct(base.u);
  return p;
}

// Runs of 3 problems of one pattern, alternating patterns (n = 30 and n = 45).
std::vector<QpProblem> make_batch() {
  const QpProblem base[2] = {make_base(101, 30), make_base(202, 45)};
  std::vector<QpProblem> v;
  for (int k = 0; k < kProblems; ++k) v.push_back(vary(base[(k / 3) % 2], 1000 + k));
  return v;
}

std::vector<Vector> make_loss_gradients(const std::vector<QpProblem>& problems) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> sym(-1.0, 1.0);
  std::vector<Vector> g;
  for (const QpProblem& p : problems)
    g.push_back(Vector::NullaryExpr(p.num_variables(), [&](Index) { return sym(rng); }));
  return g;
}

bool bitwise_equal(const QpResult& a, const QpResult& b) {
  auto eq = [](const Vector& u, const Vector& v) { return u.size() == v.size() && (u.array() == v.array()).all(); };
  return eq(a.x, b.x) && eq(a.y, b.y) && eq(a.z, b.z) && eq(a.z_bounds, b.z_bounds);
}

double rel_diff(const Vector& a, const Vector& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1.0, b.lpNorm<Eigen::Infinity>());
}

TEST(QpBatch, PatternsAlternateInRunsOfThree) {
  const std::vector<QpProblem> v = make_batch();
  EXPECT_TRUE(v[19].same_pattern(v[20]));
  EXPECT_FALSE(v[20].same_pattern(v[21]));
  EXPECT_TRUE(v[0].same_pattern(v[6]));
}

TEST(QpBatch, ThreadCountDoesNotChangeResults) {
  const std::vector<QpProblem> problems = make_batch();
  const std::vector<QpResult> one = solve_qp_batch(problems, QpSettings{}, 1);
  const std::vector<QpResult> two = solve_qp_batch(problems, QpSettings{}, 2);
  ASSERT_EQ(one.size(), problems.size());
  ASSERT_EQ(two.size(), problems.size());
  for (int k = 0; k < kProblems; ++k) {
    SCOPED_TRACE("problem " + std::to_string(k));
    ASSERT_EQ(one[k].info.status, QpStatus::solved) << one[k].info.message;
    ASSERT_EQ(two[k].info.status, QpStatus::solved) << two[k].info.message;
    EXPECT_TRUE(bitwise_equal(one[k], two[k])) << "max |Δx| = " << (one[k].x - two[k].x).lpNorm<Eigen::Infinity>();
    EXPECT_EQ(one[k].info.iterations, two[k].info.iterations);
  }
}

TEST(QpBatch, MatchesIndependentSolves) {
  const std::vector<QpProblem> problems = make_batch();
  const std::vector<QpResult> batch = solve_qp_batch(problems, QpSettings{}, 2);
  for (int k = 0; k < kProblems; ++k) {
    SCOPED_TRACE("problem " + std::to_string(k));
    QpSolver solver;
    solver.setup(problems[k]);
    const QpResult& r = solver.solve();
    ASSERT_EQ(r.info.status, QpStatus::solved);
    ASSERT_EQ(batch[k].info.status, QpStatus::solved);
    EXPECT_LE(rel_diff(batch[k].x, r.x), 1e-9);
  }
}

TEST(QpBatch, BackwardMatchesSingleSolver) {
  const std::vector<QpProblem> problems = make_batch();
  const std::vector<Vector> dl_dx = make_loss_gradients(problems);
  std::vector<QpResult> results;
  std::vector<QpGradient> grads;
  solve_qp_batch_backward(problems, dl_dx, results, grads, QpSettings{}, 2);
  ASSERT_EQ(results.size(), problems.size());
  ASSERT_EQ(grads.size(), problems.size());
  for (int k = 0; k < kProblems; ++k) {
    SCOPED_TRACE("problem " + std::to_string(k));
    ASSERT_EQ(results[k].info.status, QpStatus::solved) << results[k].info.message;
    QpSolver solver;
    solver.setup(problems[k]);
    ASSERT_EQ(solver.solve().info.status, QpStatus::solved);
    const QpGradient g = solver.backward(dl_dx[k]);
    ASSERT_EQ(grads[k].dq.size(), g.dq.size());
    EXPECT_LE(rel_diff(grads[k].dq, g.dq), 1e-9);
    EXPECT_LE(rel_diff(grads[k].db, g.db), 1e-9);
  }
  // The gradients, too, do not depend on the thread count.
  std::vector<QpResult> results1;
  std::vector<QpGradient> grads1;
  solve_qp_batch_backward(problems, dl_dx, results1, grads1, QpSettings{}, 1);
  for (int k = 0; k < kProblems; ++k)
    EXPECT_TRUE((grads1[k].dq.array() == grads[k].dq.array()).all()) << "problem " << k;
}

// A missing loss gradient is misuse of the API: InputError naming both counts.
TEST(QpBatch, BackwardWithMissingLossGradientThrows) {
  std::vector<QpProblem> problems = make_batch();
  problems.resize(4);
  std::vector<Vector> dl_dx = make_loss_gradients(problems);
  dl_dx.resize(3);
  std::vector<QpResult> results;
  std::vector<QpGradient> grads;
  try {
    solve_qp_batch_backward(problems, dl_dx, results, grads, QpSettings{}, 2);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("3 loss gradients for 4 problems"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lcprelax
