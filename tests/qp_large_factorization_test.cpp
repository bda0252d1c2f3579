// Large-problem factorization choices of the QP solver (issue 16), on generated 2-D and 3-D
// grid problems whose fill depends strongly on the ordering:
// - CholmodLlt/CholmodLdlt with CholmodOrdering::best keep METIS or NESDIS nested
//   dissection when it predicts fewer flops than AMD (on a k×k 5-point Laplacian nested
//   dissection needs O(k³) flops: George, "Nested dissection of a regular finite element
//   mesh", SIAM J. Numer. Anal. 10(2), 1973; AMD's count is larger, measured here), and the
//   factor solves to roundoff either way;
// - QpSolver with KktOrdering::automatic (nested dissection kept) and KktOrdering::amd (the
//   former path) reach the same solution of a grid control QP (a CONT-like problem: state y
//   and control u on a 3-D grid, L y = u with the 7-point Laplacian L, bounds on both,
//   objective ½‖y − t‖² + ½β‖u‖², strongly convex so the solution is unique) to 1e-9, with
//   the smaller factor on the automatic path;
// - QpSettings::time_limit: a solve whose first factorization is predicted (analysis flops
//   at 1e9 flops/s) to end past the limit stops with time_limit before factorizing.
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/sparse/cholmod_ldlt.hpp>
#include <lcprelax/sparse/cholmod_llt.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

// Laplacian of a k×k (dims = 2, 5-point) or k×k×k (dims = 3, 7-point) grid (Dirichlet),
// plus `shift` on the diagonal; the upper triangle only or the full matrix.
SparseMatrix grid_laplacian(Index k, int dims, double shift, bool upper_only) {
  const Index m = dims == 2 ? k * k : k * k * k;
  const Index stride[3] = {1, k, k * k};
  std::vector<Triplet> t;
  for (Index v = 0; v < m; ++v) {
    t.emplace_back(v, v, 2.0 * dims + shift);
    for (int d = 0; d < dims; ++d) {
      const Index coord = (v / stride[d]) % k;
      if (coord + 1 >= k) continue;
      t.emplace_back(v, v + stride[d], -1.0);
      if (!upper_only) t.emplace_back(v + stride[d], v, -1.0);
    }
  }
  SparseMatrix L(m, m);
  L.setFromTriplets(t.begin(), t.end());
  L.makeCompressed();
  return L;
}

double relative_residual(const SparseMatrix& full, const Vector& x, const Vector& b) {
  return (full * x - b).lpNorm<Eigen::Infinity>() / b.lpNorm<Eigen::Infinity>();
}

TEST(QpLargeFactorization, LltKeepsNestedDissectionOnAGrid) {
  const Index k = 100;
  const SparseMatrix upper = grid_laplacian(k, 2, 0.0, true), full = grid_laplacian(k, 2, 0.0, false);
  sparse::CholmodLlt amd(sparse::CholmodOrdering::amd), best;
  ASSERT_TRUE(amd.analyze(upper).ok());
  ASSERT_TRUE(best.analyze(upper).ok());
  EXPECT_STREQ(amd.ordering_name(), "amd");
  const std::string kept = best.ordering_name();
  EXPECT_TRUE(kept == "metis" || kept == "nesdis") << kept;
  EXPECT_GT(amd.factor_flops(), sparse::kNestedDissectionFlops);
  EXPECT_LT(best.factor_flops(), amd.factor_flops());
  EXPECT_LT(best.factor_nnz(), amd.factor_nnz());
  Vector b = Vector::LinSpaced(k * k, -1.0, 2.0);
  for (sparse::CholmodLlt* f : {&amd, &best}) {
    ASSERT_TRUE(f->factorize(upper).ok());
    Vector x = b;
    ASSERT_TRUE(f->solve(x).ok());
    EXPECT_LT(relative_residual(full, x, b), 1e-12) << f->ordering_name();
  }
}

TEST(QpLargeFactorization, SmallMatrixStaysWithAmd) {
  // Below kNestedDissectionFlops nested dissection is not tried (its analysis costs more
  // than it can save).
  const SparseMatrix upper = grid_laplacian(10, 2, 0.0, true);
  sparse::CholmodLdlt f;
  ASSERT_TRUE(f.analyze(upper).ok());
  EXPECT_LT(f.factor_flops(), sparse::kNestedDissectionFlops);
  EXPECT_STREQ(f.ordering_name(), "amd");
}

