// CholmodLdlt specifics: dynamic regularization of a zero pivot, clone_analysis across
// threads on seeded random quasi-definite KKT matrices K = [H Bᵀ; B −D], and moves. The
// Factorization contract (residuals, many right-hand sides, refactorization, inertia, the
// exact symbolic factor size, failure statuses, lifecycle, empty matrix) is checked for
// every backend in sparse_factorization_test.cpp.
#include "factorization_test_support.hpp"

#include <lcprelax/sparse/cholmod_ldlt.hpp>

#include <gtest/gtest.h>

#include <thread>
#include <utility>
#include <vector>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::SparseMatrix;
using lcprelax::Triplet;
using lcprelax::sparse::CholmodLdlt;
using lcprelax::sparse::FactorStatus;
using lcprelax::test::quasi_definite_kkt;
using lcprelax::test::random_rhs;

SparseMatrix upper(const SparseMatrix& K) { return K.triangularView<Eigen::Upper>(); }

// diag(2, 0, 3) with the zero stored: the zero pivot is column 1 whatever the ordering.
SparseMatrix singular_diagonal() {
  std::vector<Triplet> t{{0, 0, 2.0}, {1, 1, 0.0}, {2, 2, 3.0}, {0, 2, 1.0}};
  SparseMatrix A(3, 3);
  A.setFromTriplets(t.begin(), t.end());
  return A;
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

TEST(CholmodLdlt, CloneAnalysisFactorizesOnAnotherThread) {
  const SparseMatrix K1 = upper(quasi_definite_kkt(60, 30, 61));
  const SparseMatrix K2 = upper(quasi_definite_kkt(60, 30, 62, 2.0));
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

TEST(CholmodLdlt, MovesKeepTheFactor) {
  SparseMatrix good = singular_diagonal();
  good.coeffRef(1, 1) = 5.0;
  CholmodLdlt f;
  ASSERT_TRUE(f.analyze(good).ok());
  ASSERT_TRUE(f.factorize(good).ok());
  DenseMatrix x = DenseMatrix::Ones(3, 1);
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

}  // namespace
