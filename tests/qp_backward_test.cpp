// The adjoint backward pass against central finite differences, for every data block.
//
// ℓ(x*, y*, z*) = w_xᵀx* + w_yᵀy* + w_zᵀz* on seeded random strictly convex QPs with
// active and inactive row and bound constraints (non-degenerate: active constraints have
// multipliers well away from 0, inactive ones slacks well away from 0). Each datum d is
// perturbed by ±h and ∂ℓ/∂d ≈ (ℓ(d + h) − ℓ(d − h)) / 2h is compared with backward().
// Also checked: backward() performs no numeric factorization.
#include <lcprelax/kkt/qp_solver.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Case {
  QpProblem problem;
  Vector wx, wy, wz;
};

Case random_case(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  const Index n = 8, ma = 2, mi = 5;
  Case c{QpProblem(n), Vector(n), Vector(ma), Vector(mi)};
  QpProblem& p = c.problem;
  DenseMatrix B = DenseMatrix::NullaryExpr(n, n, [&] { return N(rng); });
  DenseMatrix P = B.transpose() * B / n + DenseMatrix::Identity(n, n);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j)
      if (std::abs(i - j) > 2) P(i, j) = 0.0;  // banded: a sparse pattern
  P += 3.0 * DenseMatrix::Identity(n, n);       // keep it positive definite
  p.P = DenseMatrix(P.triangularView<Eigen::Upper>()).sparseView();
  p.q = 3.0 * Vector::NullaryExpr(n, [&] { return N(rng); });
  DenseMatrix A = DenseMatrix::NullaryExpr(ma, n, [&] { return N(rng); });
  p.A = A.sparseView();
  p.b = Vector::NullaryExpr(ma, [&] { return N(rng); });
  DenseMatrix G = DenseMatrix::NullaryExpr(mi, n, [&] { return N(rng); });
  p.G = G.sparseView();
  p.l = Vector::Constant(mi, -kInf);
  p.u = Vector::Constant(mi, kInf);
  p.l(0) = -0.3;
  p.u(0) = 0.4;      // two-sided
  p.u(1) = 0.1;      // upper only
  p.l(2) = -0.2;     // lower only
  p.l(3) = -0.5;
  p.u(3) = 0.5;
  p.u(4) = 2.0;
  p.xl = Vector::Constant(n, -kInf);
  p.xu = Vector::Constant(n, kInf);
  p.xl(0) = -0.2;
  p.xu(1) = 0.3;
  p.xl(2) = -1.0;
  p.xu(2) = 1.0;
  c.wx = Vector::NullaryExpr(n, [&] { return N(rng); });
  c.wy = Vector::NullaryExpr(ma, [&] { return N(rng); });
  c.wz = Vector::NullaryExpr(mi, [&] { return N(rng); });
  return c;
}

QpSettings tight() {
  QpSettings s;
  s.eps_abs = 1e-12;
  s.max_iter = 400;
  return s;
}

double loss(const Case& c, const QpProblem& p) {
  QpSolver solver(tight());
  solver.setup(p);
  const QpResult& r = solver.solve();
  EXPECT_TRUE(r.info.status == QpStatus::solved || r.info.status == QpStatus::solved_inaccurate)
      << to_string(r.info.status);
  return c.wx.dot(r.x) + c.wy.dot(r.y) + c.wz.dot(r.z);
}

// Central difference of the loss in one scalar datum reached through `slot`.
double central_difference(const Case& c, const std::function<double&(QpProblem&)>& slot, double h) {
  QpProblem plus = c.problem, minus = c.problem;
  slot(plus) += h;
  slot(minus) -= h;
  return (loss(c, plus) - loss(c, minus)) / (2.0 * h);
}

void expect_close(double fd, double adj, const std::string& what) {
  EXPECT_NEAR(fd, adj, 1e-5 * (1.0 + std::abs(fd))) << what;
}

class QpBackward : public ::testing::TestWithParam<unsigned> {};

