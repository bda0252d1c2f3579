// The Factorization contract (sparse/factorization.hpp), checked on every backend through
// parameterized suites: CholmodLdlt, CholmodLlt, KluLu, DenseLdlt and, with PETSc,
// PetscMumpsLdlt. Each suite is instantiated over the backends it applies to, so no test is
// skipped: FactorizationContract (all backends, SPD matrices: solve and transposed solve
// residuals, many right-hand sides in place on a grid matrix with supernodes, numeric
// refactorization, the pattern_mismatch, invalid_input (NaN, Inf, non-square),
// not_analyzed and singular statuses, the empty matrix), QuasiDefiniteFactorization
// (quasi-definite KKT matrices), UnsymmetricFactorization (KluLu, with its transposed
// solve), UpperTriangleFactorization (symmetric backends ignore the lower triangle),
// InertiaFactorization (LDLᵀ backends report n positive and m negative pivots),
// ExactFactorSizeFactorization (factor_nnz() after analyze() is the factor's) and
// CholmodLdltAgreement (the other quasi-definite backends solve like CholmodLdlt).
// Behaviour specific to one backend (dynamic regularization, clone_analysis, moves, KLU's
// refactorize/rcond, MUMPS' pivoting modes, DenseLdlt's pivoting and size limit) is in the
// backend's own sparse_*_test.cpp.
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

using test::grid_spd;
using test::quasi_definite_kkt;
using test::random_rhs;
using test::relative_residual;
using test::residual_over_rhs;
using test::spd;

// What a backend factorizes besides SPD matrices, and what it reports.
enum Capability : unsigned {
  upper_triangle = 1,    // symmetric: reads the upper triangle only
  quasi_definite = 2,    // symmetric indefinite quasi-definite matrices
  unsymmetric = 4,       // unsymmetric matrices (solve_transposed differs from solve)
  ldlt_inertia = 8,      // inertia() of the LDLᵀ pivots
  exact_factor_nnz = 16  // factor_nnz() after analyze() equals the factor's
};

struct Backend {
  std::string name;
  std::function<std::unique_ptr<Factorization>()> make;
  unsigned capabilities;
  FactorStatus singular;  // status of a singular matrix
  Index singular_pivot;   // FactorResult::pivot of the singular 3×3 matrix (-1: not known)
  double tolerance;       // backward error of a solve
  // PetscMumpsLdlt differs here (sparse/ is unchanged by these tests): it counts a failed
  // numeric factorization in numeric_factorizations(), factorize() of the 0×0 matrix
  // returns a status instead of ok, and refactorize_pivoted() repeats factorize() (so it
  // is not_analyzed before one) instead of the default invalid_input; MUMPS does not say
  // which pivot was zero.
  bool counts_failed_factorizations = false;
  bool factorizes_empty = true;
  FactorStatus fresh_refactorize_pivoted = FactorStatus::invalid_input;
};

std::ostream& operator<<(std::ostream& os, const Backend& b) { return os << b.name; }

std::vector<Backend> backends(unsigned required = 0) {
  std::vector<Backend> all = {
      {"CholmodLdlt", [] { return std::make_unique<CholmodLdlt>(); },
       upper_triangle | quasi_definite | ldlt_inertia | exact_factor_nnz, FactorStatus::zero_pivot, 1, 1e-14},
      {"CholmodLlt", [] { return std::make_unique<CholmodLlt>(); }, upper_triangle | exact_factor_nnz,
       FactorStatus::not_positive_definite, 1, 1e-14},
      // Threshold partial pivoting (KLU tol 0.001) allows some growth.
      {"KluLu", [] { return std::make_unique<KluLu>(); }, quasi_definite | unsymmetric, FactorStatus::singular, 1, 1e-11},
      {"DenseLdlt", [] { return std::make_unique<DenseLdlt>(); },
       upper_triangle | quasi_definite | ldlt_inertia | exact_factor_nnz, FactorStatus::zero_pivot, 1, 1e-13},
  };
#ifdef LCPRELAX_HAS_PETSC
  all.push_back({"PetscMumpsLdlt", [] { return std::make_unique<PetscMumpsLdlt>(); },
                 upper_triangle | quasi_definite | ldlt_inertia, FactorStatus::zero_pivot, -1, 1e-13, true, false,
                 FactorStatus::not_analyzed});
#endif
  std::vector<Backend> selected;
  for (const Backend& b : all)
    if ((b.capabilities & required) == required) selected.push_back(b);
  return selected;
}

