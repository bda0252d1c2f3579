// CholmodLdlt: simplicial LDLᵀ of seeded random quasi-definite KKT matrices
// K = [H Bᵀ; B −D] — residuals, inertia, numeric refactorization on a fixed pattern,
// failure statuses (pattern mismatch, zero pivot, NaN), dynamic regularization,
// clone_analysis across threads, and the lifecycle errors.
#include "factorization_test_support.hpp"

#include <lcprelax/sparse/cholmod_ldlt.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <thread>
#include <vector>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::SparseMatrix;
using lcprelax::Triplet;
using lcprelax::Vector;
using lcprelax::sparse::CholmodLdlt;
using lcprelax::sparse::FactorStatus;
using lcprelax::test::random_rhs;

// Backward error of K X = B (K full).
double residual(const SparseMatrix& K, const DenseMatrix& X, const DenseMatrix& B) {
  return lcprelax::test::relative_residual(DenseMatrix(K), X, B);
}

// Full symmetric K = [H Bᵀ; B −D] with H SPD (n×n), D diagonal positive (m×m), B m×n.
// `scale` multiplies every value so that two seeds/scales give one pattern, new values.
SparseMatrix quasi_definite(int n, int m, unsigned seed, double scale = 1.0) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::bernoulli_distribution keep(0.15);
  std::mt19937 pattern_gen(1234);  // the pattern depends on n and m only
  std::vector<Triplet> t;
  std::vector<double> row_sum(n, 0.0);
  for (int j = 0; j < n; ++j) {
    for (int i = j + 1; i < n; ++i) {
      if (!keep(pattern_gen)) continue;
      const double v = scale * val(gen);
      t.emplace_back(i, j, v);
      t.emplace_back(j, i, v);
      row_sum[i] += std::abs(v);
      row_sum[j] += std::abs(v);
    }
  }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, row_sum[i] + scale * (1.0 + std::abs(val(gen))));
  for (int r = 0; r < m; ++r) {
    for (int c = 0; c < n; ++c) {
      if (!keep(pattern_gen) && c != r % n) continue;
      const double v = scale * val(gen);
      t.emplace_back(n + r, c, v);
      t.emplace_back(c, n + r, v);
    }
    t.emplace_back(n + r, n + r, -scale * (0.1 + std::abs(val(gen))));
  }
  SparseMatrix K(n + m, n + m);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

SparseMatrix upper(const SparseMatrix& K) { return K.triangularView<Eigen::Upper>(); }



TEST(CholmodLdlt, SolvesRandomQuasiDefiniteSystems) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const SparseMatrix K = quasi_definite(40, 25, seed);
    CholmodLdlt f;
    ASSERT_TRUE(f.analyze(upper(K)).ok());
    ASSERT_TRUE(f.factorize(upper(K)).ok());
    const DenseMatrix b = random_rhs(65, 1, seed + 100);
    DenseMatrix x = b;
    ASSERT_TRUE(f.solve(x).ok());
    EXPECT_LT(residual(K, x, b), 1e-14) << "seed " << seed;
    EXPECT_EQ(f.rows(), 65);
  }
}

TEST(CholmodLdlt, IgnoresTheLowerTriangleAndAcceptsUncompressedInput) {
  const SparseMatrix K = quasi_definite(30, 10, 7);
  SparseMatrix full = K;
  full.uncompress();
  CholmodLdlt f;
  ASSERT_TRUE(f.analyze(full).ok());
  ASSERT_TRUE(f.factorize(full).ok());
  const DenseMatrix b = random_rhs(40, 1, 8);
  DenseMatrix x = b;
  ASSERT_TRUE(f.solve(x).ok());
  EXPECT_LT(residual(K, x, b), 1e-14);
}

