// PetscMumpsLdlt (MUMPS LDLᵀ through PETSc) on one process: its static pivot order
// (pivoting = false, the KKT backend's mode). Expected, with PETSc, on seeded random
// quasi-definite KKT matrices K = [H Bᵀ; B −D] (n = 40, m = 15): a singular matrix gives
// zero_pivot (MUMPS' static pivoting would otherwise replace the zero pivot silently) and
// leaves no factor to solve with; after a failed numeric phase (also the threshold-pivoted
// refactorization's, INFOG(1) = −10) the next factorize() of a good matrix succeeds (PETSc
// would skip it), with ‖KX − B‖/‖B‖ ≤ 1e-12 and the inertia (40, 15); the static-order
// backend's refactorize_pivoted() gives the same inertia and residual ≤ 1e-12, and the next
// factorize() is in the static order again. The Factorization contract with the default
// (pivoting) backend — residuals, agreement with CholmodLdlt, inertia, refactorization,
// pattern_mismatch, NaN, singular, lifecycle — is checked in sparse_factorization_test.cpp.
// Without PETSc: analyze() returns invalid_input naming LCPRELAX_WITH_PETSC.
#include "factorization_test_support.hpp"

#include <lcprelax/mpi/mpi_session.hpp>
#include <lcprelax/sparse/petsc_mumps_ldlt.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::SparseMatrix;
using lcprelax::sparse::FactorStatus;
using lcprelax::sparse::PetscMumpsLdlt;
using lcprelax::test::quasi_definite_kkt;
using lcprelax::test::random_rhs;
using lcprelax::test::residual_over_rhs;
using lcprelax::test::symmetric_from_upper;

// Upper triangle of the quasi-definite K = [H Bᵀ; B −D] of factorization_test_support.hpp.
SparseMatrix kkt_upper(int n, int m, unsigned seed, double scale = 1.0) {
  SparseMatrix U = quasi_definite_kkt(n, m, seed, scale).triangularView<Eigen::Upper>();
  U.makeCompressed();
  return U;
}

#ifdef LCPRELAX_HAS_PETSC

SparseMatrix with_zero_row_and_column(SparseMatrix U, int row) {
  for (int k = U.outerIndexPtr()[row]; k < U.outerIndexPtr()[row + 1]; ++k) U.valuePtr()[k] = 0.0;
  for (int j = row + 1; j < U.cols(); ++j)
    for (int k = U.outerIndexPtr()[j]; k < U.outerIndexPtr()[j + 1]; ++k)
      if (U.innerIndexPtr()[k] == row) U.valuePtr()[k] = 0.0;
  return U;
}

// Without pivoting MUMPS' static pivoting would silently replace the zero pivot by 1e-300
// and return a factor with entries ~1e300 (the cause of the QADLITTL divergence with
// kkt_backend = mumps); it must be a zero_pivot status with no factor left to use. PETSc
// skips MUMPS' numeric phase while the previous phase's INFOG(1) is negative; the backend
// creates its factor anew after a failure, so the next factorize() factorizes. (With
// pivoting = true, ICNTL(24) turns a singular matrix into null pivots, INFOG(1) ≥ 0; the
// failure here is the threshold-pivoted refactorization's, INFOG(1) = −10.)
TEST(PetscMumpsLdlt, StaticPivotOrderReportsReplacedPivotsAndFactorizesAgain) {
  const SparseMatrix U = kkt_upper(40, 15, 1);
  PetscMumpsLdlt mumps(/*distributed=*/false, /*pivoting=*/false);
  ASSERT_TRUE(mumps.analyze(U).ok());
  ASSERT_TRUE(mumps.factorize(U).ok());
  const auto singular = mumps.factorize(with_zero_row_and_column(U, 5));
  EXPECT_EQ(singular.status, FactorStatus::zero_pivot) << singular.message;
  DenseMatrix X = random_rhs(55, 1, 7);
  EXPECT_EQ(mumps.solve(X).status, FactorStatus::not_analyzed);  // no factor to use
  const auto failed = mumps.refactorize_pivoted();
  EXPECT_EQ(failed.status, FactorStatus::zero_pivot);
  EXPECT_NE(failed.message.find("INFOG(1) = -10"), std::string::npos) << failed.message;
  const auto r = mumps.factorize(U);
  ASSERT_TRUE(r.ok()) << r.message;
  const DenseMatrix B = random_rhs(55, 2, 7);
  X = B;
  ASSERT_TRUE(mumps.solve(X).ok());
  EXPECT_LE(residual_over_rhs(symmetric_from_upper(U), X, B), 1e-12);
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
  const DenseMatrix B = random_rhs(55, 2, 7);
  DenseMatrix X = B;
  ASSERT_TRUE(mumps.solve(X).ok());
  EXPECT_LE(residual_over_rhs(symmetric_from_upper(U1), X, B), 1e-12);

  // A singular matrix: replaced pivot in the static order, MUMPS' failure with pivoting;
  // both are statuses, and the backend factorizes the next matrix in the static order.
  const SparseMatrix singular = with_zero_row_and_column(U1, 5);
  EXPECT_EQ(mumps.factorize(singular).status, FactorStatus::zero_pivot);
  EXPECT_EQ(mumps.refactorize_pivoted().status, FactorStatus::zero_pivot);
  EXPECT_EQ(mumps.factorize(singular).status, FactorStatus::zero_pivot);  // static order again
  ASSERT_TRUE(mumps.factorize(U2).ok());
  X = B;
  ASSERT_TRUE(mumps.solve(X).ok());
  EXPECT_LE(residual_over_rhs(symmetric_from_upper(U2), X, B), 1e-12);
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
