// PetscMumpsLdlt (MUMPS LDLᵀ through PETSc) on one process, against CholmodLdlt.
// Expected, with PETSc: on seeded random quasi-definite KKT matrices K = [H Bᵀ; B −D]
// (n = 60, m = 25) the solution of K X = B for 3 right-hand sides has a relative residual
// ≤ 1e-12 and equals CHOLMOD's to 1e-10; the inertia is (60 positive, 25 negative) like
// CHOLMOD's; refactorizing new values on the same pattern counts one more numeric
// factorization and solves the new matrix; a changed pattern gives pattern_mismatch, NaN
// gives invalid_input, a singular matrix zero_pivot (also without pivoting, where MUMPS'
// static pivoting would otherwise replace the zero pivot silently), solve() before
// factorize() not_analyzed — statuses with messages, never an abort; after a failed
// numeric phase the next factorize() of a good matrix succeeds (PETSc would skip it);
// the static-order backend's refactorize_pivoted() gives the same inertia and residual
// ≤ 1e-12, and the next factorize() is in the static order again.
// Without PETSc: analyze() returns invalid_input naming LCPRELAX_WITH_PETSC.
#include "factorization_test_support.hpp"

#include <lcprelax/sparse/cholmod_ldlt.hpp>
#include <lcprelax/mpi/mpi_session.hpp>
#include <lcprelax/sparse/petsc_mumps_ldlt.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::SparseMatrix;
using lcprelax::Triplet;
using lcprelax::sparse::CholmodLdlt;
using lcprelax::sparse::FactorStatus;
using lcprelax::sparse::PetscMumpsLdlt;

// Upper triangle of K = [H Bᵀ; B −D]: H diagonally dominant SPD, D positive diagonal. The
// pattern depends on n and m only; `scale` and `seed` change the values.
SparseMatrix kkt_upper(int n, int m, unsigned seed, double scale = 1.0) {
  std::mt19937 gen(seed), pattern(99);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::bernoulli_distribution keep(0.12);
  std::vector<Triplet> t;
  std::vector<double> dominance(static_cast<std::size_t>(n), 1.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < j; ++i)
      if (keep(pattern)) {
        const double v = scale * val(gen);
        t.emplace_back(i, j, v);
        dominance[static_cast<std::size_t>(i)] += std::abs(v);
        dominance[static_cast<std::size_t>(j)] += std::abs(v);
      }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, scale * dominance[static_cast<std::size_t>(i)]);
  for (int r = 0; r < m; ++r) {
    for (int c = 0; c < n; ++c)
      if (keep(pattern) || c == r % n) t.emplace_back(c, n + r, scale * val(gen));
    t.emplace_back(n + r, n + r, -scale * (0.1 + std::abs(val(gen))));
  }
  SparseMatrix U(n + m, n + m);
  U.setFromTriplets(t.begin(), t.end());
  U.makeCompressed();
  return U;
}


// ‖K X − B‖∞ / ‖B‖∞ (stricter than the backward error of factorization_test_support.hpp).
double residual_over_rhs(const SparseMatrix& U, const DenseMatrix& X, const DenseMatrix& B) {
  const SparseMatrix K = U.selfadjointView<Eigen::Upper>();
  return (K * X - B).lpNorm<Eigen::Infinity>() / B.lpNorm<Eigen::Infinity>();
}

#ifdef LCPRELAX_HAS_PETSC

TEST(PetscMumpsLdlt, SolvesQuasiDefiniteKktLikeCholmod) {
  const SparseMatrix U = kkt_upper(60, 25, 1);
  const DenseMatrix B = lcprelax::test::random_rhs(85, 3, 7);
  PetscMumpsLdlt mumps;
  ASSERT_TRUE(mumps.analyze(U).ok());
  EXPECT_GT(mumps.factor_nnz(), 0);
  const auto f = mumps.factorize(U);
  ASSERT_TRUE(f.ok()) << f.message;
  DenseMatrix X = B;
  ASSERT_TRUE(mumps.solve(X).ok());
  EXPECT_LE(residual_over_rhs(U, X, B), 1e-12);

  CholmodLdlt cholmod;
  ASSERT_TRUE(cholmod.analyze(U).ok());
  ASSERT_TRUE(cholmod.factorize(U).ok());
  DenseMatrix Y = B;
  ASSERT_TRUE(cholmod.solve(Y).ok());
  EXPECT_LE((X - Y).lpNorm<Eigen::Infinity>(), 1e-10 * Y.lpNorm<Eigen::Infinity>());
  EXPECT_EQ(mumps.inertia().positive, 60);
  EXPECT_EQ(mumps.inertia().negative, 25);
  EXPECT_EQ(mumps.inertia().positive, cholmod.inertia().positive);
  EXPECT_EQ(mumps.numeric_factorizations(), 1);
}