TEST(CholmodLdlt, SolvesManyRightHandSidesInPlace) {
  const SparseMatrix K = quasi_definite(50, 20, 11);
  CholmodLdlt f;
  ASSERT_TRUE(f.analyze(upper(K)).ok());
  ASSERT_TRUE(f.factorize(upper(K)).ok());
  const DenseMatrix B = random_rhs(70, 7, 12);
  DenseMatrix X = B;
  ASSERT_TRUE(f.solve(X).ok());
  EXPECT_LT(residual(K, X, B), 1e-14);
  // A block of a taller matrix: leading dimension 75 ≠ 70 rows.
  DenseMatrix tall = DenseMatrix::Constant(75, 7, 42.0);
  tall.topRows(70) = B;
  ASSERT_TRUE(f.solve(tall.topRows(70)).ok());
  EXPECT_EQ((tall.topRows(70) - X).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(tall.bottomRows(5).cwiseAbs().minCoeff(), 42.0);  // rows below untouched
  // Zero columns: a no-op that succeeds.
  DenseMatrix empty(70, 0);
  EXPECT_TRUE(f.solve(empty).ok());
  DenseMatrix wrong(69, 1);
  EXPECT_EQ(f.solve(wrong).status, FactorStatus::invalid_input);
}

TEST(CholmodLdlt, InertiaCountsPrimalPositiveAndDualNegativePivots) {
  const SparseMatrix K = quasi_definite(35, 15, 21);
  CholmodLdlt f;
  ASSERT_TRUE(f.analyze(upper(K)).ok());
  ASSERT_TRUE(f.factorize(upper(K)).ok());
  EXPECT_EQ(f.inertia().positive, 35);
  EXPECT_EQ(f.inertia().negative, 15);
  EXPECT_EQ(f.inertia().zero, 0);
}

TEST(CholmodLdlt, RefactorizesNewValuesWithoutNewAnalysis) {
  const SparseMatrix K1 = quasi_definite(30, 12, 31);
  const SparseMatrix K2 = quasi_definite(30, 12, 32, 3.0);
  ASSERT_EQ(K1.nonZeros(), K2.nonZeros());
  CholmodLdlt f;
  ASSERT_TRUE(f.analyze(upper(K1)).ok());
  const long predicted = f.factor_nnz();
  EXPECT_GE(predicted, upper(K1).nonZeros());
  EXPECT_EQ(f.numeric_factorizations(), 0);
  ASSERT_TRUE(f.factorize(upper(K1)).ok());
  EXPECT_EQ(f.numeric_factorizations(), 1);
  EXPECT_EQ(f.factor_nnz(), predicted);  // simplicial: the symbolic count is exact
  ASSERT_TRUE(f.factorize(upper(K2)).ok());
  EXPECT_EQ(f.numeric_factorizations(), 2);
  const DenseMatrix b = random_rhs(42, 2, 33);
  DenseMatrix x = b;
  ASSERT_TRUE(f.solve(x).ok());
  EXPECT_LT(residual(K2, x, b), 1e-14);
}

TEST(CholmodLdlt, RejectsAnotherPattern) {
  const SparseMatrix K = quasi_definite(20, 5, 41);
  CholmodLdlt f;
  ASSERT_TRUE(f.analyze(upper(K)).ok());
  SparseMatrix other = upper(K);
  other.coeffRef(0, 24) += 0.5;  // one new entry in the upper triangle
  if (K.coeff(0, 24) != 0.0) other.coeffRef(0, 23) += 0.5;
  const auto r = f.factorize(other);
  EXPECT_EQ(r.status, FactorStatus::pattern_mismatch);
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(f.factorize(upper(quasi_definite(20, 6, 41))).status, FactorStatus::pattern_mismatch);
  EXPECT_EQ(f.numeric_factorizations(), 0);
}

// diag(2, 0, 3) with the zero stored: the zero pivot is column 1 whatever the ordering.
SparseMatrix singular_diagonal() {
  std::vector<Triplet> t{{0, 0, 2.0}, {1, 1, 0.0}, {2, 2, 3.0}, {0, 2, 1.0}};
  SparseMatrix A(3, 3);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

TEST(CholmodLdlt, ReportsZeroPivotWithoutRegularization) {
  CholmodLdlt f;
  ASSERT_TRUE(f.analyze(singular_diagonal()).ok());
  const auto r = f.factorize(singular_diagonal());
  EXPECT_EQ(r.status, FactorStatus::zero_pivot);
  EXPECT_EQ(r.pivot, 1);
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(f.numeric_factorizations(), 0);
  DenseMatrix x = DenseMatrix::Ones(3, 1);
  EXPECT_EQ(f.solve(x).status, FactorStatus::not_analyzed);  // no usable factor
  // A later nonsingular matrix with the same pattern factorizes fine.
  SparseMatrix good = singular_diagonal();
  good.coeffRef(1, 1) = -4.0;
  ASSERT_TRUE(f.factorize(good).ok());
  EXPECT_EQ(f.inertia().negative, 1);
}

TEST(CholmodLdlt, DynamicRegularizationReplacesTheZeroPivot) {
  CholmodLdlt f(1e-8);
  ASSERT_TRUE(f.analyze(singular_diagonal()).ok());
  ASSERT_TRUE(f.factorize(singular_diagonal()).ok());
  EXPECT_EQ(f.inertia().positive, 3);  // 0 is replaced by +dbound
  DenseMatrix x(3, 1);
  x << 0.0, 1e-8, 0.0;
  ASSERT_TRUE(f.solve(x).ok());
  EXPECT_NEAR(x(1, 0), 1.0, 1e-12);
}

TEST(CholmodLdlt, RejectsNonFiniteValues) {
  const SparseMatrix K = upper(quasi_definite(10, 4, 51));
  CholmodLdlt f;
  ASSERT_TRUE(f.analyze(K).ok());
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    SparseMatrix Kb = K;
    Kb.valuePtr()[Kb.nonZeros() / 2] = bad;
    EXPECT_EQ(f.factorize(Kb).status, FactorStatus::invalid_input);
  }
  EXPECT_EQ(f.numeric_factorizations(), 0);
}

TEST(CholmodLdlt, CloneAnalysisFactorizesOnAnotherThread) {
  const SparseMatrix K1 = upper(quasi_definite(60, 30, 61));
  const SparseMatrix K2 = upper(quasi_definite(60, 30, 62, 2.0));
  CholmodLdlt f;
  ASSERT_TRUE(f.analyze(K1).ok());
  CholmodLdlt before = f.clone_analysis();  // cloned from a symbolic factor
  ASSERT_TRUE(f.factorize(K1).ok());
  CholmodLdlt after = f.clone_analysis();  // cloned from a numeric factor
  EXPECT_EQ(after.rows(), 90);
  DenseMatrix x_clone = DenseMatrix::Zero(90, 1);
  EXPECT_EQ(after.solve(x_clone).status, FactorStatus::not_analyzed);  // no numeric copy

  const DenseMatrix b = random_rhs(90, 1, 63);
  DenseMatrix x_before = b, x_after = b;
  std::thread worker([&] {
    ASSERT_TRUE(before.factorize(K2).ok());
    ASSERT_TRUE(before.solve(x_before).ok());
  });
  ASSERT_TRUE(after.factorize(K2).ok());
  ASSERT_TRUE(after.solve(x_after).ok());
  worker.join();
  ASSERT_TRUE(f.factorize(K2).ok());
  DenseMatrix x = b;
  ASSERT_TRUE(f.solve(x).ok());
  // Same ordering, same arithmetic: identical solutions.
  EXPECT_EQ((x - x_before).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((x - x_after).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(before.numeric_factorizations(), 1);
  EXPECT_EQ(after.factor_nnz(), f.factor_nnz());
}

TEST(CholmodLdlt, LifecycleErrorsAndMoves) {
  CholmodLdlt f;
  DenseMatrix x = DenseMatrix::Ones(3, 1);
  EXPECT_EQ(f.solve(x).status, FactorStatus::not_analyzed);
  EXPECT_EQ(f.factorize(singular_diagonal()).status, FactorStatus::not_analyzed);
  EXPECT_EQ(f.rows(), 0);
  EXPECT_EQ(f.analyze(SparseMatrix(3, 4)).status, FactorStatus::invalid_input);

  SparseMatrix good = singular_diagonal();
  good.coeffRef(1, 1) = 5.0;
  ASSERT_TRUE(f.analyze(good).ok());
  ASSERT_TRUE(f.factorize(good).ok());
  ASSERT_TRUE(f.solve(x).ok());
  CholmodLdlt g(std::move(f));
  EXPECT_EQ(g.numeric_factorizations(), 1);
  DenseMatrix y = DenseMatrix::Ones(3, 1);
  ASSERT_TRUE(g.solve(y).ok());
  EXPECT_EQ((x - y).cwiseAbs().maxCoeff(), 0.0);
  CholmodLdlt h;
  h = std::move(g);
  y.setOnes();
  ASSERT_TRUE(h.solve(y).ok());
  EXPECT_EQ((x - y).cwiseAbs().maxCoeff(), 0.0);
}

TEST(CholmodLdlt, EmptyMatrix) {
  CholmodLdlt f;
  const SparseMatrix A(0, 0);
  ASSERT_TRUE(f.analyze(A).ok());
  ASSERT_TRUE(f.factorize(A).ok());
  DenseMatrix x(0, 2);
  EXPECT_TRUE(f.solve(x).ok());
}

}  // namespace
