// KluLu specifics: refactorize() with the kept pivot order, factorize_reusing_pivots()
// (reuse while the condition estimate holds, a pivoted factorization when not), numerically and structurally
// singular unsymmetric matrices, the reciprocal condition estimate, the partial-pivoting
// threshold, and moves. The
// Factorization contract (solve and transposed solve residuals on unsymmetric matrices
// with a weak diagonal, many right-hand sides, refactorization, failure statuses,
// lifecycle, empty matrix) is checked in sparse_factorization_test.cpp.
#include "factorization_test_support.hpp"

#include <lcprelax/sparse/klu_lu.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::SparseMatrix;
using lcprelax::Triplet;
using lcprelax::sparse::FactorStatus;
using lcprelax::sparse::KluLu;
using lcprelax::test::random_rhs;
using lcprelax::test::relative_residual;

// Unsymmetric, with a fixed pattern for a given n (values depend on seed and scale).
SparseMatrix unsymmetric(int n, unsigned seed, double scale = 1.0) {
  std::mt19937 pattern_gen(99);
  std::bernoulli_distribution keep(0.1);
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::vector<Triplet> t;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (i != j && !keep(pattern_gen)) continue;
      t.emplace_back(i, j, scale * (i == j ? 0.5 : 1.0) * val(gen));
    }
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

TEST(KluLu, RefactorizesWithTheKeptPivotOrder) {
  const SparseMatrix A1 = unsymmetric(60, 6);
  const SparseMatrix A2 = unsymmetric(60, 6, 1.5);  // same values scaled: pivots stay good
  KluLu f;
  ASSERT_TRUE(f.analyze(A1).ok());
  EXPECT_EQ(f.refactorize(A1).status, FactorStatus::not_analyzed);  // needs factorize()
  ASSERT_TRUE(f.factorize(A1).ok());
  ASSERT_TRUE(f.refactorize(A2).ok());
  EXPECT_EQ(f.numeric_factorizations(), 2);
  const DenseMatrix b = random_rhs(60, 1, 8);
  DenseMatrix x = b;
  ASSERT_TRUE(f.solve(x).ok());
  EXPECT_LT(relative_residual(DenseMatrix(A2), x, b), 1e-11);
  SparseMatrix other = A1;
  other.coeffRef(0, 59) += 1.0;
  if (A1.coeff(0, 59) != 0.0) other.coeffRef(1, 59) += 1.0;
  EXPECT_EQ(f.refactorize(other).status, FactorStatus::pattern_mismatch);
  SparseMatrix nan = A1;
  nan.valuePtr()[5] = std::nan("");
  EXPECT_EQ(f.refactorize(nan).status, FactorStatus::invalid_input);
  EXPECT_EQ(f.numeric_factorizations(), 2);
}

TEST(KluLu, ReusesPivotsWhileTheConditionEstimateHolds) {
  KluLu f;
  f.set_pivot_tolerance(1.0);
  const SparseMatrix A1 = unsymmetric(60, 6);
  ASSERT_TRUE(f.analyze(A1).ok());
  // No factorization held yet: a pivoted one.
  ASSERT_TRUE(f.factorize_reusing_pivots(A1, 0.1).ok());
  EXPECT_FALSE(f.reused_pivots());
  // Values scaled: the kept pivots suit them (same rcond), klu_refactor runs.
  const SparseMatrix A2 = unsymmetric(60, 6, 1.5);
  ASSERT_TRUE(f.factorize_reusing_pivots(A2, 0.1).ok());
  EXPECT_TRUE(f.reused_pivots());
  EXPECT_EQ(f.numeric_factorizations(), 2);
  const DenseMatrix b = random_rhs(60, 1, 8);
  DenseMatrix x = b;
  ASSERT_TRUE(f.solve(x).ok());
  EXPECT_LT(relative_residual(DenseMatrix(A2), x, b), 1e-11);
  // [[4, 1], [1, 3]] pivots on 4; in [[1e-9, 1], [1, 3]] that pivot is 1e-9 and the
  // refactorization's rcond collapses: the pivoted factorization runs instead.
  auto two_by_two = [](double a00) {
    SparseMatrix A(2, 2);
    const std::vector<Triplet> t{{0, 0, a00}, {1, 0, 1.0}, {0, 1, 1.0}, {1, 1, 3.0}};
    A.setFromTriplets(t.begin(), t.end());
    A.makeCompressed();
    return A;
  };
  KluLu g;
  g.set_pivot_tolerance(1.0);
  ASSERT_TRUE(g.analyze(two_by_two(4.0)).ok());
  ASSERT_TRUE(g.factorize(two_by_two(4.0)).ok());
  const SparseMatrix tiny = two_by_two(1e-9);
  ASSERT_TRUE(g.factorize_reusing_pivots(tiny, 0.1).ok());
  EXPECT_FALSE(g.reused_pivots());
  EXPECT_EQ(g.numeric_factorizations(), 3);  // the refused refactorization counts too
  DenseMatrix y = DenseMatrix::Ones(2, 1);
  ASSERT_TRUE(g.solve(y).ok());
  EXPECT_LT(relative_residual(DenseMatrix(tiny), y, DenseMatrix::Ones(2, 1)), 1e-14);
  // A pattern other than the analysed one is refused, as factorize() refuses it.
  SparseMatrix other = A1;
  other.coeffRef(0, 59) += 1.0;
  if (A1.coeff(0, 59) != 0.0) other.coeffRef(1, 59) += 1.0;
  EXPECT_EQ(f.factorize_reusing_pivots(other, 0.1).status, FactorStatus::pattern_mismatch);
}

