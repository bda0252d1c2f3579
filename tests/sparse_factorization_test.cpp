// The Factorization contract (sparse/factorization.hpp), checked on every backend through
// one parameterized suite: CholmodLdlt, CholmodLlt, KluLu, DenseLdlt and, with PETSc,
// PetscMumpsLdlt. Each backend is given what it supports (symmetric backends the upper
// triangle of SPD and, for LDLᵀ, quasi-definite matrices; KluLu full SPD, quasi-definite
// and unsymmetric matrices, and its transposed solve): solve residuals on seeded random
// matrices, many right-hand sides in place (also a block with a leading dimension, zero
// columns, wrong row count), numeric refactorization on the analysed pattern, the
// pattern_mismatch, invalid_input (NaN, Inf, non-square), not_analyzed and singular
// statuses, and the empty matrix. Behaviour specific to one backend (inertia, dynamic
// regularization, clone_analysis, KLU's refactorize/rcond, MUMPS' pivoting modes) is in
// the backend's own sparse_*_test.cpp.
#include "factorization_test_support.hpp"

#include <lcprelax/sparse/cholmod_ldlt.hpp>
#include <lcprelax/sparse/cholmod_llt.hpp>
#include <lcprelax/sparse/dense_ldlt.hpp>
#include <lcprelax/sparse/klu_lu.hpp>
#ifdef LCPRELAX_HAS_PETSC
#include <lcprelax/sparse/petsc_mumps_ldlt.hpp>
#endif

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace lcprelax::sparse {
namespace {

using test::random_rhs;
using test::relative_residual;

struct Backend {
  std::string name;
  std::function<std::unique_ptr<Factorization>()> make;
  bool symmetric;        // reads the upper triangle only
  bool quasi_definite;   // factorizes symmetric indefinite quasi-definite matrices
  bool unsymmetric;      // factorizes unsymmetric matrices (and solve_transposed differs)
  FactorStatus singular; // status of a singular matrix
  double tolerance;      // backward error of a solve
  // PetscMumpsLdlt differs here (sparse/ is unchanged by these tests): it counts a failed
  // numeric factorization in numeric_factorizations(), and factorize() of the 0×0 matrix
  // returns a status instead of ok.
  bool counts_failed_factorizations = false;
  bool factorizes_empty = true;
};

std::ostream& operator<<(std::ostream& os, const Backend& b) { return os << b.name; }

std::vector<Backend> backends() {
  std::vector<Backend> b = {
      {"CholmodLdlt", [] { return std::make_unique<CholmodLdlt>(); }, true, true, false, FactorStatus::zero_pivot, 1e-14},
      {"CholmodLlt", [] { return std::make_unique<CholmodLlt>(); }, true, false, false,
       FactorStatus::not_positive_definite, 1e-14},
      // Threshold partial pivoting (KLU tol 0.001) allows some growth.
      {"KluLu", [] { return std::make_unique<KluLu>(); }, false, true, true, FactorStatus::singular, 1e-11},
      {"DenseLdlt", [] { return std::make_unique<DenseLdlt>(); }, true, true, false, FactorStatus::zero_pivot, 1e-13},
  };
#ifdef LCPRELAX_HAS_PETSC
  b.push_back({"PetscMumpsLdlt", [] { return std::make_unique<PetscMumpsLdlt>(); }, true, true, false,
               FactorStatus::zero_pivot, 1e-13, true, false});
#endif
  return b;
}

// Full symmetric SPD, diagonally dominant; the pattern depends on n only.
SparseMatrix spd(int n, unsigned seed, double scale = 1.0) {
  std::mt19937 gen(seed), pattern(4321);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::bernoulli_distribution keep(0.15);
  std::vector<Triplet> t;
  std::vector<double> row_sum(static_cast<std::size_t>(n), 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = j + 1; i < n; ++i) {
      if (!keep(pattern)) continue;
      const double v = scale * val(gen);
      t.emplace_back(i, j, v);
      t.emplace_back(j, i, v);
      row_sum[static_cast<std::size_t>(i)] += std::abs(v);
      row_sum[static_cast<std::size_t>(j)] += std::abs(v);
    }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, row_sum[static_cast<std::size_t>(i)] + scale * (1.0 + std::abs(val(gen))));
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// Full symmetric K = [H Bᵀ; B −D] (H SPD n×n, D positive diagonal m×m); pattern by (n, m).
SparseMatrix quasi_definite(int n, int m, unsigned seed) {
  const SparseMatrix H = spd(n, seed);
  std::mt19937 gen(seed + 1000), pattern(8765);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::bernoulli_distribution keep(0.15);
  std::vector<Triplet> t;
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(H, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  for (int r = 0; r < m; ++r) {
    for (int c = 0; c < n; ++c) {
      if (!keep(pattern) && c != r % n) continue;
      const double v = val(gen);
      t.emplace_back(n + r, c, v);
      t.emplace_back(c, n + r, v);
    }
    t.emplace_back(n + r, n + r, -(0.1 + std::abs(val(gen))));
  }
  SparseMatrix K(n + m, n + m);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

// Unsymmetric with a nonzero diagonal; pattern by n.
SparseMatrix unsymmetric(int n, unsigned seed) {
  std::mt19937 gen(seed), pattern(99);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::bernoulli_distribution keep(0.1);
  std::vector<Triplet> t;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (i == j) t.emplace_back(i, j, 2.0 + val(gen));
      else if (keep(pattern)) t.emplace_back(i, j, val(gen));
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

class FactorizationContract : public ::testing::TestWithParam<Backend> {
 protected:
  // What the backend reads of a full matrix A.
  SparseMatrix input(const SparseMatrix& A) const {
    if (!GetParam().symmetric) return A;
    SparseMatrix U = A.triangularView<Eigen::Upper>();
    U.makeCompressed();
    return U;
  }
  std::unique_ptr<Factorization> make() const { return GetParam().make(); }

  // Factorizes A and checks the residual of 3 right-hand sides (and of the transposed
  // solve for unsymmetric backends).
  void check_solves(const SparseMatrix& A, unsigned seed) const {
    auto f = make();
    const SparseMatrix in = input(A);
    ASSERT_TRUE(f->analyze(in).ok());
    EXPECT_EQ(f->rows(), A.rows());
    EXPECT_GT(f->factor_nnz(), 0);
    const auto r = f->factorize(in);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(f->numeric_factorizations(), 1);
    const DenseMatrix B = random_rhs(static_cast<int>(A.rows()), 3, seed + 100);
    DenseMatrix X = B, Y = B;
    ASSERT_TRUE(f->solve(X).ok());
    ASSERT_TRUE(f->solve_transposed(Y).ok());
    const DenseMatrix Ad(A);
    EXPECT_LT(relative_residual(Ad, X, B), GetParam().tolerance) << "seed " << seed;
    EXPECT_LT(relative_residual(Ad.transpose(), Y, B), GetParam().tolerance) << "seed " << seed;
  }
};

TEST_P(FactorizationContract, SolvesRandomSpdSystems) {
  for (unsigned seed : {1u, 2u, 3u}) check_solves(spd(50, seed), seed);
}

TEST_P(FactorizationContract, SolvesRandomQuasiDefiniteSystems) {
  if (!GetParam().quasi_definite) GTEST_SKIP() << GetParam().name << " needs a positive definite matrix";
  for (unsigned seed : {1u, 2u, 3u}) check_solves(quasi_definite(40, 25, seed), seed);
}

TEST_P(FactorizationContract, SolvesRandomUnsymmetricSystems) {
  if (!GetParam().unsymmetric) GTEST_SKIP() << GetParam().name << " is symmetric";
  for (unsigned seed : {1u, 2u, 3u}) check_solves(unsymmetric(60, seed), seed);
}

TEST_P(FactorizationContract, SolvesManyRightHandSidesInPlace) {
  const SparseMatrix A = spd(40, 11);
  auto f = make();
  ASSERT_TRUE(f->analyze(input(A)).ok());
  ASSERT_TRUE(f->factorize(input(A)).ok());
  const DenseMatrix B = random_rhs(40, 7, 12);
  DenseMatrix X = B;
  ASSERT_TRUE(f->solve(X).ok());
  EXPECT_LT(relative_residual(DenseMatrix(A), X, B), GetParam().tolerance);
  DenseMatrix first = B;  // one column alone agrees with the batch
  ASSERT_TRUE(f->solve(first.leftCols(1)).ok());
  EXPECT_LT((first.col(0) - X.col(0)).cwiseAbs().maxCoeff(), 1e-12);
  // A block of a taller matrix: leading dimension 45 ≠ 40 rows.
  DenseMatrix tall = DenseMatrix::Constant(45, 7, 42.0);
  tall.topRows(40) = B;
  ASSERT_TRUE(f->solve(tall.topRows(40)).ok());
  EXPECT_LT((tall.topRows(40) - X).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(tall.bottomRows(5).cwiseAbs().minCoeff(), 42.0);  // rows below untouched
  EXPECT_EQ(tall.bottomRows(5).cwiseAbs().maxCoeff(), 42.0);
  DenseMatrix none(40, 0);
  EXPECT_TRUE(f->solve(none).ok());
  DenseMatrix wrong(39, 1);
  EXPECT_EQ(f->solve(wrong).status, FactorStatus::invalid_input);
}

TEST_P(FactorizationContract, RefactorizesNewValuesOnTheAnalysedPattern) {
  const SparseMatrix A1 = spd(30, 31), A2 = spd(30, 32, 3.0);
  ASSERT_EQ(A1.nonZeros(), A2.nonZeros());
  auto f = make();
  ASSERT_TRUE(f->analyze(input(A1)).ok());
  EXPECT_EQ(f->numeric_factorizations(), 0);
  ASSERT_TRUE(f->factorize(input(A1)).ok());
  ASSERT_TRUE(f->factorize(input(A2)).ok());
  EXPECT_EQ(f->numeric_factorizations(), 2);
  const DenseMatrix b = random_rhs(30, 2, 33);
  DenseMatrix x = b;
  ASSERT_TRUE(f->solve(x).ok());
  EXPECT_LT(relative_residual(DenseMatrix(A2), x, b), GetParam().tolerance);
}

TEST_P(FactorizationContract, RejectsAnotherPattern) {
  const SparseMatrix A = spd(20, 41);
  auto f = make();
  ASSERT_TRUE(f->analyze(input(A)).ok());
  SparseMatrix other = A;
  const int j = A.coeff(0, 19) != 0.0 ? 18 : 19;  // a new entry in the upper triangle
  other.coeffRef(0, j) += 0.01;
  other.coeffRef(j, 0) += 0.01;
  const auto r = f->factorize(input(other));
  EXPECT_EQ(r.status, FactorStatus::pattern_mismatch);
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(f->factorize(input(spd(21, 41))).status, FactorStatus::pattern_mismatch);  // another size
  EXPECT_EQ(f->numeric_factorizations(), 0);
}

TEST_P(FactorizationContract, RejectsNonFiniteValues) {
  const SparseMatrix A = input(spd(10, 51));
  auto f = make();
  ASSERT_TRUE(f->analyze(A).ok());
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    SparseMatrix Ab = A;
    Ab.valuePtr()[Ab.nonZeros() / 2] = bad;
    EXPECT_EQ(f->factorize(Ab).status, FactorStatus::invalid_input);
  }
  EXPECT_EQ(f->numeric_factorizations(), 0);
  DenseMatrix x = DenseMatrix::Ones(10, 1);
  EXPECT_EQ(f->solve(x).status, FactorStatus::not_analyzed);  // no factor
}

// diag(2, 0, 3) plus A(0,2) = A(2,0) = 1, with the zero stored: singular whatever the
// ordering; the same pattern with A(1,1) = 5 is positive definite.
SparseMatrix singular_matrix(double a11) {
  std::vector<Triplet> t{{0, 0, 2.0}, {1, 1, a11}, {2, 2, 3.0}, {0, 2, 1.0}, {2, 0, 1.0}};
  SparseMatrix A(3, 3);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

TEST_P(FactorizationContract, ReportsASingularMatrix) {
  auto f = make();
  ASSERT_TRUE(f->analyze(input(singular_matrix(0.0))).ok());
  const auto r = f->factorize(input(singular_matrix(0.0)));
  EXPECT_EQ(r.status, GetParam().singular) << r.message;
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(f->numeric_factorizations(), GetParam().counts_failed_factorizations ? 1 : 0);
  DenseMatrix x = DenseMatrix::Ones(3, 1);
  EXPECT_EQ(f->solve(x).status, FactorStatus::not_analyzed);
  // The next nonsingular matrix of the same pattern factorizes.
  ASSERT_TRUE(f->factorize(input(singular_matrix(5.0))).ok());
  ASSERT_TRUE(f->solve(x).ok());
  EXPECT_LT(relative_residual(DenseMatrix(singular_matrix(5.0)), x, DenseMatrix::Ones(3, 1)), GetParam().tolerance);
}

TEST_P(FactorizationContract, LifecycleErrors) {
  auto f = make();
  DenseMatrix x = DenseMatrix::Ones(3, 1);
  EXPECT_EQ(f->solve(x).status, FactorStatus::not_analyzed);
  EXPECT_EQ(f->factorize(input(singular_matrix(5.0))).status, FactorStatus::not_analyzed);
  EXPECT_EQ(f->rows(), 0);
  EXPECT_EQ(f->analyze(SparseMatrix(3, 4)).status, FactorStatus::invalid_input);
  EXPECT_NE(std::string(f->name()), "");
}

TEST_P(FactorizationContract, EmptyMatrix) {
  auto f = make();
  const SparseMatrix E(0, 0);
  ASSERT_TRUE(f->analyze(E).ok());
  if (!GetParam().factorizes_empty) {
    const auto r = f->factorize(E);
    EXPECT_FALSE(r.ok());
    EXPECT_FALSE(r.message.empty());
    return;
  }
  ASSERT_TRUE(f->factorize(E).ok());
  EXPECT_EQ(f->rows(), 0);
  DenseMatrix x(0, 2);
  EXPECT_TRUE(f->solve(x).ok());
}

INSTANTIATE_TEST_SUITE_P(Backends, FactorizationContract, ::testing::ValuesIn(backends()),
                         [](const ::testing::TestParamInfo<Backend>& info) { return info.param.name; });

}  // namespace
}  // namespace lcprelax::sparse
