// Hypersparse rows of B⁻¹ in Lemke's lexicographic ratio test (LemkeSettings::
// sparse_tie_rows; lcp/src/lemke_lexicographic.hpp, sparse/hypersparse_solve.hpp):
// - the hypersparse transposed and column solves with KLU's factors agree with KLU's own
//   dense solves, on matrices where KLU finds BTF blocks (so the off-diagonal block F
//   takes part) and scales rows, and reach few nodes when the solution is sparse; the dense
//   solve that skips zero entries repeats klu_solve bit for bit;
// - Lemke with sparse tie rows takes exactly the pivot sequence of the full-row reference on
//   degenerate LCPs (granular fc2d, 667 contacts; a redundant-contact LCP), where most
//   pivots are decided by ties on rows of B⁻¹; so does Lemke with hypersparse entering
//   columns (LemkeSettings::sparse_columns) against dense column solves, on those and on a
//   polygon pile's LCP.
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/sparse/hypersparse_column_solve.hpp>
#include <lcprelax/sparse/hypersparse_solve.hpp>
#include <lcprelax/sparse/klu_lu.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

// A block upper triangular matrix (diagonal blocks of 1–8, diagonally dominant, sparse
// entries above them) with its rows and columns permuted and rows scaled by 10^[−3, 3]:
// KLU's BTF recovers the blocks, so L, U and F all take part.
SparseMatrix permuted_block_triangular(std::mt19937& rng, Index n) {
  std::uniform_int_distribution<Index> size(1, 8);
  std::uniform_real_distribution<double> value(-1.0, 1.0), exponent(-3.0, 3.0), coin(0.0, 1.0);
  std::vector<Index> start;
  for (Index b = 0; b < n; b += size(rng)) start.push_back(b);
  start.push_back(n);
  std::vector<Triplet> t;
  for (std::size_t k = 0; k + 1 < start.size(); ++k)
    for (Index j = start[k]; j < start[k + 1]; ++j) {
      for (Index i = start[k]; i < start[k + 1]; ++i)
        if (i == j) t.emplace_back(i, j, 10.0 + value(rng));
        else if (coin(rng) < 0.6) t.emplace_back(i, j, value(rng));
      for (Index i = 0; i < start[k]; ++i)
        if (coin(rng) < 2.0 / static_cast<double>(n)) t.emplace_back(i, j, value(rng));
    }
  std::vector<Index> rp(static_cast<std::size_t>(n)), cp(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) rp[static_cast<std::size_t>(i)] = cp[static_cast<std::size_t>(i)] = i;
  std::shuffle(rp.begin(), rp.end(), rng);
  std::shuffle(cp.begin(), cp.end(), rng);
  std::vector<double> scale(static_cast<std::size_t>(n));
  for (double& s : scale) s = std::pow(10.0, exponent(rng));
  for (Triplet& e : t) {
    const Index i = rp[static_cast<std::size_t>(e.row())];
    e = Triplet(i, cp[static_cast<std::size_t>(e.col())], e.value() * scale[static_cast<std::size_t>(i)]);
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

// Both hypersparse solvers against KLU's dense solves (transposed or not) on the matrices
// above, for right-hand sides of 1–3 nonzeros.
template <class Solver>
void check_against_klu(bool transposed) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 6; ++trial) {
    const Index n = trial < 3 ? 40 : 400;
    const SparseMatrix A = permuted_block_triangular(rng, n);
    sparse::KluLu klu;
    ASSERT_TRUE(klu.analyze(A).ok());
    ASSERT_TRUE(klu.factorize(A).ok());
    Solver h;
    h.reserve(klu);
    ASSERT_TRUE(h.build(klu));
    std::uniform_int_distribution<Index> pick(0, n - 1);
    std::normal_distribution<double> N(0.0, 1.0);
    std::vector<int> y_index;
    std::vector<double> y_value;
    long reached = 0;
    for (int rhs = 0; rhs < 30; ++rhs) {
      std::vector<int> b_index;
      std::vector<double> b_value;
      const int nb = 1 + rhs % 3;
      for (int k = 0; k < nb; ++k) {
        const int i = static_cast<int>(pick(rng));
        if (std::find(b_index.begin(), b_index.end(), i) != b_index.end()) continue;
        b_index.push_back(i);
        b_value.push_back(N(rng));
      }
      Vector x = Vector::Zero(n);
      for (std::size_t k = 0; k < b_index.size(); ++k) x(b_index[k]) = b_value[k];
      ASSERT_TRUE((transposed ? klu.solve_transposed(x) : klu.solve(x)).ok());
      h.solve(static_cast<int>(b_index.size()), b_index.data(), b_value.data(), y_index, y_value);
      reached += h.last_reach();
      Vector y = Vector::Zero(n);
      for (std::size_t k = 0; k < y_index.size(); ++k) {
        EXPECT_EQ(y(y_index[k]), 0.0) << "position reported twice";
        y(y_index[k]) = y_value[k];
      }
      const double scale = std::max(1.0, x.lpNorm<Eigen::Infinity>());
      EXPECT_LE((x - y).lpNorm<Eigen::Infinity>(), 1e-12 * scale) << "n " << n << ", trial " << trial;
    }
    // Block triangular with few couplings: a unit right-hand side reaches a small part of
    // the 2n nodes (v and u per position).
    if (n == 400) {
      EXPECT_LT(reached, 30L * n);
    }
  }
}

