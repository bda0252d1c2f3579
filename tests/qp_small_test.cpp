// Small hand-solved QPs: each states the problem and its solution in a comment, and every
// solve is checked on its KKT residuals as well as against the closed form.
#include <lcprelax/kkt/qp_solver.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

SparseMatrix dense_to_sparse(const DenseMatrix& M) { return M.sparseView(); }

SparseMatrix upper(const DenseMatrix& M) {
  DenseMatrix U = M.triangularView<Eigen::Upper>();
  return U.sparseView();
}

const QpResult& solve_checked(QpSolver& solver, const QpProblem& p) {
  solver.setup(p);
  const QpResult& r = solver.solve();
  EXPECT_EQ(r.info.status, QpStatus::solved) << r.info.message;
  EXPECT_LE(r.info.primal_residual, 1e-9);
  EXPECT_LE(r.info.dual_residual, 1e-9);
  EXPECT_LE(r.info.duality_gap, 1e-9);
  return r;
}

// min ½(x1² + x2²) s.t. x1 + x2 = 1  →  x = (½, ½), y = −½ (x + Aᵀy = 0).
TEST(QpSmall, EqualityOnly) {
  QpProblem p(2);
  p.P = upper(DenseMatrix::Identity(2, 2));
  p.A = dense_to_sparse((DenseMatrix(1, 2) << 1, 1).finished());
  p.b = Vector::Ones(1);
  QpSolver solver;
  const QpResult& r = solve_checked(solver, p);
  EXPECT_NEAR(r.x(0), 0.5, 1e-9);
  EXPECT_NEAR(r.x(1), 0.5, 1e-9);
  EXPECT_NEAR(r.y(0), -0.5, 1e-9);
  EXPECT_NEAR(r.info.objective, 0.25, 1e-9);
}

// min ½x² − 2x s.t. x ≤ 1  →  x = 1, z_bound = 1 (> 0: upper side active).
TEST(QpSmall, BoundsOnly) {
  QpProblem p(1);
  p.P = upper(DenseMatrix::Identity(1, 1));
  p.q << -2;
  p.xu << 1;
  QpSolver solver;
  const QpResult& r = solve_checked(solver, p);
  EXPECT_NEAR(r.x(0), 1.0, 1e-9);
  EXPECT_NEAR(r.z_bounds(0), 1.0, 1e-8);
}

// Degenerate: min ½x² s.t. x ≥ 0  →  x = 0 with a zero multiplier (weakly active). At a
// weakly active constraint the termination tests (gap x² ≤ 1e-9) bound x only by
// √1e-9 ≈ 3e-5, the usual accuracy of interior points on degenerate problems.
TEST(QpSmall, DegenerateWeaklyActive) {
  QpProblem p(1);
  p.P = upper(DenseMatrix::Identity(1, 1));
  p.xl << 0;
  QpSolver solver;
  const QpResult& r = solve_checked(solver, p);
  EXPECT_NEAR(r.x(0), 0.0, 5e-5);
  EXPECT_NEAR(r.z_bounds(0), 0.0, 5e-5);
}

// A redundant (repeated) equality row: min ½‖x‖² s.t. x1 + x2 = 1 (twice)  →  x = (½, ½),
// and y1 + y2 = −½ (the split is not unique).
TEST(QpSmall, RedundantEqualityRow) {
  QpProblem p(2);
  p.P = upper(DenseMatrix::Identity(2, 2));
  p.A = dense_to_sparse((DenseMatrix(2, 2) << 1, 1, 1, 1).finished());
  p.b = Vector::Ones(2);
  QpSolver solver;
  const QpResult& r = solve_checked(solver, p);
  EXPECT_NEAR(r.x(0), 0.5, 1e-9);
  EXPECT_NEAR(r.x(1), 0.5, 1e-9);
  EXPECT_NEAR(r.y.sum(), -0.5, 1e-8);
}

