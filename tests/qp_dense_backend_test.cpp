// The dense KKT backend of the interior-point QP (QpSettings::kkt_backend = dense,
// sparse/dense_ldlt.hpp) against CHOLMOD, and the automatic backend selection.
//
// - Small Maros–Meszaros problems and seeded random QPs (tests/random_qp_support.hpp):
//   both backends solve, the recomputed KKT residuals of each result are ≤ kResidual
//   (definitions of qp_settings.hpp, ∞-norms, unscaled; eps_abs = 1e-9 plus the roundoff
//   of our recomputation, as in qp_maros_meszaros_test.cpp), the objectives agree, and on
//   the strictly convex random QPs (unique solution) so do x, y and z.
// - backward() with the dense backend matches central finite differences (step 1e-5,
//   tolerance 1e-5·(1 + |fd|)) and CHOLMOD's backward(), with no new factorization.
// - An infeasible problem still ends primal_infeasible with the dense backend.
// - automatic: dense iff n + me + mi ≤ dense_max_kkt (QpInfo::kkt_backend), both ways.
#include "random_qp_support.hpp"

#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kResidual = 2e-9;  // eps_abs = 1e-9 + roundoff of the recomputation

QpSettings with(KktBackend b, double eps = 1e-9) {
  QpSettings s;
  s.kkt_backend = b;
  s.eps_abs = eps;
  return s;
}

double dist(double v, double lo, double hi) { return std::max({lo - v, v - hi, 0.0}); }
long double support(double z, double lo, double hi) {  // u z⁺ + l z⁻, 0 for z = 0
  return z > 0 ? static_cast<long double>(hi) * z : z < 0 ? static_cast<long double>(lo) * z : 0.0L;
}

// max(primal residual, dual residual, duality gap) of qp_settings.hpp at r.
double kkt_residual(const QpProblem& p, const QpResult& r) {
  const Vector Px = p.P.selfadjointView<Eigen::Upper>() * r.x, Gx = p.G * r.x;
  double res = p.A.rows() ? (p.A * r.x - p.b).lpNorm<Eigen::Infinity>() : 0.0;
  for (Index i = 0; i < Gx.size(); ++i) res = std::max(res, dist(Gx(i), p.l(i), p.u(i)));
  for (Index j = 0; j < r.x.size(); ++j) res = std::max(res, dist(r.x(j), p.xl(j), p.xu(j)));
  const Vector stat = Px + p.q + p.A.transpose() * r.y + p.G.transpose() * r.z + r.z_bounds;
  res = std::max(res, stat.lpNorm<Eigen::Infinity>());
  long double g = static_cast<long double>(r.x.dot(Px)) + r.x.dot(p.q) + p.b.dot(r.y);
  for (Index j = 0; j < r.x.size(); ++j) g += support(r.z_bounds(j), p.xl(j), p.xu(j));
  for (Index i = 0; i < r.z.size(); ++i) g += support(r.z(i), p.l(i), p.u(i));
  return std::max(res, static_cast<double>(std::fabs(g)));
}

QpResult solve(const QpProblem& p, const QpSettings& s) {
  QpSolver solver(s);
  solver.setup(p);
  return solver.solve();
}

void expect_same_solution(const QpProblem& p, bool unique) {
  const QpResult c = solve(p, with(KktBackend::cholmod)), d = solve(p, with(KktBackend::dense));
  ASSERT_EQ(c.info.status, QpStatus::solved) << to_string(c.info.status) << ": " << c.info.message;
  ASSERT_EQ(d.info.status, QpStatus::solved) << to_string(d.info.status) << ": " << d.info.message;
  EXPECT_EQ(c.info.kkt_backend, KktBackend::cholmod);
  EXPECT_EQ(d.info.kkt_backend, KktBackend::dense);
  EXPECT_LE(kkt_residual(p, c), kResidual);
  EXPECT_LE(kkt_residual(p, d), kResidual);
  EXPECT_NEAR(d.info.objective, c.info.objective, 1e-8 * std::max(1.0, std::fabs(c.info.objective)));
  if (unique) {
    const double scale = 1.0 + c.x.lpNorm<Eigen::Infinity>();
    EXPECT_LT((d.x - c.x).lpNorm<Eigen::Infinity>(), 1e-6 * scale);
    if (c.y.size()) {
      EXPECT_LT((d.y - c.y).lpNorm<Eigen::Infinity>(), 1e-5 * (1.0 + c.y.lpNorm<Eigen::Infinity>()));
    }
    if (c.z.size()) {
      EXPECT_LT((d.z - c.z).lpNorm<Eigen::Infinity>(), 1e-5 * (1.0 + c.z.lpNorm<Eigen::Infinity>()));
    }
  }
}

class DenseMarosMeszaros : public ::testing::TestWithParam<std::string> {};

TEST_P(DenseMarosMeszaros, SameOptimumAsCholmod) {
  const io::QpsModel m = io::read_qps(std::string(LCPRELAX_TEST_DATA_DIR) + "/maros_meszaros/" + GetParam() + ".qps");
  expect_same_solution(m.problem, /*unique=*/false);  // LPs and singular P: x need not be unique
}