TEST_P(QpBackward, MatchesCentralDifferences) {
  const Case c = random_case(GetParam());
  QpSolver solver(tight());
  solver.setup(c.problem);
  const QpResult& r = solver.solve();
  ASSERT_EQ(r.info.status, QpStatus::solved) << r.info.message;

  // The case must exercise both active and inactive inequalities and be non-degenerate.
  const Vector Gx = c.problem.G * r.x;
  int active = 0, inactive = 0;
  for (Index i = 0; i < Gx.size(); ++i) {
    const double slack = std::min(c.problem.u(i) - Gx(i), Gx(i) - c.problem.l(i));
    if (std::abs(r.z(i)) > 1e-3) ++active;
    else if (slack > 1e-3) ++inactive;
    else GTEST_FAIL() << "degenerate row " << i << " in seed " << GetParam();
  }
  for (Index j = 0; j < r.x.size(); ++j) {
    const double slack = std::min(c.problem.xu(j) - r.x(j), r.x(j) - c.problem.xl(j));
    if (std::abs(r.z_bounds(j)) > 1e-3) ++active;
    else if (slack > 1e-3) ++inactive;
    else GTEST_FAIL() << "degenerate bound " << j << " in seed " << GetParam();
  }
  EXPECT_GT(active, 0);
  EXPECT_GT(inactive, 0);

  const int factorizations = solver.numeric_factorizations();
  const QpGradient g = solver.backward(c.wx, c.wy, c.wz);
  EXPECT_EQ(solver.numeric_factorizations(), factorizations) << "backward() refactorized";

  const double h = 1e-5;
  const QpProblem& p = c.problem;
  for (Index i = 0; i < p.q.size(); ++i)
    expect_close(central_difference(c, [i](QpProblem& d) -> double& { return d.q(i); }, h), g.dq(i), "dq");
  for (Index i = 0; i < p.b.size(); ++i)
    expect_close(central_difference(c, [i](QpProblem& d) -> double& { return d.b(i); }, h), g.db(i), "db");
  for (Index i = 0; i < p.l.size(); ++i) {
    if (std::isfinite(p.l(i)))
      expect_close(central_difference(c, [i](QpProblem& d) -> double& { return d.l(i); }, h), g.dl(i), "dl");
    if (std::isfinite(p.u(i)))
      expect_close(central_difference(c, [i](QpProblem& d) -> double& { return d.u(i); }, h), g.du(i), "du");
  }
  for (Index j = 0; j < p.xl.size(); ++j) {
    if (std::isfinite(p.xl(j)))
      expect_close(central_difference(c, [j](QpProblem& d) -> double& { return d.xl(j); }, h), g.dxl(j), "dxl");
    if (std::isfinite(p.xu(j)))
      expect_close(central_difference(c, [j](QpProblem& d) -> double& { return d.xu(j); }, h), g.dxu(j), "dxu");
  }
  // Matrix blocks: every stored entry, on the input's pattern (k-th stored value).
  auto check_matrix = [&](SparseMatrix QpProblem::*M, const SparseMatrix& dM, const char* name) {
    ASSERT_EQ(dM.nonZeros(), (p.*M).nonZeros()) << name;
    for (Index k = 0; k < (p.*M).nonZeros(); ++k)
      expect_close(central_difference(c, [M, k](QpProblem& d) -> double& { return (d.*M).valuePtr()[k]; }, h),
                   dM.valuePtr()[k], name);
  };
  check_matrix(&QpProblem::P, g.dP, "dP");
  check_matrix(&QpProblem::A, g.dA, "dA");
  check_matrix(&QpProblem::G, g.dG, "dG");
}

INSTANTIATE_TEST_SUITE_P(Seeds, QpBackward, ::testing::Values(1u, 2u, 3u, 4u));

// Zero gradient blocks for strictly inactive constraints: ∂ℓ/∂u_i = 0 where the row's
// upper side is not active.
TEST(QpBackwardStructure, InactiveBoundsHaveZeroGradient) {
  const Case c = random_case(7);
  QpSolver solver(tight());
  solver.setup(c.problem);
  const QpResult& r = solver.solve();
  ASSERT_EQ(r.info.status, QpStatus::solved);
  const QpGradient g = solver.backward(c.wx);
  for (Index i = 0; i < r.z.size(); ++i) {
    if (r.z(i) <= 1e-6) {
      EXPECT_NEAR(g.du(i), 0.0, 1e-6) << "row " << i;
    }
    if (r.z(i) >= -1e-6) {
      EXPECT_NEAR(g.dl(i), 0.0, 1e-6) << "row " << i;
    }
  }
}

}  // namespace
}  // namespace lcprelax