// LP (P = 0): min −x1 − x2 s.t. x1 + 2x2 ≤ 4, 3x1 + x2 ≤ 6, x ≥ 0  →  x = (1.6, 1.2),
// objective −2.8, both rows active with z = (0.4, 0.2).
TEST(QpSmall, LinearProgram) {
  QpProblem p(2);
  p.q << -1, -1;
  p.G = dense_to_sparse((DenseMatrix(2, 2) << 1, 2, 3, 1).finished());
  p.l = Vector::Constant(2, -kInf);
  p.u = (Vector(2) << 4, 6).finished();
  p.xl = Vector::Zero(2);
  QpSolver solver;
  const QpResult& r = solve_checked(solver, p);
  EXPECT_NEAR(r.x(0), 1.6, 1e-8);
  EXPECT_NEAR(r.x(1), 1.2, 1e-8);
  EXPECT_NEAR(r.info.objective, -2.8, 1e-8);
  EXPECT_NEAR(r.z(0), 0.4, 1e-8);
  EXPECT_NEAR(r.z(1), 0.2, 1e-8);
}

// Two-sided row, lower side active: min ½(x1² + x2²) s.t. 1 ≤ x1 + x2 ≤ 3  →  x = (½, ½),
// z = −½ (< 0: lower side active).
TEST(QpSmall, TwoSidedRowLowerActive) {
  QpProblem p(2);
  p.P = upper(DenseMatrix::Identity(2, 2));
  p.G = dense_to_sparse((DenseMatrix(1, 2) << 1, 1).finished());
  p.l = Vector::Constant(1, 1.0);
  p.u = Vector::Constant(1, 3.0);
  QpSolver solver;
  const QpResult& r = solve_checked(solver, p);
  EXPECT_NEAR(r.x(0), 0.5, 1e-9);
  EXPECT_NEAR(r.z(0), -0.5, 1e-8);
}

// An equality row inside G and a fixed variable: min ½‖x‖² s.t. x1 + x2 + x3 = 3 (l = u),
// x3 = 2 (xl = xu)  →  x = (½, ½, 2), z = −½, z_bound3 = −2 + ½ = −1.5.
TEST(QpSmall, EqualityRowInGAndFixedVariable) {
  QpProblem p(3);
  p.P = upper(DenseMatrix::Identity(3, 3));
  p.G = dense_to_sparse((DenseMatrix(1, 3) << 1, 1, 1).finished());
  p.l = Vector::Constant(1, 3.0);
  p.u = Vector::Constant(1, 3.0);
  p.xl(2) = p.xu(2) = 2;
  QpSolver solver;
  const QpResult& r = solve_checked(solver, p);
  EXPECT_NEAR(r.x(0), 0.5, 1e-9);
  EXPECT_NEAR(r.x(2), 2.0, 1e-9);
  EXPECT_NEAR(r.z(0), -0.5, 1e-8);
  EXPECT_NEAR(r.z_bounds(2), -1.5, 1e-8);
}

// Infeasible: x ≥ 1 and x ≤ 0 as two rows of G. Certificate: z = (−1, 1)/1 normalized,
// Gᵀz = 0 and u₂z₂⁺ + l₁z₁⁻ = 0·1 + 1·(−1) < 0.
TEST(QpSmall, PrimalInfeasible) {
  QpProblem p(1);
  p.P = upper(DenseMatrix::Identity(1, 1));
  p.G = dense_to_sparse((DenseMatrix(2, 1) << 1, 1).finished());
  p.l = (Vector(2) << 1, -kInf).finished();
  p.u = (Vector(2) << kInf, 0).finished();
  QpSolver solver;
  solver.setup(p);
  const QpResult& r = solver.solve();
  ASSERT_EQ(r.info.status, QpStatus::primal_infeasible) << r.info.message;
  EXPECT_NEAR((p.G.transpose() * r.z)(0) + r.z_bounds(0), 0.0, 1e-7);
  EXPECT_LT(p.u(1) * std::max(r.z(1), 0.0) + p.l(0) * std::min(r.z(0), 0.0), -1e-3);
}

// Unbounded: min −x1 s.t. x1 ≥ 0 (P = 0)  →  dual infeasible, certificate x = (1).
TEST(QpSmall, DualInfeasible) {
  QpProblem p(1);
  p.q << -1;
  p.xl << 0;
  QpSolver solver;
  solver.setup(p);
  const QpResult& r = solver.solve();
  ASSERT_EQ(r.info.status, QpStatus::dual_infeasible) << r.info.message;
  EXPECT_NEAR(r.x(0), 1.0, 1e-6);
}

}  // namespace
}  // namespace lcprelax