TEST(PetscMumpsLdlt, RefactorizesNewValuesOnTheAnalysedPattern) {
  const SparseMatrix U1 = kkt_upper(40, 15, 1), U2 = kkt_upper(40, 15, 2, 3.0);
  PetscMumpsLdlt mumps;
  ASSERT_TRUE(mumps.analyze(U1).ok());
  ASSERT_TRUE(mumps.factorize(U1).ok());
  ASSERT_TRUE(mumps.factorize(U2).ok());
  EXPECT_EQ(mumps.numeric_factorizations(), 2);
  const DenseMatrix B = lcprelax::test::random_rhs(55, 2, 7);
  DenseMatrix X = B;
  ASSERT_TRUE(mumps.solve(X).ok());
  EXPECT_LE(residual_over_rhs(U2, X, B), 1e-12);
}

TEST(PetscMumpsLdlt, FailuresAreStatuses) {
  PetscMumpsLdlt mumps;
  DenseMatrix X = lcprelax::test::random_rhs(55, 1, 7);
  EXPECT_EQ(mumps.solve(X).status, FactorStatus::not_analyzed);
  EXPECT_EQ(mumps.factorize(kkt_upper(40, 15, 1)).status, FactorStatus::not_analyzed);
  ASSERT_TRUE(mumps.analyze(kkt_upper(40, 15, 1)).ok());
  EXPECT_EQ(mumps.factorize(kkt_upper(41, 15, 1)).status, FactorStatus::pattern_mismatch);
  SparseMatrix bad = kkt_upper(40, 15, 1);
  bad.valuePtr()[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(mumps.factorize(bad).status, FactorStatus::invalid_input);

  // Singular: a zero row and column (the pattern keeps an explicit zero diagonal).
  SparseMatrix singular = kkt_upper(40, 15, 1);
  for (int k = singular.outerIndexPtr()[5]; k < singular.outerIndexPtr()[6]; ++k) singular.valuePtr()[k] = 0.0;
  for (int j = 6; j < singular.cols(); ++j)
    for (int k = singular.outerIndexPtr()[j]; k < singular.outerIndexPtr()[j + 1]; ++k)
      if (singular.innerIndexPtr()[k] == 5) singular.valuePtr()[k] = 0.0;
  const auto r = mumps.factorize(singular);
  EXPECT_EQ(r.status, FactorStatus::zero_pivot) << r.message;
  EXPECT_FALSE(r.message.empty());
}

// Without pivoting (the KKT backend's mode) MUMPS' static pivoting would silently replace
// the zero pivot by 1e-300 and return a factor with entries ~1e300 (the cause of the
// QADLITTL divergence with kkt_backend = mumps); it must be a zero_pivot status instead.
TEST(PetscMumpsLdlt, StaticPivotOrderReportsReplacedPivots) {
  PetscMumpsLdlt mumps(/*distributed=*/false, /*pivoting=*/false);
  const SparseMatrix U = kkt_upper(40, 15, 1);
  ASSERT_TRUE(mumps.analyze(U).ok());
  ASSERT_TRUE(mumps.factorize(U).ok());
  SparseMatrix singular = U;
  for (int k = singular.outerIndexPtr()[5]; k < singular.outerIndexPtr()[6]; ++k) singular.valuePtr()[k] = 0.0;
  for (int j = 6; j < singular.cols(); ++j)
    for (int k = singular.outerIndexPtr()[j]; k < singular.outerIndexPtr()[j + 1]; ++k)
      if (singular.innerIndexPtr()[k] == 5) singular.valuePtr()[k] = 0.0;
  const auto r = mumps.factorize(singular);
  EXPECT_EQ(r.status, FactorStatus::zero_pivot) << r.message;
  DenseMatrix X = lcprelax::test::random_rhs(55, 1, 7);
  EXPECT_EQ(mumps.solve(X).status, FactorStatus::not_analyzed);  // no factor to use
  ASSERT_TRUE(mumps.factorize(U).ok());                           // and it recovers
  const DenseMatrix B = lcprelax::test::random_rhs(55, 1, 7);
  X = B;
  ASSERT_TRUE(mumps.solve(X).ok());
  EXPECT_LE(residual_over_rhs(U, X, B), 1e-12);
}

SparseMatrix with_zero_row_and_column(SparseMatrix U, int row) {
  for (int k = U.outerIndexPtr()[row]; k < U.outerIndexPtr()[row + 1]; ++k) U.valuePtr()[k] = 0.0;
  for (int j = row + 1; j < U.cols(); ++j)
    for (int k = U.outerIndexPtr()[j]; k < U.outerIndexPtr()[j + 1]; ++k)
      if (U.innerIndexPtr()[k] == row) U.valuePtr()[k] = 0.0;
  return U;
}

// PETSc skips MUMPS' numeric phase while the previous phase's INFOG(1) is negative; the
// backend creates its factor anew after a failure, so the next factorize() factorizes.
// (With pivoting = true, ICNTL(24) turns a singular matrix into null pivots, INFOG(1) ≥ 0;
// the failure here is the threshold-pivoted refactorization's, INFOG(1) = −10.)
TEST(PetscMumpsLdlt, FactorizesAgainAfterAFailedNumericPhase) {
  const SparseMatrix U = kkt_upper(40, 15, 1);
  PetscMumpsLdlt mumps(/*distributed=*/false, /*pivoting=*/false);
  ASSERT_TRUE(mumps.analyze(U).ok());
  EXPECT_EQ(mumps.factorize(with_zero_row_and_column(U, 5)).status, FactorStatus::zero_pivot);
  const auto failed = mumps.refactorize_pivoted();
  EXPECT_EQ(failed.status, FactorStatus::zero_pivot);
  EXPECT_NE(failed.message.find("INFOG(1) = -10"), std::string::npos) << failed.message;
  const auto r = mumps.factorize(U);
  ASSERT_TRUE(r.ok()) << r.message;
  const DenseMatrix B = lcprelax::test::random_rhs(55, 2, 7);
  DenseMatrix X = B;
  ASSERT_TRUE(mumps.solve(X).ok());
  EXPECT_LE(residual_over_rhs(U, X, B), 1e-12);
  EXPECT_EQ(mumps.inertia().negative, 15);
}

// refactorize_pivoted() of the static-order backend: the last factorize()'s matrix with
// threshold pivoting, the same inertia and solution quality; the next factorize() is in the
// static order again (a zero pivot is reported as replaced, not pivoted away).
TEST(PetscMumpsLdlt, PivotedRefactorizationOfTheStaticOrderBackend) {
  const SparseMatrix U1 = kkt_upper(40, 15, 1), U2 = kkt_upper(40, 15, 2, 3.0);
  PetscMumpsLdlt mumps(/*distributed=*/false, /*pivoting=*/false);
  EXPECT_TRUE(mumps.can_refactorize_pivoted());
  EXPECT_EQ(mumps.refactorize_pivoted().status, FactorStatus::not_analyzed);
  ASSERT_TRUE(mumps.analyze(U1).ok());
  EXPECT_EQ(mumps.refactorize_pivoted().status, FactorStatus::not_analyzed);  // nothing factorized yet
  ASSERT_TRUE(mumps.factorize(U1).ok());
  const auto r = mumps.refactorize_pivoted();
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(mumps.pivoted_refactorizations(), 1);
  EXPECT_EQ(mumps.numeric_factorizations(), 2);
  EXPECT_EQ(mumps.inertia().positive, 40);
  EXPECT_EQ(mumps.inertia().negative, 15);
  const DenseMatrix B = lcprelax::test::random_rhs(55, 2, 7);
  DenseMatrix X = B;
  ASSERT_TRUE(mumps.solve(X).ok());
  EXPECT_LE(residual_over_rhs(U1, X, B), 1e-12);

  // A singular matrix: replaced pivot in the static order, MUMPS' failure with pivoting;
  // both are statuses, and the backend factorizes the next matrix in the static order.
  const SparseMatrix singular = with_zero_row_and_column(U1, 5);
  EXPECT_EQ(mumps.factorize(singular).status, FactorStatus::zero_pivot);
  EXPECT_EQ(mumps.refactorize_pivoted().status, FactorStatus::zero_pivot);
  EXPECT_EQ(mumps.factorize(singular).status, FactorStatus::zero_pivot);  // static order again
  ASSERT_TRUE(mumps.factorize(U2).ok());
  X = B;
  ASSERT_TRUE(mumps.solve(X).ok());
  EXPECT_LE(residual_over_rhs(U2, X, B), 1e-12);

  PetscMumpsLdlt pivoting;  // already pivots: nothing to redo differently
  EXPECT_FALSE(pivoting.can_refactorize_pivoted());
  CholmodLdlt cholmod;
  EXPECT_FALSE(cholmod.can_refactorize_pivoted());
  EXPECT_EQ(cholmod.refactorize_pivoted().status, FactorStatus::invalid_input);
}

TEST(MpiSession, OneProcessWithoutMpiexec) {
  lcprelax::mpi::ensure_petsc_initialized();
  EXPECT_TRUE(lcprelax::mpi::petsc_available());
  EXPECT_EQ(lcprelax::mpi::mpi_rank(), 0);
  EXPECT_EQ(lcprelax::mpi::mpi_size(), 1);
  EXPECT_EQ(lcprelax::mpi::allgather({1.0, 2.0}), (std::vector<double>{1.0, 2.0}));
}

#else

TEST(PetscMumpsLdlt, BuiltWithoutPetscSaysSo) {
  PetscMumpsLdlt mumps;
  const auto r = mumps.analyze(kkt_upper(10, 5, 1));
  EXPECT_EQ(r.status, FactorStatus::invalid_input);
  EXPECT_NE(r.message.find("LCPRELAX_WITH_PETSC"), std::string::npos) << r.message;
  EXPECT_FALSE(lcprelax::mpi::petsc_available());
}

#endif

}  // namespace