TEST(HypersparseTransposedSolve, AgreesWithKluDenseTransposedSolve) {
  check_against_klu<sparse::HypersparseTransposedSolver>(true);
}

TEST(HypersparseColumnSolve, AgreesWithKluDenseSolve) { check_against_klu<sparse::HypersparseColumnSolver>(false); }

// solve_dense against klu_solve on the same matrices, for right-hand sides 2% and 50% dense
// (the solutions then have zero entries, whose columns are skipped): klu_solve's sums in its
// order, so the results are the same to the last bit; the count of nonzeros is returned.
TEST(HypersparseColumnSolve, DenseSolveRepeatsKluSolveBitForBit) {
  std::mt19937 rng(23);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    const Index n = trial < 2 ? 40 : 400;
    const SparseMatrix A = permuted_block_triangular(rng, n);
    sparse::KluLu klu;
    ASSERT_TRUE(klu.analyze(A).ok());
    ASSERT_TRUE(klu.factorize(A).ok());
    sparse::HypersparseColumnSolver h;
    h.reserve(klu);
    ASSERT_TRUE(h.build(klu));
    for (int rhs = 0; rhs < 10; ++rhs) {
      std::vector<int> b_index;
      std::vector<double> b_value;
      for (Index i = 0; i < n; ++i)
        if (coin(rng) < (rhs < 5 ? 0.02 : 0.5)) b_index.push_back(static_cast<int>(i)), b_value.push_back(N(rng));
      Vector x = Vector::Zero(n);
      for (std::size_t k = 0; k < b_index.size(); ++k) x(b_index[k]) = b_value[k];
      ASSERT_TRUE(klu.solve(x).ok());
      Vector y = Vector::Constant(n, 7.0);  // overwritten entirely
      const Index nonzeros = h.solve_dense(static_cast<int>(b_index.size()), b_index.data(), b_value.data(), y);
      for (Index i = 0; i < n; ++i) ASSERT_EQ(y(i), x(i)) << "n " << n << ", trial " << trial << ", entry " << i;
      EXPECT_EQ(nonzeros, (x.array() != 0.0).count());
    }
  }
}

struct Traced {
  LcpResult result;
  std::vector<Index> trace;  // entering, leaving variable per pivot
};

Traced solve_traced(const SparseMatrix& M, const Vector& q, bool sparse_rows, bool sparse_columns,
                    double lu_pivot_tolerance, LuOrdering lu_ordering) {
  LemkeSettings s;
  s.method = LemkeMethod::sparse;
  s.lu_pivot_tolerance = lu_pivot_tolerance;
  s.lu_ordering = lu_ordering;
  s.sparse_tie_rows = sparse_rows;
  s.sparse_columns = sparse_columns;
  s.covering_retries = 0;
  s.regularization_retries = 0;
  LemkeSolver solver(s);
  Traced t;
  solver.set_pivot_trace(&t.trace);
  solver.setup(M, q);
  t.result = solver.solve();
  return t;
}