TEST(KluLu, ReportsNumericallyAndStructurallySingularMatrices) {
  // Rows 0 and 2 are equal: numerically singular.
  DenseMatrix D(3, 3);
  D << 1, 2, 3,
       4, 5, 6,
       1, 2, 3;
  const SparseMatrix A = D.sparseView();
  KluLu f;
  ASSERT_TRUE(f.analyze(A).ok());
  const auto r = f.factorize(A);
  EXPECT_EQ(r.status, FactorStatus::singular);
  EXPECT_GE(r.pivot, 0);
  // Structurally singular: column 1 is empty.
  std::vector<Triplet> t{{0, 0, 1.0}, {1, 0, 2.0}, {2, 2, 3.0}, {1, 2, 1.0}};
  SparseMatrix S(3, 3);
  S.setFromTriplets(t.begin(), t.end());
  KluLu g;
  ASSERT_TRUE(g.analyze(S).ok());
  EXPECT_EQ(g.factorize(S).status, FactorStatus::singular);
  EXPECT_EQ(g.numeric_factorizations(), 0);
}

TEST(KluLu, EstimatesReciprocalCondition) {
  KluLu f;
  EXPECT_EQ(f.rcond(), 0.0);  // no factorization yet
  SparseMatrix I(4, 4);
  I.setIdentity();
  ASSERT_TRUE(f.analyze(I).ok());
  ASSERT_TRUE(f.factorize(I).ok());
  EXPECT_DOUBLE_EQ(f.rcond(), 1.0);
  // KLU scales rows by their largest entry, so a tiny diagonal alone is not ill-conditioned;
  // nearly dependent rows are: [1 1; 1 1+1e-10] has min|Uᵢᵢ| / max|Uᵢᵢ| ≈ 1e-10.
  DenseMatrix W(2, 2);
  W << 2, 1,
       1, 2;
  DenseMatrix N(2, 2);
  N << 1, 1,
       1, 1 + 1e-10;
  ASSERT_TRUE(f.analyze(W.sparseView()).ok());
  ASSERT_TRUE(f.factorize(W.sparseView()).ok());
  EXPECT_GT(f.rcond(), 0.5);
  ASSERT_TRUE(f.refactorize(N.sparseView()).ok());
  EXPECT_GT(f.rcond(), 1e-11);
  EXPECT_LT(f.rcond(), 1e-9);
}

TEST(KluLu, MovedFromStaysSafe) {
  KluLu f;
  const SparseMatrix E(0, 0);
  ASSERT_TRUE(f.analyze(E).ok());
  ASSERT_TRUE(f.factorize(E).ok());
  KluLu g(std::move(f));
  EXPECT_EQ(g.numeric_factorizations(), 1);
  EXPECT_EQ(f.rows(), 0);  // NOLINT(bugprone-use-after-move): moved-from stays safe
  EXPECT_EQ(f.analyze(E).status, FactorStatus::not_analyzed);
}

// The partial-pivoting threshold reaches KLU: on a matrix whose diagonal is small but
// above 0.001 of its column (ε = 0.01 against off-diagonal entries of 1), KLU's default
// threshold keeps the diagonal pivots and L gets entries of about 1/ε; with u = 1 (true
// partial pivoting) every |L_ij| ≤ 1. Both solve the system; out-of-range thresholds throw.
TEST(KluLu, PivotToleranceBoundsTheMultipliers) {
  const int n = 40;
  std::vector<Triplet> t;
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> val(0.5, 1.0);
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 0.01);
    t.emplace_back((i + 1) % n, i, val(gen));
    t.emplace_back((i + 7) % n, i, -val(gen));
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  const DenseMatrix b = random_rhs(n, 1, 3);
  auto largest_multiplier = [&](double u) {
    KluLu lu;
    if (u > 0) lu.set_pivot_tolerance(u);
    EXPECT_TRUE(lu.analyze(A).ok());
    EXPECT_TRUE(lu.factorize(A).ok());
    DenseMatrix x = b;
    EXPECT_TRUE(lu.solve(x).ok());
    EXPECT_LT(relative_residual(DenseMatrix(A), x, b), 1e-12) << "u = " << u;
    KluLu::Factors f;
    EXPECT_TRUE(lu.extract(f));
    double largest = 0.0;
    for (int j = 0; j < f.n; ++j)
      for (int k = f.Lp[j]; k < f.Lp[j + 1]; ++k)
        if (f.Li[k] != j) largest = std::max(largest, std::abs(f.Lx[k]));
    return largest;
  };
  EXPECT_EQ(KluLu().pivot_tolerance(), 0.001);  // KLU's own default until set
  EXPECT_GT(largest_multiplier(-1.0), 10.0);
  EXPECT_LE(largest_multiplier(1.0), 1.0 + 1e-12);
  KluLu lu;
  EXPECT_THROW(lu.set_pivot_tolerance(0.0), std::invalid_argument);
  EXPECT_THROW(lu.set_pivot_tolerance(1.5), std::invalid_argument);
  EXPECT_THROW(lu.set_pivot_tolerance(std::nan("")), std::invalid_argument);
  lu.set_pivot_tolerance(0.25);
  EXPECT_EQ(lu.pivot_tolerance(), 0.25);
}

}  // namespace