// Grid control QP on a k×k×k grid (3-D: nested dissection's advantage over AMD is large
// there; on 2-D grids of this size AMD's factor has about as many nonzeros): x = (y, u) with
// y, u on the grid; L y − u = 0; 0 ≤ y ≤ 0.5, −0.3 ≤ u ≤ 0.3; minimize ½‖y − t‖² + ½β‖u‖²
// with a target t that the bounds cut.
QpProblem grid_control_qp(Index k) {
  const Index m = k * k * k, n = 2 * m;
  QpProblem p(n);
  std::vector<Triplet> pt;
  for (Index i = 0; i < m; ++i) {
    pt.emplace_back(i, i, 1.0);
    pt.emplace_back(m + i, m + i, 1e-2);
  }
  p.P.resize(n, n);
  p.P.setFromTriplets(pt.begin(), pt.end());
  p.q = Vector::Zero(n);
  for (Index i = 0; i < m; ++i) p.q(i) = -std::sin(0.1 * static_cast<double>(i % k)) * std::cos(0.07 * static_cast<double>(i / k)) - 0.2;
  const SparseMatrix L = grid_laplacian(k, 3, 0.0, false);
  std::vector<Triplet> at;
  for (Index c = 0; c < m; ++c)
    for (SparseMatrix::InnerIterator it(L, c); it; ++it) at.emplace_back(it.row(), c, it.value());
  for (Index i = 0; i < m; ++i) at.emplace_back(i, m + i, -1.0);
  p.A.resize(m, n);
  p.A.setFromTriplets(at.begin(), at.end());
  p.b = Vector::Zero(m);
  p.xl = Vector::Zero(n);
  p.xu = Vector::Constant(n, 0.5);
  p.xl.tail(m).setConstant(-0.3);
  p.xu.tail(m).setConstant(0.3);
  return p;
}

TEST(QpLargeFactorization, NestedDissectionPathMatchesAmdPath) {
  const QpProblem p = grid_control_qp(14);  // 5,488 variables, 2,744 equality rows
  QpSettings s;
  s.kkt_backend = KktBackend::cholmod;
  s.kkt_ordering = KktOrdering::amd;
  QpSolver amd(s);
  amd.setup(p);
  const QpResult& ra = amd.solve();
  s.kkt_ordering = KktOrdering::automatic;
  QpSolver best(s);
  best.setup(p);
  const QpResult& rb = best.solve();
  ASSERT_EQ(ra.info.status, QpStatus::solved) << ra.info.message;
  ASSERT_EQ(rb.info.status, QpStatus::solved) << rb.info.message;
  EXPECT_EQ(rb.info.kkt_form, KktForm::full);
  EXPECT_LT(rb.info.kkt_factor_nnz, ra.info.kkt_factor_nnz);
  std::printf("nnz(L): amd %ld, automatic %ld; iterations %d, %d; |x_amd - x_auto| %.2e\n", ra.info.kkt_factor_nnz,
              rb.info.kkt_factor_nnz, ra.info.iterations, rb.info.iterations, (ra.x - rb.x).lpNorm<Eigen::Infinity>());
  EXPECT_LT((ra.x - rb.x).lpNorm<Eigen::Infinity>(), 1e-9);
  EXPECT_LT(std::abs(ra.info.objective - rb.info.objective), 1e-9 * (1.0 + std::abs(ra.info.objective)));
  // Residuals of the returned point, recomputed here.
  EXPECT_LT((p.A * rb.x - p.b).lpNorm<Eigen::Infinity>(), 1e-9);
  const Vector dual = p.P.selfadjointView<Eigen::Upper>() * rb.x + p.q + p.A.transpose() * rb.y + rb.z_bounds;
  EXPECT_LT(dual.lpNorm<Eigen::Infinity>(), 1e-9);
}

TEST(QpLargeFactorization, TimeLimitStopsBeforeAFactorizationThatCannotFinish) {
  const QpProblem p = grid_control_qp(12);
  QpSettings s;
  s.kkt_backend = KktBackend::cholmod;
  s.time_limit = 1e-5;  // below the predicted first factorization (> 1e5 flops at 1e9/s)
  QpSolver solver(s);
  solver.setup(p);
  const QpResult& r = solver.solve();
  EXPECT_EQ(r.info.status, QpStatus::time_limit) << r.info.message;
  EXPECT_EQ(solver.numeric_factorizations(), 0);
  EXPECT_EQ(r.info.factorizations, 0);
  EXPECT_FALSE(has_solution(r.info.status));
}

}  // namespace
}  // namespace lcprelax