INSTANTIATE_TEST_SUITE_P(Small, DenseMarosMeszaros,
                         ::testing::Values("HS21", "HS35", "HS35MOD", "HS51", "HS76", "HS118", "HS268", "GENHS28",
                                           "LOTSCHD", "QPTEST", "TAME", "ZECEVIC2", "QAFIRO", "DUALC1", "QADLITTL"));

class DenseRandom : public ::testing::TestWithParam<unsigned> {};

TEST_P(DenseRandom, SameSolutionAsCholmod) {
  for (Index n : {4, 12, 30})
    for (bool eq : {false, true}) {
      SCOPED_TRACE("n " + std::to_string(n) + (eq ? " with" : " without") + " equality rows");
      expect_same_solution(testing_support::make_random_qp(GetParam(), n, eq), /*unique=*/true);  // P ≻ 0
    }
}

INSTANTIATE_TEST_SUITE_P(Seeds, DenseRandom, ::testing::Values(1u, 2u, 3u, 4u, 5u));

// Strictly convex feasible QP with 2 equalities, 4 inequality rows and 4 bounds whose active
// set is checked non-degenerate; ℓ = w_xᵀx + w_yᵀy + w_zᵀz.
struct Case {
  QpProblem p{6};
  Vector wx, wy, wz;
};

Case fd_case(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  Case c;
  QpProblem& p = c.p;
  const Index n = 6;
  const DenseMatrix B = DenseMatrix::NullaryExpr(n, n, [&] { return N(rng); });
  const DenseMatrix P = B.transpose() * B / n + 2.0 * DenseMatrix::Identity(n, n);
  p.P = DenseMatrix(P.triangularView<Eigen::Upper>()).sparseView();
  p.q = 3.0 * Vector::NullaryExpr(n, [&] { return N(rng); });
  // Feasible by construction: x0 inside the bounds below, b = A x0, l < G x0 < u.
  const Vector x0 = Vector::NullaryExpr(n, [&] { return std::clamp(0.1 * N(rng), -0.15, 0.25); });
  p.A = DenseMatrix(DenseMatrix::NullaryExpr(2, n, [&] { return N(rng); })).sparseView();
  p.b = p.A * x0;
  p.G = DenseMatrix(DenseMatrix::NullaryExpr(4, n, [&] { return N(rng); })).sparseView();
  const Vector g0 = p.G * x0;
  p.l = g0 + (Vector(4) << -0.3, -kInf, -0.2, -0.5).finished();
  p.u = g0 + (Vector(4) << 0.4, 0.1, kInf, 0.5).finished();
  p.xl(0) = -0.2;
  p.xu(1) = 0.3;
  p.xl(2) = -1.0;
  p.xu(2) = 1.0;
  c.wx = Vector::NullaryExpr(n, [&] { return N(rng); });
  c.wy = Vector::NullaryExpr(2, [&] { return N(rng); });
  c.wz = Vector::NullaryExpr(4, [&] { return N(rng); });
  return c;
}

double loss(const Case& c, const QpProblem& p) {
  const QpResult r = solve(p, with(KktBackend::dense, 1e-12));
  EXPECT_EQ(r.info.status, QpStatus::solved) << to_string(r.info.status) << ": " << r.info.message;
  return c.wx.dot(r.x) + c.wy.dot(r.y) + c.wz.dot(r.z);
}

class DenseBackward : public ::testing::TestWithParam<unsigned> {};

