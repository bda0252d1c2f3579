// CholmodLlt specifics: clone_analysis of a supernodal factor, the column of a
// non-positive pivot through the fill-reducing ordering, and moves. The Factorization
// contract (residuals, many right-hand sides on a supernodal grid matrix, refactorization,
// the exact symbolic factor size, failure statuses, lifecycle, empty matrix) is checked for
// every backend in sparse_factorization_test.cpp.
#include "factorization_test_support.hpp"

#include <lcprelax/sparse/cholmod_llt.hpp>

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::SparseMatrix;
using lcprelax::Triplet;
using lcprelax::sparse::CholmodLlt;
using lcprelax::sparse::FactorStatus;
using lcprelax::test::grid_spd;  // full symmetric: CholmodLlt reads its upper triangle
using lcprelax::test::random_rhs;
using lcprelax::test::relative_residual;

TEST(CholmodLlt, ClonesTheAnalysisOfANumericFactor) {
  const SparseMatrix A1 = grid_spd(10, 4);
  const SparseMatrix A2 = grid_spd(10, 5, 3.0);
  CholmodLlt f;
  ASSERT_TRUE(f.analyze(A1).ok());
  ASSERT_TRUE(f.factorize(A1).ok());
  CholmodLlt g = f.clone_analysis();
  ASSERT_TRUE(f.factorize(A2).ok());
  ASSERT_TRUE(g.factorize(A2).ok());
  EXPECT_EQ(g.numeric_factorizations(), 1);
  const DenseMatrix b = random_rhs(100, 2, 6);
  DenseMatrix x = b, y = b;
  ASSERT_TRUE(f.solve(x).ok());
  ASSERT_TRUE(g.solve(y).ok());
  EXPECT_EQ((x - y).cwiseAbs().maxCoeff(), 0.0);  // same ordering, same arithmetic
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
}

TEST(CholmodLlt, WorksAfterMove) {
  const SparseMatrix A = grid_spd(5, 8);
  CholmodLlt f;
  ASSERT_TRUE(f.analyze(A).ok());
  ASSERT_TRUE(f.factorize(A).ok());
  CholmodLlt g(std::move(f));
  DenseMatrix x = random_rhs(25, 1, 9);
  const DenseMatrix b = x;
  ASSERT_TRUE(g.solve(x).ok());
  EXPECT_LT(relative_residual(DenseMatrix(A), x, b), 1e-14);
}

}  // namespace
