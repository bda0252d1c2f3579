// DenseLdlt specifics: the dense factor of seeded random quasi-definite matrices
// K = [H Bᵀ; B −D] with a dense H = CᵀC + h·I (its size and residuals), a tiny primal pivot
// that diagonal pivoting defers, a matrix without a nonzero diagonal pivot (zero_pivot, or
// ±τ with dynamic regularization), the inertia of a matrix that is not quasi-definite, and
// the dimension limit. The Factorization contract (residuals, many right-hand sides,
// refactorization, quasi-definite inertia, agreement with CholmodLdlt, failure statuses,
// lifecycle, empty matrix) is checked for every backend in sparse_factorization_test.cpp.
#include "factorization_test_support.hpp"

#include <lcprelax/sparse/dense_ldlt.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::SparseMatrix;
using lcprelax::Vector;
using lcprelax::sparse::DenseLdlt;
using lcprelax::sparse::FactorStatus;
using lcprelax::test::random_rhs;
using lcprelax::test::relative_residual;
using lcprelax::test::residual_over_rhs;
using lcprelax::test::symmetric_from_upper;

// Upper triangle of K = [H Bᵀ; B −D]: H = CᵀC + h·I (n×n, SPD), B m×n with ~half of its
// entries, D = diag in [d, 2d]. The pattern depends on (n, m) only; `seed` sets values.
SparseMatrix quasi_definite(int n, int m, unsigned seed, double h = 1.0, double d = 1.0) {
  std::mt19937 gen(seed), pattern(77);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::bernoulli_distribution keep(0.5);
  DenseMatrix C = DenseMatrix::NullaryExpr(n, n, [&] { return val(gen); });
  DenseMatrix K = DenseMatrix::Zero(n + m, n + m);
  K.topLeftCorner(n, n) = C.transpose() * C + h * DenseMatrix::Identity(n, n);
  for (int r = 0; r < m; ++r) {
    for (int c = 0; c < n; ++c)
      if (keep(pattern) || c == r % n) K(c, n + r) = val(gen);
    K(n + r, n + r) = -d * (1.0 + std::abs(val(gen)));
  }
  SparseMatrix S = DenseMatrix(K.triangularView<Eigen::Upper>()).sparseView(0.0, 0.0);
  S.makeCompressed();
  return S;
}

// Dense H: the largest diagonal entries mix primal and dual rows, so pivoting interleaves
// them; the inertia is still (n, m).
TEST(DenseLdlt, StoresTheFullTriangleAndSolvesDenseBlocks) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const int n = 7, m = 5;
    const SparseMatrix K = quasi_definite(n, m, seed);
    DenseLdlt f;
    ASSERT_TRUE(f.analyze(K).ok());
    EXPECT_EQ(f.factor_nnz(), (n + m) * (n + m + 1) / 2);
    ASSERT_TRUE(f.factorize(K).ok());
    EXPECT_EQ(f.inertia().positive, n);
    EXPECT_EQ(f.inertia().negative, m);
    const DenseMatrix B = random_rhs(n + m, 3, seed);
    DenseMatrix X = B;
    ASSERT_TRUE(f.solve(X).ok());
    EXPECT_LT(residual_over_rhs(symmetric_from_upper(K), X, B), 1e-12) << "seed " << seed;
  }
}

// A primal pivot of size ρ = 1e-9 (an LP's free variable): in natural order it would be
// eliminated first with growth ~1/ρ; pivoting takes the rows first, and the solve stays
// accurate (relative residual near machine precision, no refinement).
TEST(DenseLdlt, TinyPrimalPivotStaysAccurate) {
  const int n = 4, m = 4;
  SparseMatrix K = quasi_definite(n, m, 5, 1.0, 1e-3);
  for (int k = K.outerIndexPtr()[0]; k < K.outerIndexPtr()[1]; ++k)
    if (K.innerIndexPtr()[k] == 0) K.valuePtr()[k] = 1e-9;  // H(0,0)
  for (int j = 1; j < n; ++j)  // decouple variable 0 inside H
    for (int k = K.outerIndexPtr()[j]; k < K.outerIndexPtr()[j + 1]; ++k)
      if (K.innerIndexPtr()[k] == 0) K.valuePtr()[k] = 0.0;
  DenseLdlt f;
  ASSERT_TRUE(f.analyze(K).ok());
  ASSERT_TRUE(f.factorize(K).ok());
  EXPECT_EQ(f.inertia().positive, n);
  const DenseMatrix b = Vector::LinSpaced(n + m, -1.0, 1.0);
  DenseMatrix x = b;
  ASSERT_TRUE(f.solve(x).ok());
  EXPECT_LT(relative_residual(symmetric_from_upper(K), x, b), 1e-14);
}

// [[0, 1], [1, 0]]: no diagonal pivot exists (not quasi-definite) → zero_pivot; with
// dynamic regularization τ the zero pivots become +τ and the factorization succeeds.
TEST(DenseLdlt, NoNonzeroDiagonalPivotIsAZeroPivotUnlessRegularized) {
  SparseMatrix Z(2, 2);
  Z.insert(0, 0) = 0.0;
  Z.insert(0, 1) = 1.0;
  Z.insert(1, 1) = 0.0;
  Z.makeCompressed();
  DenseLdlt g;
  ASSERT_TRUE(g.analyze(Z).ok());
  const auto r = g.factorize(Z);
  EXPECT_EQ(r.status, FactorStatus::zero_pivot);
  EXPECT_GE(r.pivot, 0);
  EXPECT_FALSE(r.message.empty());

  DenseLdlt reg(1e-8);
  ASSERT_TRUE(reg.analyze(Z).ok());
  ASSERT_TRUE(reg.factorize(Z).ok());
  EXPECT_EQ(reg.regularized_pivots(), 1) << "the first pivot is τ, the second −1/τ";
  EXPECT_EQ(reg.inertia().positive, 1);
  EXPECT_EQ(reg.inertia().negative, 1);
}

// An indefinite matrix that is not quasi-definite (H has a negative eigenvalue): the
// factorization succeeds, and the inertia exposes it (fewer than n positive pivots), which
// is what the interior point checks before raising its regularization.
TEST(DenseLdlt, InertiaExposesANonQuasiDefiniteMatrix) {
  SparseMatrix K = quasi_definite(3, 2, 4);
  for (int k = K.outerIndexPtr()[1]; k < K.outerIndexPtr()[2]; ++k)
    if (K.innerIndexPtr()[k] == 1) K.valuePtr()[k] = -50.0;  // H(1,1) ≪ 0
  DenseLdlt f;
  ASSERT_TRUE(f.analyze(K).ok());
  ASSERT_TRUE(f.factorize(K).ok());
  EXPECT_LT(f.inertia().positive, 3);
  const Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(symmetric_from_upper(K));
  EXPECT_EQ(f.inertia().positive, (eig.eigenvalues().array() > 0).count()) << "Sylvester's law of inertia";
}

TEST(DenseLdlt, RefusesADimensionAboveTheLimit) {
  SparseMatrix I(DenseLdlt::kMaxDimension + 1, DenseLdlt::kMaxDimension + 1);
  I.setIdentity();
  DenseLdlt f;
  const auto r = f.analyze(I);
  EXPECT_EQ(r.status, FactorStatus::out_of_memory);
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(f.rows(), 0);
}

}  // namespace