// The reference (dense solves of the chosen kind) and the hypersparse variant take the same
// pivots: rows = true compares tie rows (full vs sparse, dense columns in both), rows =
// false the entering columns (dense vs sparse, sparse tie rows in both).
// Both end with the same status; `must_solve`: that status must be `solved`. Without it,
// any end is accepted: a plain Lemke path (no retries) of a degenerate pile may end on a
// ray or, where roundoff led it to a singular basis or an inaccurate end, with a numerical
// error, and which one depends on the factorization's roundoff (its orderings), not on the
// variant under test.
// `lu`, `ordering`: LemkeSettings::lu_pivot_tolerance and lu_ordering of both.
void expect_same_pivots(const SparseMatrix& M, const Vector& q, long min_tie_breaks, bool rows = true,
                        bool must_solve = true, double lu = LemkeSettings{}.lu_pivot_tolerance,
                        LuOrdering ordering = LemkeSettings{}.lu_ordering) {
  const Traced full = solve_traced(M, q, !rows, false, lu, ordering);  // full tie rows or dense columns
  const Traced sparse = solve_traced(M, q, true, !rows, lu, ordering);
  std::printf("full: %s %ld pivots %ld ties; sparse: %s %ld pivots %ld ties\n", to_string(full.result.info.status),
              full.result.info.pivots, full.result.info.tie_breaks, to_string(sparse.result.info.status),
              sparse.result.info.pivots, sparse.result.info.tie_breaks);
  if (must_solve) {
    ASSERT_EQ(full.result.info.status, LcpStatus::solved) << full.result.info.message;
  }
  ASSERT_EQ(sparse.result.info.status, full.result.info.status) << sparse.result.info.message;
  ASSERT_NE(full.result.info.status, LcpStatus::pivot_limit);
  EXPECT_GE(sparse.result.info.tie_breaks, min_tie_breaks);
  EXPECT_EQ(sparse.result.info.tie_breaks, full.result.info.tie_breaks);
  EXPECT_EQ(sparse.result.info.pivots, full.result.info.pivots);
  ASSERT_EQ(sparse.trace.size(), full.trace.size());
  for (std::size_t k = 0; k < full.trace.size(); ++k)
    ASSERT_EQ(sparse.trace[k], full.trace[k]) << "pivot " << k / 2;
  if (full.result.info.status != LcpStatus::solved) return;
  EXPECT_EQ(sparse.result.z_basic, full.result.z_basic);
  EXPECT_LE((sparse.result.z - full.result.z).lpNorm<Eigen::Infinity>(),
            1e-9 * std::max(1.0, full.result.z.lpNorm<Eigen::Infinity>()));
}

TEST(LemkeSparseTieRows, SamePivotSequenceAsFullRowsOnGranularFc2d) {
  const io::Fc2dData d = io::read_siconos_fc2d(std::string(LCPRELAX_TEST_DATA_DIR) +
                                               "/siconos/fc2d/fc2d_granularflowonwall_00667_00000.dat");
  const Fc2dLcp lcp = fc2d_to_lcp(d.W, d.q, d.mu);
  expect_same_pivots(lcp.M, lcp.q, 50);
}

TEST(LemkeSparseColumns, SamePivotSequenceAsDenseSolvesOnGranularFc2d) {
  const io::Fc2dData d = io::read_siconos_fc2d(std::string(LCPRELAX_TEST_DATA_DIR) +
                                               "/siconos/fc2d/fc2d_granularflowonwall_00667_00000.dat");
  const Fc2dLcp lcp = fc2d_to_lcp(d.W, d.q, d.mu);
  expect_same_pivots(lcp.M, lcp.q, 50, /*rows=*/false);
}

