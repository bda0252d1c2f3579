// KluLu's analysis with the column singletons first (sparse/src/klu_singleton_analysis.hpp):
// on Lemke-like bases (slack columns e_i beside columns of a sparse M) it peels every
// singleton, and the factorization (either column ordering) solves as a dense LU does,
// transposed too, refactorizes with kept pivots, extracts factors whose dense solve repeats klu_solve bit for bit, and
// finds zero pivots; where it does not apply (no singleton, two on one row, a structurally
// singular rest) KLU's own analysis runs and reports the matrix as before.
#include "factorization_test_support.hpp"

#include <lcprelax/sparse/hypersparse_column_solve.hpp>
#include <lcprelax/sparse/klu_lu.hpp>

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace {

using lcprelax::DenseMatrix;
using lcprelax::Index;
using lcprelax::SparseMatrix;
using lcprelax::Triplet;
using lcprelax::Vector;
using lcprelax::sparse::FactorStatus;
using lcprelax::sparse::HypersparseColumnSolver;
using lcprelax::sparse::KluLu;
using lcprelax::test::random_rhs;
using lcprelax::test::relative_residual;

// A Lemke-like basis of size n: for a random set W of rows (fraction `slack`), the slack
// columns e_i (i ∈ W, scaled by `value_scale` on odd rows), and for the other rows R the
// columns −M(:, j), j ∈ R, of a sparse diagonally dominant M (so that the rest M(R, R) is
// nonsingular); columns in shuffled order. `singletons`: |W|.
SparseMatrix lemke_like_basis(int n, double slack, unsigned seed, Index& singletons, double value_scale = 1.0) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::bernoulli_distribution coupled(6.0 / n), is_slack(slack);
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), gen);
  std::vector<Triplet> t;
  singletons = 0;
  for (int c = 0; c < n; ++c) {
    const int j = order[static_cast<std::size_t>(c)];  // the row/unknown this column belongs to
    if (is_slack(gen)) {
      t.emplace_back(j, c, j % 2 ? value_scale : 1.0);
      ++singletons;
      continue;
    }
    t.emplace_back(j, c, -8.0);
    for (int i = 0; i < n; ++i)
      if (i != j && coupled(gen)) t.emplace_back(i, c, -val(gen));
  }
  SparseMatrix B(n, n);
  B.setFromTriplets(t.begin(), t.end());
  B.makeCompressed();
  return B;
}

// Against KLU's own analysis of the whole matrix (set_singletons_first(false)) and a dense
// LU, both with true partial pivoting (the Lemke basis' setting), with either column
// ordering of the rest (AMD, COLAMD).
TEST(KluSingletonAnalysis, PeelsSlackColumnsAndSolvesAsKlusOwnAnalysis) {
  for (unsigned seed : {1u, 2u, 3u}) {
    for (double slack : {0.3, 0.6, 0.9}) {
      SCOPED_TRACE("seed " + std::to_string(seed) + ", slack fraction " + std::to_string(slack));
      Index singletons = 0;
      const SparseMatrix B = lemke_like_basis(300, slack, seed, singletons);
      ASSERT_GT(singletons, 0);
      for (KluLu::Ordering ordering : {KluLu::Ordering::amd, KluLu::Ordering::colamd}) {
        SCOPED_TRACE(ordering == KluLu::Ordering::amd ? "AMD" : "COLAMD");
        KluLu f, whole;
        whole.set_singletons_first(false);
        for (KluLu* g : {&f, &whole}) {
          g->set_pivot_tolerance(1.0);
          g->set_ordering(ordering);
          EXPECT_EQ(g->ordering(), ordering);
          ASSERT_TRUE(g->analyze(B).ok());
          ASSERT_TRUE(g->factorize(B).ok());
        }
        // At least the slack columns; a column of M may have a single entry too.
        EXPECT_GE(f.leading_singletons(), singletons);
        EXPECT_EQ(whole.leading_singletons(), 0);
        const DenseMatrix D(B);
        const DenseMatrix rhs = random_rhs(300, 3, seed);
        const DenseMatrix expected = Eigen::PartialPivLU<DenseMatrix>(D).solve(rhs);
        DenseMatrix X = rhs, Xw = rhs, Y = rhs, Yw = rhs;
        ASSERT_TRUE(f.solve(X).ok());
        ASSERT_TRUE(whole.solve(Xw).ok());
        ASSERT_TRUE(f.solve_transposed(Y).ok());
        ASSERT_TRUE(whole.solve_transposed(Yw).ok());
        EXPECT_LT(relative_residual(D, X, rhs), 1e-15);
        EXPECT_LT(relative_residual(D.transpose(), Y, rhs), 1e-15);
        EXPECT_LT((X - expected).cwiseAbs().maxCoeff(), 1e-13 * expected.cwiseAbs().maxCoeff());
        EXPECT_LT((X - Xw).cwiseAbs().maxCoeff(), 1e-13 * Xw.cwiseAbs().maxCoeff());
        EXPECT_LT((Y - Yw).cwiseAbs().maxCoeff(), 1e-13 * Yw.cwiseAbs().maxCoeff());
        Index l = 0, u = 0, off = 0, lw = 0, uw = 0, offw = 0;
        f.factor_counts(l, u, off);
        whole.factor_counts(lw, uw, offw);
        EXPECT_EQ(off, offw);  // the same diagonal blocks, so the same off-diagonal entries
      }
    }
  }
}

