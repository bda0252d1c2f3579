// Sparse Lemke (KLU basis + Schur-complement block update) against the dense path: same
// status, solution and pivot count on random P-matrix and monotone LCPs; backward pass
// against central differences; warm start; small refactorization intervals; and a
// 20,000-unknown problem that only the sparse path can hold (a dense B⁻¹ would be 3.2 GB).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

LemkeSettings with(LemkeMethod method, int refactor_interval = LemkeSettings{}.refactor_interval) {
  LemkeSettings s;
  s.method = method;
  s.refactor_interval = refactor_interval;
  return s;
}

LcpResult solve(const SparseMatrix& M, const Vector& q, const LemkeSettings& settings) {
  LemkeSolver solver(settings);
  solver.setup(M, q);
  return solver.solve();
}

// Independent check of a returned solution: z ≥ 0, w = Mz + q ≥ 0, z ⊥ w (relative to q).
void expect_lcp_solution(const SparseMatrix& M, const Vector& q, const LcpResult& r) {
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  const double tol = 1e-9 * std::max(1.0, q.lpNorm<Eigen::Infinity>());
  const Vector w = M * r.z + q;
  EXPECT_GE(r.z.minCoeff(), 0.0);
  EXPECT_GE(w.minCoeff(), -tol);
  EXPECT_LE(r.z.cwiseMin(w).cwiseAbs().maxCoeff(), tol);
}

