// Lemke's crash start (LemkeSettings::crash_start, lemke.hpp) from the basis of projected
// Gauss–Seidel sweeps (lcp/fc2d_pgs.hpp), with basis repair (sparse::KluLu::
// zero_pivot_columns) when that basis is singular. Measured on the Siconos fc2d problems
// of tests/data/siconos/fc2d (`lcprelax fc2d FILE --crash pgs|none`): the 667-contact
// granular problem takes 568 pivots from the crash basis (one repair round) against 1,405
// cold, FrictionContactProblem00071 67 against 184; FrictionContactProblem00374 and the
// slider-crank are solved by the PGS basis itself (0 pivots); the 2,020-contact granular
// problem 1,900 pivots from the crash basis against 5,274 cold (its final bases are
// feasible only to roundoff: x_B has basic z of −1e-11, and clipping them at 0 would move
// w by 2e-9 through M; Lemke returns the unclipped z there).
// Expected here:
// - zero_pivot_columns names the dependent column of a singular matrix and none of a
//   nonsingular one;
// - PGS converges on FrictionContactProblem00071 (Siconos' fc2d error ≤ 1e-8 after 2,000
//   sweeps), and its basis, when exact, is the solution's (zero pivots);
// - the crash-started solves of all six fc2d files are solved to Siconos' error ≤ 1e-10
//   (scaled to ‖q‖₂ = 1) with no more pivots than the cold start, and the granular one
//   with fewer than half of them, after repairing its singular guess;
// - backward() after a crash start differentiates the final basis: on a P-matrix LCP
//   (unique, nondegenerate solution) crash-started from the basis of a perturbed q, ∂(wᵀz)/∂q
//   equals the cold start's and central differences at every entry.
#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/fc2d_pgs.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/sparse/klu_lu.hpp>