TEST(KluSingletonAnalysis, RefactorizesWithKeptPivotsOnThePeeledAnalysis) {
  Index singletons = 0;
  const SparseMatrix B = lemke_like_basis(200, 0.6, 7, singletons);
  KluLu f;
  f.set_pivot_tolerance(1.0);
  ASSERT_TRUE(f.analyze(B).ok());
  ASSERT_GT(f.leading_singletons(), 0);
  ASSERT_TRUE(f.factorize(B).ok());
  SparseMatrix B2 = B;
  for (Index k = 0; k < B2.nonZeros(); ++k) B2.valuePtr()[k] *= 1.0 + 1e-3 * static_cast<double>(k % 5);
  ASSERT_TRUE(f.analyzed_for(B2));
  ASSERT_TRUE(f.factorize_reusing_pivots(B2, 0.1).ok());
  EXPECT_TRUE(f.reused_pivots());
  const DenseMatrix rhs = random_rhs(200, 1, 8);
  DenseMatrix X = rhs;
  ASSERT_TRUE(f.solve(X).ok());
  EXPECT_LT(relative_residual(DenseMatrix(B2), X, rhs), 1e-15);
}

// The extracted factors of a peeled analysis (KLU's N = L·U + F over the composed blocks):
// the dense solve that skips zero entries repeats klu_solve bit for bit, so the block
// boundaries and off-diagonal entries that klu_factor produced from it are consistent.
TEST(KluSingletonAnalysis, ExtractedFactorsRepeatKluSolveBitForBit) {
  Index singletons = 0;
  const SparseMatrix B = lemke_like_basis(400, 0.6, 11, singletons, 1e-2);  // unequal row scales
  KluLu f;
  ASSERT_TRUE(f.analyze(B).ok());
  ASSERT_GT(f.leading_singletons(), 0);
  ASSERT_TRUE(f.factorize(B).ok());
  HypersparseColumnSolver columns;
  columns.reserve(f);
  ASSERT_TRUE(columns.build(f));
  std::mt19937 gen(12);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<int> index;
    std::vector<double> value;
    for (int i = 0; i < 400; ++i)
      if (i % (trial + 2) == 0) index.push_back(i), value.push_back(val(gen));
    DenseMatrix expected = DenseMatrix::Zero(400, 1);
    for (std::size_t k = 0; k < index.size(); ++k) expected(index[k], 0) = value[k];
    ASSERT_TRUE(f.solve(expected).ok());
    Vector x = Vector::Zero(400);
    columns.solve_dense(static_cast<int>(index.size()), index.data(), value.data(), x);
    for (int i = 0; i < 400; ++i) ASSERT_EQ(x(i), expected(i, 0)) << "entry " << i << ", trial " << trial;
  }
}