// Sparse random matrix with about k entries per column, N(0, 1) values.
SparseMatrix random_sparse(std::mt19937& rng, Index rows, Index cols, int k) {
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_int_distribution<Index> row(0, rows - 1);
  std::vector<Triplet> t;
  for (Index j = 0; j < cols; ++j)
    for (int e = 0; e < k; ++e) t.emplace_back(row(rng), j, N(rng));
  SparseMatrix A(rows, cols);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

SparseMatrix identity(Index n) {
  SparseMatrix I(n, n);
  I.setIdentity();
  return I;
}

// P-matrices: kind 0 is A Aᵀ + I (symmetric positive definite); kind 1 is nonsymmetric,
// strictly row diagonally dominant with a positive diagonal (so are all its principal
// submatrices, hence all principal minors are positive).
SparseMatrix random_p_matrix(std::mt19937& rng, Index n, int kind) {
  if (kind == 0) {
    const SparseMatrix A = random_sparse(rng, n, n, 2);
    SparseMatrix M = A * SparseMatrix(A.transpose()) + identity(n);
    M.makeCompressed();
    return M;
  }
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_int_distribution<Index> col(0, n - 1);
  std::uniform_real_distribution<double> U(0.1, 1.0);
  std::vector<Triplet> t;
  for (Index i = 0; i < n; ++i) {
    double off = 0.0;
    for (int e = 0; e < 4; ++e) {
      const Index j = col(rng);
      if (j == i) continue;
      const double v = N(rng);
      off += std::abs(v);  // duplicates sum, |a + b| ≤ |a| + |b|: still dominant
      t.emplace_back(i, j, v);
    }
    t.emplace_back(i, i, off + U(rng));
  }
  SparseMatrix M(n, n);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

// Monotone LCP: M = B Bᵀ + S (B n×n/2, rank deficient; S skew), q = w* − M z* with a
// complementary pair z*, w* ≥ 0, so the LCP is feasible and Lemke must solve it.
void random_monotone_lcp(std::mt19937& rng, Index n, SparseMatrix& M, Vector& q) {
  const SparseMatrix B = random_sparse(rng, n, std::max<Index>(n / 2, 1), 3);
  const SparseMatrix R = random_sparse(rng, n, n, 1);
  M = B * SparseMatrix(B.transpose()) + 0.5 * (R - SparseMatrix(R.transpose()));
  M.makeCompressed();
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Vector z = Vector::Zero(n), w = Vector::Zero(n);
  for (Index i = 0; i < n; ++i) (U(rng) < 0.5 ? z(i) : w(i)) = U(rng) + 0.1;
  q = w - M * z;
}

Vector random_vector(std::mt19937& rng, Index n) {
  std::normal_distribution<double> N(0.0, 1.0);
  return Vector::NullaryExpr(n, [&] { return N(rng); });
}

void expect_same(const LcpResult& dense, const LcpResult& sparse, const char* what) {
  ASSERT_EQ(dense.info.method, LemkeMethod::dense);
  ASSERT_EQ(sparse.info.method, LemkeMethod::sparse);
  ASSERT_EQ(dense.info.status, sparse.info.status)
      << what << ": " << dense.info.message << " / " << sparse.info.message;
  EXPECT_EQ(dense.info.pivots, sparse.info.pivots) << what;
  if (dense.info.status != LcpStatus::solved) return;
  const double scale = std::max(1.0, dense.z.lpNorm<Eigen::Infinity>());
  EXPECT_LE((dense.z - sparse.z).lpNorm<Eigen::Infinity>(), 1e-9 * scale) << what;
  EXPECT_EQ(dense.z_basic, sparse.z_basic) << what;
}

class LemkeSparseVsDense : public ::testing::TestWithParam<Index> {};

TEST_P(LemkeSparseVsDense, RandomPMatrixLcps) {
  const Index n = GetParam();
  for (int kind : {0, 1})
    for (unsigned seed = 1; seed <= 3; ++seed) {
      std::mt19937 rng(1000 * seed + 10 * kind + static_cast<unsigned>(n));
      const SparseMatrix M = random_p_matrix(rng, n, kind);
      const Vector q = random_vector(rng, n);
      const LcpResult d = solve(M, q, with(LemkeMethod::dense));
      const LcpResult s = solve(M, q, with(LemkeMethod::sparse));
      SCOPED_TRACE("n = " + std::to_string(n) + ", kind " + std::to_string(kind) + ", seed " + std::to_string(seed));
      expect_lcp_solution(M, q, s);  // a P-matrix LCP always has a (unique) solution
      expect_same(d, s, "P-matrix");
    }
}

TEST_P(LemkeSparseVsDense, RandomMonotoneLcps) {
  const Index n = GetParam();
  for (unsigned seed = 1; seed <= 3; ++seed) {
    std::mt19937 rng(7000 * seed + static_cast<unsigned>(n));
    SparseMatrix M;
    Vector q;
    random_monotone_lcp(rng, n, M, q);
    const LcpResult d = solve(M, q, with(LemkeMethod::dense));
    const LcpResult s = solve(M, q, with(LemkeMethod::sparse));
    SCOPED_TRACE("n = " + std::to_string(n) + ", seed " + std::to_string(seed));
    expect_lcp_solution(M, q, s);  // feasible monotone LCP: Lemke does not end on a ray
    expect_same(d, s, "monotone");
  }
}

INSTANTIATE_TEST_SUITE_P(Sizes, LemkeSparseVsDense, ::testing::Values(5, 20, 60, 150, 300));

// ℓ(z) = gᵀz: sparse backward ∂ℓ/∂q and ∂ℓ/∂M_ij (every stored entry) against central
// differences, only at non-degenerate solutions (min_i z_i + w_i > 1e-6) where the
// solution map is differentiable.
TEST(LemkeSparse, BackwardMatchesCentralDifferences) {
  int checked = 0;
  for (Index n : {10, 25})
    for (int kind : {0, 1})
      for (unsigned seed = 1; seed <= 3; ++seed) {
        std::mt19937 rng(500 + 100 * seed + 10 * kind + static_cast<unsigned>(n));
        const SparseMatrix M = random_p_matrix(rng, n, kind);
        const Vector q = random_vector(rng, n);
        const Vector g = random_vector(rng, n);
        LemkeSolver solver(with(LemkeMethod::sparse));
        solver.setup(M, q);
        const LcpResult& r = solver.solve();
        ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
        if ((r.z + r.w).minCoeff() <= 1e-6) continue;  // degenerate: not differentiable
        ++checked;
        const LcpGradient grad = solver.backward(g);
        ASSERT_EQ(grad.dM.nonZeros(), M.nonZeros());  // on M's pattern
        auto loss = [&](const SparseMatrix& Mp, const Vector& qp) {
          const LcpResult rp = solve(Mp, qp, with(LemkeMethod::sparse));
          EXPECT_EQ(rp.info.status, LcpStatus::solved);
          return g.dot(rp.z);
        };
        const double h = 1e-6;
        for (Index i = 0; i < n; ++i) {
          Vector qp = q, qm = q;
          qp(i) += h;
          qm(i) -= h;
          const double fd = (loss(M, qp) - loss(M, qm)) / (2 * h);
          EXPECT_NEAR(fd, grad.dq(i), 1e-6 * std::max(1.0, std::abs(fd))) << "dq " << i;
        }
        for (Index k = 0; k < M.nonZeros(); ++k) {
          SparseMatrix Mp = M, Mm = M;
          Mp.valuePtr()[k] += h;
          Mm.valuePtr()[k] -= h;
          const double fd = (loss(Mp, q) - loss(Mm, q)) / (2 * h);
          EXPECT_NEAR(fd, grad.dM.valuePtr()[k], 1e-6 * std::max(1.0, std::abs(fd))) << "dM entry " << k;
        }
      }
  EXPECT_GE(checked, 6) << "too few non-degenerate cases were checked";
}

// The final basis of a solve, given back as a warm start, is complementary and feasible:
// zero pivots. After a small change of q (non-degenerate solution) it still is.
TEST(LemkeSparse, WarmStartFromThePreviousBasisTakesZeroPivots) {
  std::mt19937 rng(11);
  const Index n = 200;
  const SparseMatrix M = random_p_matrix(rng, n, 1);
  const Vector q = random_vector(rng, n);
  LemkeSolver solver(with(LemkeMethod::sparse));
  solver.setup(M, q);
  const LcpResult cold = solver.solve();
  ASSERT_EQ(cold.info.status, LcpStatus::solved);
  EXPECT_GT(cold.info.pivots, 0);
  EXPECT_FALSE(cold.info.warm_started);
  solver.warm_start(cold.z_basic);
  const LcpResult& warm = solver.solve();
  expect_lcp_solution(M, q, warm);
  EXPECT_EQ(warm.info.method, LemkeMethod::sparse);
  EXPECT_EQ(warm.info.pivots, 0);
  EXPECT_TRUE(warm.info.warm_started);
  EXPECT_LE((warm.z - cold.z).lpNorm<Eigen::Infinity>(), 1e-12 * std::max(1.0, cold.z.lpNorm<Eigen::Infinity>()));

  ASSERT_GT((cold.z + cold.w).minCoeff(), 1e-6);  // non-degenerate: the basis survives a small change
  const Vector q2 = q + 1e-8 * random_vector(rng, n);
  solver.update_q(q2);
  solver.warm_start(cold.z_basic);
  const LcpResult& moved = solver.solve();
  expect_lcp_solution(M, q2, moved);
  EXPECT_EQ(moved.info.pivots, 0);
  EXPECT_TRUE(moved.info.warm_started);
}

// refactor_interval 1, 2, 3 forces a fresh factorization after every few pivots (dense:
// explicit inverse rebuilt; sparse: KLU refactorization, Schur complement reset). The
// answer and the pivot sequence must not change.
TEST(LemkeSparse, SmallRefactorIntervalGivesTheSameAnswer) {
  for (int kind : {0, 1}) {
    std::mt19937 rng(77 + kind);
    const Index n = 120;
    const SparseMatrix M = random_p_matrix(rng, n, kind);
    const Vector q = random_vector(rng, n);
    for (LemkeMethod method : {LemkeMethod::sparse, LemkeMethod::dense}) {
      const LcpResult reference = solve(M, q, with(method));
      expect_lcp_solution(M, q, reference);
      for (int interval : {1, 2, 3}) {
        SCOPED_TRACE(std::string(to_string(method)) + ", kind " + std::to_string(kind) + ", refactor_interval " +
                     std::to_string(interval));
        const LcpResult r = solve(M, q, with(method, interval));
        expect_lcp_solution(M, q, r);
        EXPECT_EQ(r.info.pivots, reference.info.pivots);
        EXPECT_EQ(r.z_basic, reference.z_basic);
        EXPECT_LE((r.z - reference.z).lpNorm<Eigen::Infinity>(),
                  1e-9 * std::max(1.0, reference.z.lpNorm<Eigen::Infinity>()));
        // Dense: a refactorization every `interval` pivots. Sparse: when the update would
        // hold more than `interval` distinct replaced positions (a position replaced again
        // reuses its slot), so fewer; both far more than with the default interval.
        if (method == LemkeMethod::dense) {
          EXPECT_GE(r.info.refactorizations, r.info.pivots / interval);
        }
        EXPECT_GT(r.info.refactorizations, reference.info.refactorizations + r.info.pivots / (2 * interval + 2));
      }
    }
  }
}

// LemkeSettings::lu_pivot_tolerance (KLU's partial-pivoting threshold of the sparse basis)
// and lu_ordering (its column ordering) change how the basis is factorized, not the LCP: on
// P-matrix LCPs (unique solution) KLU's default 0.001 and the range's ends, each with AMD
// (the default) and COLAMD, give the same solution and pivot sequence, with the
// refactorizations of refactor_interval 2 (the lifted bases of regularized pile LCPs:
// lcp_lemke_lifted_basis_test.cpp). Tolerances outside (0, 1] are refused.
TEST(LemkeSparse, LuPivotToleranceAndOrderingKeepTheAnswer) {
  std::mt19937 rng(78);
  const Index n = 120;
  const SparseMatrix M = random_p_matrix(rng, n, 1);
  const Vector q = random_vector(rng, n);
  const LcpResult reference = solve(M, q, with(LemkeMethod::dense));
  EXPECT_EQ(LemkeSettings{}.lu_ordering, LuOrdering::colamd);
  for (LuOrdering o : {LuOrdering::amd, LuOrdering::colamd})
    for (double u : {1.0, 0.001, 1e-6}) {
      SCOPED_TRACE("lu_pivot_tolerance " + std::to_string(u) + ", lu_ordering " + to_string(o));
      LemkeSettings s = with(LemkeMethod::sparse, 2);
      s.lu_pivot_tolerance = u;
      s.lu_ordering = o;
      const LcpResult r = solve(M, q, s);
      expect_lcp_solution(M, q, r);
      EXPECT_EQ(r.z_basic, reference.z_basic);
      EXPECT_EQ(r.info.pivots, reference.info.pivots);
    }
  for (double bad : {0.0, -1.0, 1.5, std::nan("")}) {
    LemkeSettings s;
    s.lu_pivot_tolerance = bad;
    EXPECT_FALSE(s.validation_error().empty()) << bad;
    EXPECT_THROW(LemkeSolver{s}, InputError) << bad;
  }
}

// n = 20,000, banded nonsymmetric diagonally dominant P-matrix (bandwidth 3), q positive
// except at 1% of the rows: `automatic` must choose the sparse path (a dense B⁻¹ would
// need 3.2 GB) and solve it. No timing assertion.
TEST(LemkeSparse, TwentyThousandUnknownsUseTheSparsePath) {
  const Index n = 20000, band = 3;
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<Triplet> t;
  for (Index i = 0; i < n; ++i) {
    double off = 0.0;
    for (Index j = std::max<Index>(0, i - band); j <= std::min<Index>(n - 1, i + band); ++j)
      if (j != i) {
        const double v = U(rng);
        off += std::abs(v);
        t.emplace_back(i, j, v);
      }
    t.emplace_back(i, i, off + 0.5 + 0.5 * std::abs(U(rng)));
  }
  SparseMatrix M(n, n);
  M.setFromTriplets(t.begin(), t.end());
  Vector q = Vector::NullaryExpr(n, [&] { return 1.0 + U(rng); });
  std::uniform_int_distribution<Index> row(0, n - 1);
  for (int k = 0; k < n / 100; ++k) q(row(rng)) = -1.0 - std::abs(U(rng));
  LemkeSolver solver;  // automatic
  solver.setup(M, q);
  const LcpResult& r = solver.solve();
  EXPECT_EQ(r.info.method, LemkeMethod::sparse);
  expect_lcp_solution(M, q, r);
  EXPECT_GE(r.info.pivots, n / 100);
  std::printf("n = %d: %ld pivots, %ld refactorizations, %.3f s\n", n, r.info.pivots, r.info.refactorizations,
              r.info.seconds);
}

// An LCP whose entries span 1e-300 to 1e306 (found by a random search over such matrices):
// the sparse path's basis loses all accuracy after a few pivots and x_B holds NaN. The
// minimum-ratio test then has no finite ratio; it used to take the front of an empty
// candidate list (a crash, first seen on a 20-body pile's LCP). Expected: a clear
// numerical_error status naming the non-finite ratio, never a crash.
TEST(LemkeSparse, NonFiniteRatiosGiveAStatusNotACrash) {
  const double d[6][6] = {
      {0x1.c1dae06de523fp-3, -0x1.c966b6da2a7bep+1017, -0x1.f2a09894311f5p+1013, -0x1.72f49297f8042p+1015,
       0x1.70ac1fe2626a9p-998, -0x1.29674fec0dcc6p-998},
      {-0x1.becb9584896e4p-3, -0x1.c606162d18d82p+0, 0x1.572282765086dp-998, -0x1.41d664e841856p+1016,
       -0x1.cf9f72ff6f00ep-998, 0x1.7fd5ee8b2fb4ap+1016},
      {-0x1.0212e70886145p+1012, -0x1.51972b85f07ep-4, 0x1.2836234106fc5p-1, -0x1.a81489313283bp-4,
       0x1.05af2841fc50ep-999, 0x1.04634763bbbf9p+1},
      {0x1.d0799b5685787p-999, -0x1.61ff59a826462p-996, -0x1.4d5abe918ecf8p+1017, 0x1.991167226f54cp-1,
       -0x1.5792ff03c3973p-2, 0x1.d9881f0c0e08ap-998},
      {0x1.0722762689162p+1017, 0x1.9c01d5c42957ep-999, -0x1.2d79f13b6a815p+1016, -0x1.f8c88b3612efap-2,
       0x1.27b17290e8669p-999, 0x1.4790a90d13edap+0},
      {-0x1.d03fc62247475p-1002, -0x1.efbbeaa122e62p+1013, -0x1.9f074875618dp-2, -0x1.54ebae4978dfp+1016,
       0x1.9fd90a718d7e6p+1016, 0x1.e965364a38c61p-1}};
  const double qv[6] = {0x1.0a5d70c6e5698p-4,  -0x1.4252edfcbca4dp-1, 0x1.0c44861e00a4dp-1,
                        -0x1.bdf15a4dbea7bp-4, 0x1.4dd502abe9d0fp-3,  0x1.76fcc8782159ap-1};
  DenseMatrix D(6, 6);
  Vector q(6);
  for (int i = 0; i < 6; ++i) {
    q(i) = qv[i];
    for (int j = 0; j < 6; ++j) D(i, j) = d[i][j];
  }
  const SparseMatrix M = D.sparseView();
  const LcpResult r = solve(M, q, with(LemkeMethod::sparse));
  EXPECT_NE(r.info.status, LcpStatus::solved);
  EXPECT_NE(r.info.message.find("non-finite ratio"), std::string::npos) << r.info.message;
}

}  // namespace
}  // namespace lcprelax
