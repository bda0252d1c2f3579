// CholmodLlt: supernodal LLᵀ of seeded random SPD matrices (residuals, many right-hand
// sides, refactorization, clone) and the not_positive_definite status with its column.
#include "factorization_test_support.hpp"

#include <lcprelax/sparse/cholmod_llt.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::SparseMatrix;
using lcprelax::Triplet;
using lcprelax::sparse::CholmodLlt;
using lcprelax::sparse::FactorStatus;
using lcprelax::test::random_rhs;

// Backward error of A X = B for A given by its upper triangle.
double residual(const SparseMatrix& upper, const DenseMatrix& X, const DenseMatrix& B) {
  return lcprelax::test::relative_residual(lcprelax::test::symmetric_from_upper(upper), X, B);
}

// A 2-D Laplacian-like SPD matrix on a k×k grid with random positive weights: dense
// enough after fill-in to give real supernodes. Upper triangle only.
SparseMatrix grid_spd(int k, unsigned seed, double shift = 0.1) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> w(0.5, 2.0);
  const int n = k * k;
  std::vector<double> diag(n, shift);
  std::vector<Triplet> t;
  auto edge = [&](int a, int b) {
    const double v = w(gen);
    t.emplace_back(std::min(a, b), std::max(a, b), -v);
    diag[a] += v;
    diag[b] += v;
  };
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      if (i + 1 < k) edge(i * k + j, (i + 1) * k + j);
      if (j + 1 < k) edge(i * k + j, i * k + j + 1);
    }
  }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, diag[i]);
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}



TEST(CholmodLlt, SolvesSpdSystemsWithManyRightHandSides) {
  const SparseMatrix A = grid_spd(15, 1);
  CholmodLlt f;
  ASSERT_TRUE(f.analyze(A).ok());
  const long predicted = f.factor_nnz();
  EXPECT_GT(predicted, A.nonZeros());
  ASSERT_TRUE(f.factorize(A).ok());
  EXPECT_EQ(f.factor_nnz(), predicted);
  EXPECT_EQ(f.rows(), 225);
  const DenseMatrix b = random_rhs(225, 1, 2);
  DenseMatrix x = b;
  ASSERT_TRUE(f.solve(x).ok());
  EXPECT_LT(residual(A, x, b), 1e-14);
  const DenseMatrix B = random_rhs(225, 6, 3);
  DenseMatrix X = B;
  ASSERT_TRUE(f.solve(X).ok());
  EXPECT_LT(residual(A, X, B), 1e-14);
  DenseMatrix wide = B;  // the first column alone agrees with the batch
  ASSERT_TRUE(f.solve(wide.leftCols(1)).ok());
  EXPECT_LT((wide.col(0) - X.col(0)).cwiseAbs().maxCoeff(), 1e-13);
}

TEST(CholmodLlt, RefactorizesAndClones) {
  const SparseMatrix A1 = grid_spd(10, 4);
  const SparseMatrix A2 = grid_spd(10, 5, 3.0);
  CholmodLlt f;
  ASSERT_TRUE(f.analyze(A1).ok());
  ASSERT_TRUE(f.factorize(A1).ok());
  CholmodLlt g = f.clone_analysis();
  ASSERT_TRUE(f.factorize(A2).ok());
  ASSERT_TRUE(g.factorize(A2).ok());
  EXPECT_EQ(f.numeric_factorizations(), 2);
  EXPECT_EQ(g.numeric_factorizations(), 1);
  const DenseMatrix b = random_rhs(100, 2, 6);
  DenseMatrix x = b, y = b;
  ASSERT_TRUE(f.solve(x).ok());
  ASSERT_TRUE(g.solve(y).ok());
  EXPECT_LT(residual(A2, x, b), 1e-14);
  EXPECT_EQ((x - y).cwiseAbs().maxCoeff(), 0.0);
  SparseMatrix other = A1;
  other.coeffRef(0, 99) = 0.01;
  EXPECT_EQ(f.factorize(other).status, FactorStatus::pattern_mismatch);
}

TEST(CholmodLlt, ReportsTheColumnOfANonPositivePivot) {
  // Block diagonal: an SPD grid block and an isolated −1 on the diagonal at column c, so
  // the failing column is c whatever the fill-reducing ordering.
  const SparseMatrix G = grid_spd(6, 7);
  const int n = 37, c = 20;
  std::vector<Triplet> t;
  for (int j = 0; j < G.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(G, j); it; ++it) {
      const int r = it.row() >= c ? it.row() + 1 : it.row();
      const int s = it.col() >= c ? it.col() + 1 : it.col();
      t.emplace_back(r, s, it.value());
    }
  }
  t.emplace_back(c, c, -1.0);
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  CholmodLlt f;
  ASSERT_TRUE(f.analyze(A).ok());
  const auto r = f.factorize(A);
  EXPECT_EQ(r.status, FactorStatus::not_positive_definite);
  EXPECT_EQ(r.pivot, c);
  EXPECT_NE(r.message.find("not positive definite"), std::string::npos);
  DenseMatrix x = DenseMatrix::Ones(n, 1);
  EXPECT_EQ(f.solve(x).status, FactorStatus::not_analyzed);
  SparseMatrix fixed = A;
  fixed.coeffRef(c, c) = 1.0;
  EXPECT_TRUE(f.factorize(fixed).ok());
}

TEST(CholmodLlt, RejectsNanAndWorksAfterMove) {
  const SparseMatrix A = grid_spd(5, 8);
  CholmodLlt f;
  ASSERT_TRUE(f.analyze(A).ok());
  SparseMatrix bad = A;
  bad.valuePtr()[3] = std::nan("");
  EXPECT_EQ(f.factorize(bad).status, FactorStatus::invalid_input);
  ASSERT_TRUE(f.factorize(A).ok());
  CholmodLlt g(std::move(f));
  DenseMatrix x = random_rhs(25, 1, 9);
  const DenseMatrix b = x;
  ASSERT_TRUE(g.solve(x).ok());
  EXPECT_LT(residual(A, x, b), 1e-14);
}

}  // namespace