TEST_P(DenseBackward, MatchesCentralDifferencesAndCholmod) {
  const Case c = fd_case(GetParam());
  QpSolver dense(with(KktBackend::dense, 1e-12)), cholmod(with(KktBackend::cholmod, 1e-12));
  dense.setup(c.p);
  cholmod.setup(c.p);
  const QpResult& r = dense.solve();
  ASSERT_EQ(r.info.status, QpStatus::solved) << to_string(r.info.status) << ": " << r.info.message;
  ASSERT_EQ(r.info.kkt_backend, KktBackend::dense);
  ASSERT_EQ(cholmod.solve().info.status, QpStatus::solved);
  int active = 0;
  const Vector Gx = c.p.G * r.x;
  for (Index i = 0; i < Gx.size(); ++i) {
    const double slack = std::min(c.p.u(i) - Gx(i), Gx(i) - c.p.l(i));
    ASSERT_TRUE(std::abs(r.z(i)) > 1e-3 || slack > 1e-3) << "degenerate row " << i;
    active += std::abs(r.z(i)) > 1e-3;
  }
  for (Index j = 0; j < r.x.size(); ++j) {
    const double slack = std::min(c.p.xu(j) - r.x(j), r.x(j) - c.p.xl(j));
    ASSERT_TRUE(std::abs(r.z_bounds(j)) > 1e-3 || slack > 1e-3) << "degenerate bound " << j;
    active += std::abs(r.z_bounds(j)) > 1e-3;
  }
  EXPECT_GT(active, 0) << "the case must have an active constraint";

  const int factorizations = dense.numeric_factorizations();
  const QpGradient g = dense.backward(c.wx, c.wy, c.wz);
  EXPECT_EQ(dense.numeric_factorizations(), factorizations) << "backward() refactorized";
  const QpGradient gc = cholmod.backward(c.wx, c.wy, c.wz);
  EXPECT_LT((g.dq - gc.dq).lpNorm<Eigen::Infinity>(), 1e-7 * (1.0 + gc.dq.lpNorm<Eigen::Infinity>()));
  EXPECT_LT((DenseMatrix(g.dG) - DenseMatrix(gc.dG)).lpNorm<Eigen::Infinity>(), 1e-6);

  const double h = 1e-5;
  auto fd = [&](auto&& slot) {
    Case plus = c, minus = c;
    slot(plus.p) += h;
    slot(minus.p) -= h;
    return (loss(c, plus.p) - loss(c, minus.p)) / (2 * h);
  };
  auto near = [](double f, double a, const std::string& what) { EXPECT_NEAR(f, a, 1e-5 * (1 + std::abs(f))) << what; };
  for (Index i = 0; i < c.p.q.size(); ++i) near(fd([i](QpProblem& d) -> double& { return d.q(i); }), g.dq(i), "dq");
  for (Index i = 0; i < c.p.b.size(); ++i) near(fd([i](QpProblem& d) -> double& { return d.b(i); }), g.db(i), "db");
  for (Index i = 0; i < c.p.l.size(); ++i) {
    if (std::isfinite(c.p.l(i))) near(fd([i](QpProblem& d) -> double& { return d.l(i); }), g.dl(i), "dl");
    if (std::isfinite(c.p.u(i))) near(fd([i](QpProblem& d) -> double& { return d.u(i); }), g.du(i), "du");
  }
  for (Index k = 0; k < c.p.P.nonZeros(); ++k)
    near(fd([k](QpProblem& d) -> double& { return d.P.valuePtr()[k]; }), g.dP.valuePtr()[k], "dP");
  for (Index k = 0; k < c.p.G.nonZeros(); ++k)
    near(fd([k](QpProblem& d) -> double& { return d.G.valuePtr()[k]; }), g.dG.valuePtr()[k], "dG");
}

INSTANTIATE_TEST_SUITE_P(Seeds, DenseBackward, ::testing::Values(1u, 2u, 3u));

// x ≥ 1 and x ≤ 0 as two rows of G: no feasible point.
TEST(DenseBackend, InfeasibleProblemIsReportedInfeasible) {
  QpProblem p(1);
  p.P = DenseMatrix::Identity(1, 1).sparseView();
  p.G = DenseMatrix::Ones(2, 1).sparseView();
  p.l = (Vector(2) << 1, -kInf).finished();
  p.u = (Vector(2) << kInf, 0).finished();
  const QpResult r = solve(p, with(KktBackend::dense));
  EXPECT_EQ(r.info.status, QpStatus::primal_infeasible) << r.info.message;
  EXPECT_EQ(r.info.kkt_backend, KktBackend::dense);
  EXPECT_NEAR((p.G.transpose() * r.z)(0) + r.z_bounds(0), 0.0, 1e-7);  // Gᵀz + z_b = 0
  EXPECT_LT(p.u(1) * std::max(r.z(1), 0.0) + p.l(0) * std::min(r.z(0), 0.0), -1e-3);  // support < 0
}

TEST(DenseBackend, AutomaticPicksDenseUpToTheThreshold) {
  EXPECT_EQ(QpSettings{}.kkt_backend, KktBackend::automatic);
  EXPECT_GT(QpSettings{}.dense_max_kkt, 0);
  // make_random_qp(seed, n, false): n variables, n/6 rows of A, n/2 rows of G → N = 24 + 4 + 12.
  const QpProblem p = testing_support::make_random_qp(9, 24, false);
  const int N = static_cast<int>(p.num_variables() + p.num_equalities() + p.num_inequalities());
  ASSERT_EQ(N, 40);
  QpSettings s;
  for (int threshold : {N - 1, N, N + 1, 0}) {
    s.dense_max_kkt = threshold;
    const QpResult r = solve(p, s);
    ASSERT_EQ(r.info.status, QpStatus::solved) << r.info.message;
    EXPECT_EQ(r.info.kkt_backend, N <= threshold ? KktBackend::dense : KktBackend::cholmod) << "threshold " << threshold;
  }
  // With the default threshold: a tiny problem goes dense, a large one stays on CHOLMOD.
  EXPECT_EQ(solve(testing_support::make_random_qp(3, 6, true), QpSettings{}).info.kkt_backend, KktBackend::dense);
  const QpProblem big = testing_support::make_random_qp(3, 400, true);
  ASSERT_GT(big.num_variables() + big.num_equalities() + big.num_inequalities(), QpSettings{}.dense_max_kkt);
  EXPECT_EQ(solve(big, QpSettings{}).info.kkt_backend, KktBackend::cholmod);

  s.dense_max_kkt = -1;
  EXPECT_FALSE(s.validation_error().empty());
  EXPECT_THROW(QpSolver{s}, InputError);
}

}  // namespace
}  // namespace lcprelax