TEST(KluSingletonAnalysis, AllColumnsSingletons) {
  // A scaled permutation: every column a singleton, no rest to analyse.
  std::vector<Triplet> t{{2, 0, 2.0}, {0, 1, -4.0}, {3, 2, 0.5}, {1, 3, 8.0}};
  SparseMatrix P(4, 4);
  P.setFromTriplets(t.begin(), t.end());
  KluLu f;
  ASSERT_TRUE(f.analyze(P).ok());
  EXPECT_EQ(f.leading_singletons(), 4);
  ASSERT_TRUE(f.factorize(P).ok());
  DenseMatrix b(4, 1);
  b << -4.0, 8.0, 2.0, 0.5;  // P·[1 1 1 1]ᵀ
  ASSERT_TRUE(f.solve(b).ok());
  for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(b(i, 0), 1.0);
}

TEST(KluSingletonAnalysis, FallsBackToKluWhereItDoesNotApply) {
  // No singleton column.
  DenseMatrix D(3, 3);
  D << 4, 1, 0,
       1, 4, 1,
       0, 1, 4;
  KluLu plain;
  ASSERT_TRUE(plain.analyze(SparseMatrix(D.sparseView())).ok());
  EXPECT_EQ(plain.leading_singletons(), 0);
  EXPECT_TRUE(plain.factorize(SparseMatrix(D.sparseView())).ok());
  // Two singletons on row 0: structurally singular, reported by KLU's own analysis.
  std::vector<Triplet> t{{0, 0, 1.0}, {0, 1, 2.0}, {1, 2, 1.0}, {2, 2, 1.0}};
  SparseMatrix S(3, 3);
  S.setFromTriplets(t.begin(), t.end());
  KluLu two;
  ASSERT_TRUE(two.analyze(S).ok());
  EXPECT_EQ(two.leading_singletons(), 0);
  EXPECT_EQ(two.factorize(S).status, FactorStatus::singular);
  // A singleton on row 0; the rest (rows 1 and 2, columns 1 and 2) has an empty row.
  std::vector<Triplet> u{{0, 0, 1.0}, {0, 1, 1.0}, {1, 1, 1.0}, {0, 2, 1.0}, {1, 2, 3.0}};
  SparseMatrix T(3, 3);
  T.setFromTriplets(u.begin(), u.end());
  KluLu rest;
  ASSERT_TRUE(rest.analyze(T).ok());
  EXPECT_EQ(rest.leading_singletons(), 0);
  EXPECT_EQ(rest.factorize(T).status, FactorStatus::singular);
}

TEST(KluSingletonAnalysis, FindsZeroPivotsOfANumericallySingularRest) {
  Index singletons = 0;
  SparseMatrix B = lemke_like_basis(60, 0.5, 5, singletons);
  // Make one non-singleton column a copy of another: the rest is numerically singular.
  std::vector<Index> wide;
  for (Index c = 0; c < 60; ++c)
    if (B.outerIndexPtr()[c + 1] - B.outerIndexPtr()[c] > 1) wide.push_back(c);
  ASSERT_GE(wide.size(), 2u);
  DenseMatrix D(B);
  D.col(wide[1]) = D.col(wide[0]);
  const SparseMatrix S = D.sparseView();
  KluLu f, whole;
  whole.set_singletons_first(false);
  for (KluLu* g : {&f, &whole}) {
    ASSERT_TRUE(g->analyze(S).ok());
    EXPECT_EQ(g->factorize(S).status, FactorStatus::singular);
  }
  ASSERT_GT(f.leading_singletons(), 0);
  // One of the two equal columns has a zero pivot (KLU goes on past it, and a later pivot
  // may be flagged too: two columns with either analysis on this matrix).
  const std::vector<Index> zero = f.zero_pivot_columns(S, 1e-12);
  ASSERT_FALSE(zero.empty());
  EXPECT_TRUE(std::find(zero.begin(), zero.end(), wide[0]) != zero.end() ||
              std::find(zero.begin(), zero.end(), wide[1]) != zero.end());
  EXPECT_FALSE(whole.zero_pivot_columns(S, 1e-12).empty());
}

}  // namespace