// A pile of polygons (tests/data/generated, 186 contacts): the degenerate family. With AMD:
// with COLAMD (the default) the two column solves' plain paths part by roundoff (measured:
// the dense one ends on a ray at pivot 726, the hypersparse one on a singular basis at 603),
// as they do on the redundant contacts below; the ordering decides where a degenerate path
// goes, and where the two solves' roundoff starts to matter.
TEST(LemkeSparseColumns, SamePivotSequenceAsDenseSolvesOnPolygonPile) {
  const io::Fc2dData d =
      io::read_siconos_fc2d(std::string(LCPRELAX_TEST_DATA_DIR) + "/generated/fc2d_pile_00186_b60_s150.dat");
  const Fc2dLcp lcp = fc2d_to_lcp(d.W, d.q, d.mu);
  expect_same_pivots(lcp.M, lcp.q, 0, /*rows=*/false, /*must_solve=*/false,  // cold, no retries
                     LemkeSettings{}.lu_pivot_tolerance, LuOrdering::amd);
}

// Redundant contacts: M = J Jᵀ (positive semidefinite, singular) with J (3k × k), and q =
// w* − M z* for a solution z* ≥ 0, w* ≥ 0 with z*_i = w*_i = 0 in a third of the rows (a
// solvable, highly degenerate LCP).
SparseMatrix redundant_contacts(Vector& q) {
  std::mt19937 rng(5);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_int_distribution<Index> body(0, 99);
  const Index k = 100, n = 300;
  std::vector<Triplet> t;
  for (Index i = 0; i < n; ++i)
    for (int e = 0; e < 3; ++e) t.emplace_back(i, body(rng), N(rng));
  SparseMatrix J(n, k);
  J.setFromTriplets(t.begin(), t.end());
  SparseMatrix M = J * SparseMatrix(J.transpose());
  M.makeCompressed();
  Vector z = Vector::Zero(n), w = Vector::Zero(n);
  for (Index i = 0; i < n; ++i) {
    if (i % 3 == 0) z(i) = std::abs(N(rng));
    if (i % 3 == 1) w(i) = std::abs(N(rng));
  }
  q = w - M * z;
  return M;
}

// Whether its degenerate ratios tie is decided by roundoff: its path has tie-breaks with
// KLU's sparsity-favouring pivoting threshold (0.001) and AMD, none with true partial
// pivoting (the default, LemkeSettings::lu_pivot_tolerance) or with COLAMD (the default
// ordering), so it runs with the former two, whose plain path may also end inaccurate (a
// numerical error), depending on the factors' roundoff. Solving
// it is SolvesRedundantContactsWithTheDefaultRetries' test; the granular problem above has
// ties with the default and must solve.
TEST(LemkeSparseTieRows, SamePivotSequenceAsFullRowsOnRedundantContacts) {
  Vector q;
  const SparseMatrix M = redundant_contacts(q);
  expect_same_pivots(M, q, 1, true, /*must_solve=*/false, 0.001, LuOrdering::amd);
}

// Its path visits nearly singular bases (KLU's rcond 1e-15…1e-13, measured), where the two
// column solves differ by amplified roundoff (up to 1e-1 relative) and the plain pivot
// paths part; with the default retries both solve the LCP to its tolerance.
TEST(LemkeSparseColumns, SolvesRedundantContactsWithTheDefaultRetries) {
  Vector q;
  const SparseMatrix M = redundant_contacts(q);
  for (const bool columns : {false, true}) {
    LemkeSettings s;
    s.method = LemkeMethod::sparse;
    s.sparse_columns = columns;
    LemkeSolver solver(s);
    solver.setup(M, q);
    const LcpResult& r = solver.solve();
    ASSERT_EQ(r.info.status, LcpStatus::solved) << "sparse_columns " << columns << ": " << r.info.message;
    const Vector w = M * r.z + q;
    EXPECT_LE(r.z.cwiseMin(w).cwiseAbs().maxCoeff(), 1e-9 * q.lpNorm<Eigen::Infinity>());
    EXPECT_GE(r.z.minCoeff(), 0.0);
  }
}

}  // namespace
}  // namespace lcprelax