#include "lemke_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace lcprelax {
namespace {

const std::string kFc2d = std::string(LCPRELAX_TEST_DATA_DIR) + "/siconos/fc2d/";

SparseMatrix dense_to_sparse(const DenseMatrix& A) { return A.sparseView(); }

TEST(KluZeroPivotColumns, NamesTheDependentColumn) {
  DenseMatrix A(3, 3);
  A << 1, 0, 1,  //
      0, 2, 2,   //
      3, 1, 4;   // column 2 = column 0 + column 1
  sparse::KluLu klu;
  const SparseMatrix S = dense_to_sparse(A);
  ASSERT_TRUE(klu.analyze(S).ok());
  const std::vector<Index> dependent = klu.zero_pivot_columns(S, 1e-10);
  ASSERT_EQ(dependent.size(), 1u);
  // Removing the named column leaves an invertible matrix: replace it by a unit column.
  DenseMatrix fixed = A;
  fixed.col(dependent[0]).setZero();
  fixed(dependent[0], dependent[0]) = 1.0;
  EXPECT_GT(std::abs(fixed.determinant()), 1e-12);
  DenseMatrix I = DenseMatrix::Identity(3, 3);
  I(0, 1) = 5.0;
  const SparseMatrix T = dense_to_sparse(I);
  sparse::KluLu klu2;
  ASSERT_TRUE(klu2.analyze(T).ok());
  EXPECT_TRUE(klu2.zero_pivot_columns(T, 1e-10).empty());
}

TEST(Fc2dPgs, ConvergesAndItsExactBasisIsTheSolutions) {
  const io::Fc2dData d = io::read_siconos_fc2d(kFc2d + "FrictionContactProblem00071.dat");
  const Fc2dPgsResult pgs = fc2d_pgs(d.W, d.q, d.mu, 2000, 1e-14);
  io::Fc2dData s = d;
  const double norm = d.q.norm();
  s.q /= norm;
  EXPECT_LE(io::fc2d_error(s, pgs.r / norm), 1e-8) << pgs.sweeps << " sweeps";
  for (Index c = 0; c < d.contacts; ++c) {
    EXPECT_GE(pgs.r(2 * c), 0.0);
    EXPECT_LE(std::abs(pgs.r(2 * c + 1)), d.mu(c) * pgs.r(2 * c) * (1 + 1e-12) + 1e-300);
  }
  // On the 28-contact problem the PGS basis is already complementary and feasible.
  const io::Fc2dData e = io::read_siconos_fc2d(kFc2d + "FrictionContactProblem00374.dat");
  const Fc2dLcp lcp = fc2d_to_lcp(e.W, e.q, e.mu);
  const LcpResult r = solve_fc2d_lemke_crash(e.W, e.q, e.mu, lcp, 50);
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  EXPECT_TRUE(r.info.warm_started);
  EXPECT_EQ(r.info.pivots, 0);
}

TEST(LemkeCrashStart, SolvesEverySiconosFc2dFileWithNoMorePivots) {
  for (const char* name : {"FC2D_SliderCrankLagrangian00000", "FrictionContactProblem00031",
                           "FrictionContactProblem00071", "FrictionContactProblem00374",
                           "fc2d_granularflowonwall_00667_00000", "fc2d_granularflowonwall_02020_00213"}) {
    SCOPED_TRACE(name);
    const io::Fc2dData d = io::read_siconos_fc2d(kFc2d + name + ".dat");
    const Fc2dLcp lcp = fc2d_to_lcp(d.W, d.q, d.mu);
    LemkeSolver cold;
    cold.setup(lcp.M, lcp.q);
    const LcpResult c = cold.solve();
    ASSERT_EQ(c.info.status, LcpStatus::solved) << c.info.message;
    EXPECT_LE(test::scaled_fc2d_error(d, c.z), 1e-10);
    const LcpResult r = solve_fc2d_lemke_crash(d.W, d.q, d.mu, lcp, 50);
    ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
    EXPECT_LE(test::scaled_fc2d_error(d, r.z), 1e-10);
    EXPECT_LE(r.info.pivots, c.info.pivots);
    if (std::string(name).rfind("fc2d_granularflowonwall", 0) == 0) {
      EXPECT_TRUE(r.info.crash_started);
      EXPECT_EQ(r.info.crash_pivots, r.info.pivots);  // solved on the crash path
      EXPECT_GT(r.info.repair_rounds, 0);             // the PGS basis was singular
      EXPECT_LT(2 * r.info.pivots, c.info.pivots);
    }
  }
}

TEST(LemkeCrashStart, BackwardDifferentiatesTheFinalBasis) {
  // A P-matrix LCP (M = AᵀA + I, unique solution, nondegenerate for a random q) and a crash
  // basis from the solution of a perturbed q: the crash path pivots to the solution's basis.
  const test::PMatrixLcp p = test::p_matrix_lcp(60, 7);
  const SparseMatrix& M = p.M;
  const Vector &q = p.q, &q_guess = p.q_guess, &w = p.w;
  LemkeSolver guess;
  guess.setup(M, q_guess);
  ASSERT_EQ(guess.solve().info.status, LcpStatus::solved);
  LemkeSettings settings;
  settings.crash_start = true;
  settings.crash_flip_rounds = 0;  // a Lemke crash path (the flips solve this P-matrix LCP at once)
  LemkeSolver crash(settings), cold;
  crash.setup(M, q);
  crash.warm_start(guess.result().z_basic);
  const LcpResult& rc = crash.solve();
  ASSERT_EQ(rc.info.status, LcpStatus::solved) << rc.info.message;
  ASSERT_TRUE(rc.info.crash_started);
  ASSERT_GT(rc.info.crash_pivots, 0);
  cold.setup(M, q);
  const LcpResult& r0 = cold.solve();
  ASSERT_EQ(r0.info.status, LcpStatus::solved);
  EXPECT_LT(rc.info.pivots, r0.info.pivots);
  ASSERT_LE((rc.z - r0.z).lpNorm<Eigen::Infinity>(), 1e-10 * (1.0 + r0.z.lpNorm<Eigen::Infinity>()));
  const Vector g_crash = crash.backward(w).dq, g_cold = cold.backward(w).dq;
  EXPECT_LE((g_crash - g_cold).lpNorm<Eigen::Infinity>(), 1e-10 * (1.0 + g_cold.lpNorm<Eigen::Infinity>()));
  test::expect_q_gradient_matches_central_differences(p, g_crash);  // ℓ(q) = wᵀz(q)
}

TEST(LemkeCrashStart, WithoutColdFallbackTheCrashPathAloneIsCapped) {
  // LemkeSettings::crash_cold_fallback = false: a crash path stopped by max_pivots ends the
  // solve (status pivot_limit, at most max_pivots pivots); with the default the cold start
  // runs after it in the same solve, and the pivots add up beyond max_pivots.
  const Index n = 40;
  std::mt19937 gen(3);
  std::normal_distribution<double> normal;
  DenseMatrix A = DenseMatrix::Zero(n, n);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j) A(i, j) = (i + 2 * j) % 3 == 0 ? normal(gen) : 0.0;
  const SparseMatrix M = dense_to_sparse(A.transpose() * A + DenseMatrix::Identity(n, n));
  Vector q(n);
  for (Index i = 0; i < n; ++i) q(i) = normal(gen);
  std::vector<bool> far(static_cast<std::size_t>(n));  // the complement of the solution's basis
  LemkeSolver exact;
  exact.setup(M, q);
  ASSERT_EQ(exact.solve().info.status, LcpStatus::solved);
  for (Index i = 0; i < n; ++i) far[static_cast<std::size_t>(i)] = !exact.result().z_basic[static_cast<std::size_t>(i)];
  for (bool fallback : {false, true}) {
    LemkeSettings settings;
    settings.crash_start = true;
    settings.crash_flip_rounds = 0;  // the crash path itself is capped here
    settings.crash_cold_fallback = fallback;
    settings.max_pivots = 2;
    settings.covering_retries = 0;
    settings.regularization_retries = 0;
    LemkeSolver s(settings);
    s.setup(M, q);
    s.warm_start(far);
    const LcpResult& r = s.solve();
    if (!fallback) {
      EXPECT_TRUE(r.info.status == LcpStatus::pivot_limit || r.info.status == LcpStatus::numerical_error)
          << r.info.message;
      EXPECT_LE(r.info.pivots, 2);
    } else {
      EXPECT_GT(r.info.pivots, 2) << r.info.message;
    }
  }
}

}  // namespace
}  // namespace lcprelax