// Unsymmetric, pattern by n; the diagonal is as small as the rest (|a_ii| ≤ 0.5), so LU
// has to pivot.
SparseMatrix unsymmetric_matrix(int n, unsigned seed) {
  std::mt19937 gen(seed), pattern(99);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::bernoulli_distribution keep(0.1);
  std::vector<Triplet> t;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (i == j || keep(pattern)) t.emplace_back(i, j, (i == j ? 0.5 : 1.0) * val(gen));
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// diag(2, a11, 3) plus A(0,2) = A(2,0) = 1, with a11 stored even when 0: singular for
// a11 = 0 whatever the ordering (zero pivot in column 1), positive definite for a11 = 5,
// indefinite with one negative pivot for a11 = −4.
SparseMatrix three_by_three(double a11) {
  std::vector<Triplet> t{{0, 0, 2.0}, {1, 1, a11}, {2, 2, 3.0}, {0, 2, 1.0}, {2, 0, 1.0}};
  SparseMatrix A(3, 3);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

class FactorizationContract : public ::testing::TestWithParam<Backend> {
 protected:
  // What the backend reads of a full matrix A.
  SparseMatrix input(const SparseMatrix& A) const {
    if (!(GetParam().capabilities & upper_triangle)) return A;
    SparseMatrix U = A.triangularView<Eigen::Upper>();
    U.makeCompressed();
    return U;
  }
  std::unique_ptr<Factorization> make() const { return GetParam().make(); }

  // A X = B solved: backward error within the backend's tolerance and, for the well
  // conditioned symmetric test matrices, the residual relative to B within 1e-12.
  void expect_solved(const DenseMatrix& A, const DenseMatrix& X, const DenseMatrix& B, unsigned seed = 0,
                     bool well_conditioned = true) const {
    EXPECT_LT(relative_residual(A, X, B), GetParam().tolerance) << "seed " << seed;
    if (well_conditioned) {
      EXPECT_LT(residual_over_rhs(A, X, B), 1e-12) << "seed " << seed;
    }
  }

  // Factorizes A and checks the factor size and the residuals of 3 right-hand sides with
  // solve() and solve_transposed() (which differ for an unsymmetric A).
  void check_solves(const SparseMatrix& A, unsigned seed, bool unsymmetric_matrix = false) const {
    auto f = make();
    const SparseMatrix in = input(A);
    ASSERT_TRUE(f->analyze(in).ok());
    EXPECT_EQ(f->rows(), A.rows());
    EXPECT_GT(f->factor_nnz(), 0);
    const auto r = f->factorize(in);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(f->numeric_factorizations(), 1);
    EXPECT_GE(f->factor_nnz(), in.nonZeros());
    const DenseMatrix B = random_rhs(static_cast<int>(A.rows()), 3, seed + 100);
    DenseMatrix X = B, Y = B;
    ASSERT_TRUE(f->solve(X).ok());
    ASSERT_TRUE(f->solve_transposed(Y).ok());
    const DenseMatrix Ad(A);
    expect_solved(Ad, X, B, seed, !unsymmetric_matrix);
    expect_solved(Ad.transpose(), Y, B, seed, !unsymmetric_matrix);
    if (unsymmetric_matrix) {
      EXPECT_GT((X - Y).cwiseAbs().maxCoeff(), 1e-6);
    }
  }
};

TEST_P(FactorizationContract, SolvesRandomSpdSystems) {
  for (unsigned seed : {1u, 2u, 3u}) check_solves(spd(50, seed), seed);
}

TEST_P(FactorizationContract, SolvesManyRightHandSidesInPlace) {
  const SparseMatrix A = grid_spd(15, 1);  // 225 rows
  auto f = make();
  ASSERT_TRUE(f->analyze(input(A)).ok());
  ASSERT_TRUE(f->factorize(input(A)).ok());
  const DenseMatrix B = random_rhs(225, 7, 12);
  DenseMatrix X = B;
  ASSERT_TRUE(f->solve(X).ok());
  expect_solved(DenseMatrix(A), X, B);
  DenseMatrix first = B;  // one column alone agrees with the batch
  ASSERT_TRUE(f->solve(first.leftCols(1)).ok());
  EXPECT_LT((first.col(0) - X.col(0)).cwiseAbs().maxCoeff(), 1e-13);
  // A block of a taller matrix: leading dimension 230 ≠ 225 rows, the same solution.
  DenseMatrix tall = DenseMatrix::Constant(230, 7, 42.0);
  tall.topRows(225) = B;
  ASSERT_TRUE(f->solve(tall.topRows(225)).ok());
  EXPECT_EQ((tall.topRows(225) - X).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(tall.bottomRows(5).minCoeff(), 42.0);  // rows below untouched
  EXPECT_EQ(tall.bottomRows(5).maxCoeff(), 42.0);
  DenseMatrix none(225, 0);
  EXPECT_TRUE(f->solve(none).ok());
  DenseMatrix wrong(224, 1);
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
  expect_solved(DenseMatrix(A2), x, b);
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
  EXPECT_TRUE(f->factorize(A).ok());                          // the finite values factorize
}

TEST_P(FactorizationContract, ReportsASingularMatrix) {
  auto f = make();
  ASSERT_TRUE(f->analyze(input(three_by_three(0.0))).ok());
  const auto r = f->factorize(input(three_by_three(0.0)));
  EXPECT_EQ(r.status, GetParam().singular) << r.message;
  EXPECT_EQ(r.pivot, GetParam().singular_pivot);
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(f->numeric_factorizations(), GetParam().counts_failed_factorizations ? 1 : 0);
  DenseMatrix x = DenseMatrix::Ones(3, 1);
  EXPECT_EQ(f->solve(x).status, FactorStatus::not_analyzed);
  // The next nonsingular matrix of the same pattern factorizes.
  ASSERT_TRUE(f->factorize(input(three_by_three(5.0))).ok());
  ASSERT_TRUE(f->solve(x).ok());
  expect_solved(DenseMatrix(three_by_three(5.0)), x, DenseMatrix::Ones(3, 1));
}

TEST_P(FactorizationContract, LifecycleErrors) {
  auto f = make();
  DenseMatrix x = DenseMatrix::Ones(3, 1);
  EXPECT_EQ(f->solve(x).status, FactorStatus::not_analyzed);
  EXPECT_EQ(f->factorize(input(three_by_three(5.0))).status, FactorStatus::not_analyzed);
  EXPECT_EQ(f->rows(), 0);
  EXPECT_EQ(f->analyze(SparseMatrix(3, 4)).status, FactorStatus::invalid_input);
  EXPECT_NE(std::string(f->name()), "");
  EXPECT_FALSE(f->can_refactorize_pivoted());  // only PetscMumpsLdlt without pivoting can
  EXPECT_EQ(f->refactorize_pivoted().status, GetParam().fresh_refactorize_pivoted);
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

class QuasiDefiniteFactorization : public FactorizationContract {};

TEST_P(QuasiDefiniteFactorization, SolvesRandomQuasiDefiniteSystems) {
  for (unsigned seed : {1u, 2u, 3u}) check_solves(quasi_definite_kkt(40, 25, seed), seed);
}

class UnsymmetricFactorization : public FactorizationContract {};

TEST_P(UnsymmetricFactorization, SolvesRandomUnsymmetricSystems) {
  for (unsigned seed : {1u, 2u, 3u}) check_solves(unsymmetric_matrix(80, seed), seed, true);
}

class UpperTriangleFactorization : public FactorizationContract {};

TEST_P(UpperTriangleFactorization, IgnoresTheLowerTriangleAndAcceptsUncompressedInput) {
  const SparseMatrix A = spd(30, 7);
  SparseMatrix full = A;
  for (int j = 0; j < full.outerSize(); ++j)  // garbage below the diagonal
    for (SparseMatrix::InnerIterator it(full, j); it; ++it)
      if (it.row() > j) it.valueRef() = -1e3;
  full.uncompress();
  auto f = make();
  ASSERT_TRUE(f->analyze(full).ok());
  ASSERT_TRUE(f->factorize(full).ok());
  const DenseMatrix b = random_rhs(30, 1, 8);
  DenseMatrix x = b;
  ASSERT_TRUE(f->solve(x).ok());
  expect_solved(DenseMatrix(A), x, b);
}

class InertiaFactorization : public FactorizationContract {};

TEST_P(InertiaFactorization, CountsPrimalPositiveAndDualNegativePivots) {
  auto f = make();
  EXPECT_TRUE(f->reports_inertia());
  const SparseMatrix K = input(quasi_definite_kkt(35, 15, 21));
  ASSERT_TRUE(f->analyze(K).ok());
  ASSERT_TRUE(f->factorize(K).ok());
  EXPECT_EQ(f->inertia().positive, 35);
  EXPECT_EQ(f->inertia().negative, 15);
  EXPECT_EQ(f->inertia().zero, 0);
  auto g = make();  // one negative pivot, whatever the ordering
  ASSERT_TRUE(g->analyze(input(three_by_three(0.0))).ok());
  ASSERT_TRUE(g->factorize(input(three_by_three(-4.0))).ok());
  EXPECT_EQ(g->inertia().positive, 2);
  EXPECT_EQ(g->inertia().negative, 1);
}

class ExactFactorSizeFactorization : public FactorizationContract {};

TEST_P(ExactFactorSizeFactorization, PredictsTheFactorSizeAtAnalysis) {
  const SparseMatrix A = input(grid_spd(15, 4));
  auto f = make();
  ASSERT_TRUE(f->analyze(A).ok());
  const long predicted = f->factor_nnz();
  EXPECT_GT(predicted, A.nonZeros());  // fill-in
  ASSERT_TRUE(f->factorize(A).ok());
  EXPECT_EQ(f->factor_nnz(), predicted);
}

class CholmodLdltAgreement : public FactorizationContract {};

TEST_P(CholmodLdltAgreement, SolvesQuasiDefiniteSystemsLikeCholmodLdlt) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const SparseMatrix K = quasi_definite_kkt(40, 25, seed);
    const DenseMatrix B = random_rhs(65, 3, seed + 7);
    auto f = make();
    ASSERT_TRUE(f->analyze(input(K)).ok());
    ASSERT_TRUE(f->factorize(input(K)).ok());
    DenseMatrix X = B;
    ASSERT_TRUE(f->solve(X).ok());
    CholmodLdlt reference;
    const SparseMatrix U = K.triangularView<Eigen::Upper>();
    ASSERT_TRUE(reference.analyze(U).ok());
    ASSERT_TRUE(reference.factorize(U).ok());
    DenseMatrix Y = B;
    ASSERT_TRUE(reference.solve(Y).ok());
    EXPECT_LE((X - Y).cwiseAbs().maxCoeff(), 1e-10 * Y.cwiseAbs().maxCoeff()) << "seed " << seed;
  }
}

auto backend_name = [](const ::testing::TestParamInfo<Backend>& info) { return info.param.name; };

INSTANTIATE_TEST_SUITE_P(Backends, FactorizationContract, ::testing::ValuesIn(backends()), backend_name);
INSTANTIATE_TEST_SUITE_P(Backends, QuasiDefiniteFactorization, ::testing::ValuesIn(backends(quasi_definite)),
                         backend_name);
INSTANTIATE_TEST_SUITE_P(Backends, UnsymmetricFactorization, ::testing::ValuesIn(backends(unsymmetric)),
                         backend_name);
INSTANTIATE_TEST_SUITE_P(Backends, UpperTriangleFactorization, ::testing::ValuesIn(backends(upper_triangle)),
                         backend_name);
INSTANTIATE_TEST_SUITE_P(Backends, InertiaFactorization, ::testing::ValuesIn(backends(ldlt_inertia)),
                         backend_name);
INSTANTIATE_TEST_SUITE_P(Backends, ExactFactorSizeFactorization, ::testing::ValuesIn(backends(exact_factor_nnz)),
                         backend_name);
// The other quasi-definite backends against the reference CholmodLdlt.
std::vector<Backend> quasi_definite_but_cholmod_ldlt() {
  std::vector<Backend> b;
  for (const Backend& q : backends(quasi_definite))
    if (q.name != "CholmodLdlt") b.push_back(q);
  return b;
}
INSTANTIATE_TEST_SUITE_P(Backends, CholmodLdltAgreement, ::testing::ValuesIn(quasi_definite_but_cholmod_ldlt()),
                         backend_name);

}  // namespace
}  // namespace lcprelax::sparse
