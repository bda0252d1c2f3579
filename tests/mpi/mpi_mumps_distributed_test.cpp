// The distributed MUMPS LDLᵀ (PetscMumpsLdlt with distributed = true) on 2 MPI ranks.
// Expected: the test runs with exactly 2 ranks; a 400 + 150 quasi-definite KKT matrix
// (tridiagonal-plus-coupling H, sparse B, negative diagonal −D) distributed by rows over
// the ranks is factorized and solved for 2 right-hand sides: the relative residual is
// ≤ 1e-12, the solution is the same on both ranks (bitwise, it is gathered to all), it
// equals the per-process (PETSC_COMM_SELF) factorization's to 1e-10, and the inertia is
// (400, 150); a refactorization with new values on the same pattern solves the new matrix.
#include <lcprelax/mpi/mpi_session.hpp>
#include <lcprelax/sparse/petsc_mumps_ldlt.hpp>

#include "mpi_main.hpp"

#include <cmath>
#include <cstring>
#include <vector>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::SparseMatrix;
using lcprelax::Triplet;
using lcprelax::sparse::PetscMumpsLdlt;

SparseMatrix kkt_upper(int n, int m, double scale) {
  std::vector<Triplet> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, scale * (4.0 + std::sin(i)));
    if (i + 1 < n) t.emplace_back(i, i + 1, -scale);
    if (i + 37 < n) t.emplace_back(i, i + 37, 0.5 * scale);
  }
  for (int r = 0; r < m; ++r) {
    t.emplace_back((3 * r) % n, n + r, scale * std::cos(r));
    t.emplace_back((7 * r + 1) % n, n + r, 1.0);
    t.emplace_back(n + r, n + r, -scale * (0.5 + 0.25 * std::cos(3.0 * r)));
  }
  SparseMatrix U(n + m, n + m);
  U.setFromTriplets(t.begin(), t.end());
  U.makeCompressed();
  return U;
}

DenseMatrix rhs(int rows) {
  DenseMatrix B(rows, 2);
  for (int i = 0; i < rows; ++i) {
    B(i, 0) = std::sin(0.1 * i);
    B(i, 1) = 1.0 / (1.0 + i);
  }
  return B;
}

double residual(const SparseMatrix& U, const DenseMatrix& X, const DenseMatrix& B) {
  const SparseMatrix K = U.selfadjointView<Eigen::Upper>();
  return (K * X - B).lpNorm<Eigen::Infinity>() / B.lpNorm<Eigen::Infinity>();
}

TEST(DistributedMumps, SolvesOnTwoRanksLikeOneProcess) {
  ASSERT_EQ(lcprelax::mpi::mpi_size(), 2) << "run under mpiexec -n 2";
  const SparseMatrix U = kkt_upper(400, 150, 1.0);
  const DenseMatrix B = rhs(550);
  PetscMumpsLdlt distributed(true), local(false);
  EXPECT_STREQ(distributed.name(), "mumps_ldlt_distributed");
  ASSERT_TRUE(distributed.analyze(U).ok());
  const auto f = distributed.factorize(U);
  ASSERT_TRUE(f.ok()) << f.message;
  DenseMatrix X = B;
  ASSERT_TRUE(distributed.solve(X).ok());
  EXPECT_LE(residual(U, X, B), 1e-12);
  EXPECT_EQ(distributed.inertia().positive, 400);
  EXPECT_EQ(distributed.inertia().negative, 150);

  // The same on both ranks: gather rank 1's solution and compare bitwise.
  const std::vector<double> mine(X.data(), X.data() + X.size());
  const std::vector<double> all = lcprelax::mpi::allgather(mine);
  EXPECT_EQ(std::memcmp(all.data(), all.data() + mine.size(), mine.size() * sizeof(double)), 0);

  ASSERT_TRUE(local.analyze(U).ok());
  ASSERT_TRUE(local.factorize(U).ok());
  DenseMatrix Y = B;
  ASSERT_TRUE(local.solve(Y).ok());
  EXPECT_LE((X - Y).lpNorm<Eigen::Infinity>(), 1e-10 * Y.lpNorm<Eigen::Infinity>());

  const SparseMatrix U2 = kkt_upper(400, 150, 2.5);
  ASSERT_TRUE(distributed.factorize(U2).ok());
  DenseMatrix X2 = B;
  ASSERT_TRUE(distributed.solve(X2).ok());
  EXPECT_LE(residual(U2, X2, B), 1e-12);
  EXPECT_EQ(distributed.numeric_factorizations(), 2);
}

}  // namespace

LCPRELAX_MPI_TEST_MAIN()
