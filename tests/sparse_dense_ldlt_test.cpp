// DenseLdlt (sparse/dense_ldlt.hpp): dense LDLᵀ with diagonal pivoting of seeded random
// quasi-definite matrices K = [H Bᵀ; B −D] — multi-RHS residuals against the sparse
// matrix, the inertia (n positive, m negative), agreement with CHOLMOD's LDLᵀ, a tiny
// primal pivot that pivoting defers, refactorization on a fixed pattern, and the failure
// statuses of the Factorization contract (pattern mismatch, NaN, zero pivot, lifecycle).
#include <lcprelax/sparse/cholmod_ldlt.hpp>
#include <lcprelax/sparse/dense_ldlt.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::SparseMatrix;
using lcprelax::Triplet;
using lcprelax::Vector;
using lcprelax::sparse::CholmodLdlt;
using lcprelax::sparse::DenseLdlt;
using lcprelax::sparse::FactorStatus;

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

DenseMatrix full(const SparseMatrix& upper) {
  const DenseMatrix U = DenseMatrix(upper);
  return U.selfadjointView<Eigen::Upper>();
}

TEST(DenseLdlt, SolvesManyRightHandSidesWithTheQuasiDefiniteInertia) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const int n = 7, m = 5;
    const SparseMatrix K = quasi_definite(n, m, seed);
    DenseLdlt f;
    ASSERT_TRUE(f.analyze(K).ok());
    EXPECT_EQ(f.rows(), n + m);
    EXPECT_EQ(f.factor_nnz(), (n + m) * (n + m + 1) / 2);
    ASSERT_TRUE(f.factorize(K).ok());
    EXPECT_EQ(f.inertia().positive, n);
    EXPECT_EQ(f.inertia().negative, m);
    EXPECT_EQ(f.inertia().zero, 0);
    std::mt19937 gen(seed);
    std::normal_distribution<double> N(0.0, 1.0);
    const DenseMatrix B = DenseMatrix::NullaryExpr(n + m, 3, [&] { return N(gen); });
    DenseMatrix X = B;
    ASSERT_TRUE(f.solve(X).ok());
    const DenseMatrix R = full(K) * X - B;
    EXPECT_LT(R.lpNorm<Eigen::Infinity>(), 1e-12 * (1.0 + B.lpNorm<Eigen::Infinity>())) << "seed " << seed;

    CholmodLdlt ref;  // the same solution as CHOLMOD's sparse LDLᵀ
    ASSERT_TRUE(ref.analyze(K).ok());
    ASSERT_TRUE(ref.factorize(K).ok());
    DenseMatrix Y = B;
    ASSERT_TRUE(ref.solve(Y).ok());
    EXPECT_LT((X - Y).lpNorm<Eigen::Infinity>(), 1e-10 * (1.0 + Y.lpNorm<Eigen::Infinity>()));
    EXPECT_EQ(ref.inertia().positive, f.inertia().positive);
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
  const Vector b = Vector::LinSpaced(n + m, -1.0, 1.0);
  Vector x = b;
  ASSERT_TRUE(f.solve(x).ok());
  const DenseMatrix A = full(K);
  const double scale = A.lpNorm<Eigen::Infinity>() * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>();
  EXPECT_LT((A * x - b).lpNorm<Eigen::Infinity>(), 1e-13 * scale);
}

TEST(DenseLdlt, RefactorizesOnTheSamePatternAndRefusesAnother) {
  const SparseMatrix K1 = quasi_definite(5, 3, 1), K2 = quasi_definite(5, 3, 2);
  ASSERT_TRUE(K1.nonZeros() == K2.nonZeros());
  DenseLdlt f;
  ASSERT_TRUE(f.analyze(K1).ok());
  ASSERT_TRUE(f.factorize(K1).ok());
  ASSERT_TRUE(f.factorize(K2).ok());
  EXPECT_EQ(f.numeric_factorizations(), 2);
  Vector x = Vector::Ones(8);
  ASSERT_TRUE(f.solve(x).ok());
  EXPECT_LT((full(K2) * x - Vector::Ones(8)).lpNorm<Eigen::Infinity>(), 1e-12);

  const SparseMatrix other = quasi_definite(4, 4, 1);  // same size, another pattern
  const auto r = f.factorize(other);
  EXPECT_EQ(r.status, FactorStatus::pattern_mismatch);
  EXPECT_EQ(f.numeric_factorizations(), 2);
}

TEST(DenseLdlt, ReportsStatusesInsteadOfAborting) {
  DenseLdlt f;
  Vector b = Vector::Ones(2);
  EXPECT_EQ(f.factorize(quasi_definite(1, 1, 1)).status, FactorStatus::not_analyzed);
  EXPECT_EQ(f.solve(b).status, FactorStatus::not_analyzed);
  EXPECT_EQ(f.analyze(SparseMatrix(2, 3)).status, FactorStatus::invalid_input);

  SparseMatrix K = quasi_definite(2, 1, 3);
  ASSERT_TRUE(f.analyze(K).ok());
  SparseMatrix bad = K;
  bad.valuePtr()[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(f.factorize(bad).status, FactorStatus::invalid_input);
  EXPECT_EQ(f.solve(b).status, FactorStatus::not_analyzed) << "no factor after a failed factorize()";
  ASSERT_TRUE(f.factorize(K).ok());
  Vector wrong = Vector::Ones(5);
  EXPECT_EQ(f.solve(wrong).status, FactorStatus::invalid_input);

  // [[0, 1], [1, 0]]: no diagonal pivot exists (not quasi-definite) → zero_pivot.
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

  // With dynamic regularization τ the zero pivots become +τ and the factorization succeeds.
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
  const Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(full(K));
  EXPECT_EQ(f.inertia().positive, (eig.eigenvalues().array() > 0).count()) << "Sylvester's law of inertia";
}

}  // namespace
