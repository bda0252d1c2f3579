// Lemke's purified start (LemkeSolver::warm_start_point, lcp/src/lemke_purify.cpp): an
// approximate solution is driven to a vertex basis before the warm start.
// Expected here:
// - from the exact solution of a nondegenerate P-matrix LCP the purified basis is the
//   solution's (zero pivots, the same z);
// - on a degenerate symmetric LCP M = JJᵀ (m = 40 rows, rank k = 12, like a pile with more
//   contacts than degrees of freedom) with a solution loading every row, purification
//   finds a vertex solution: zero pivots, at most k basic z, residual ≤ 1e-9, and w kept
//   (the point moves only along null directions of M);
// - backward() after a purified start differentiates the final basis: from the solution
//   of a perturbed q (a crash path follows the purification), ∂(wᵀz)/∂q equals the cold
//   start's and central differences;
// - the six Siconos fc2d files of tests/data, from 50 PGS sweeps (fc2d_pgs.hpp,
//   Fc2dCrash::purified): solved to Siconos' error ≤ 1e-10 with no more pivots than from
//   the PGS basis; five in zero pivots (measured: the purified basis is the solution's),
//   the 2,020-contact granular problem in fewer than 200 (measured 83, against 1,383 from
//   the PGS basis and 5,274 cold); the 186-contact polygon pile (its 50-sweep PGS point
//   has complementarity 1e-2: purification leaves pairs with both members basic) falls
//   back to the PGS basis: the same pivots as Fc2dCrash::basis;
// - bad input: a point of the wrong size or with a NaN, or a fallback basis of the wrong
//   size, throws InputError; before setup std::logic_error.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/fc2d_pgs.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include "lemke_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace lcprelax {
namespace {

TEST(LemkePurify, ExactSolutionOfAPMatrixLcpIsItsOwnBasis) {
  const test::PMatrixLcp p = test::p_matrix_lcp(30, 7);
  LemkeSolver cold;
  cold.setup(p.M, p.q);
  const LcpResult reference = cold.solve();
  ASSERT_EQ(reference.info.status, LcpStatus::solved);
  LemkeSolver warm;
  warm.setup(p.M, p.q);
  warm.warm_start_point(reference.z);
  const LcpResult& r = warm.solve();
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  EXPECT_TRUE(r.info.warm_started);
  EXPECT_EQ(r.info.pivots, 0);
  EXPECT_GT(r.info.purification_steps, 0);
  EXPECT_LE((r.z - reference.z).lpNorm<Eigen::Infinity>(), 1e-10 * (1.0 + reference.z.lpNorm<Eigen::Infinity>()));
}

struct DegenerateLcp {
  SparseMatrix M;
  Vector q, z, w;  // a solution z > 0 on every row of the first m_loaded, w = Mz + q
};

// M = JJᵀ (m × m, rank k); z > 0 on rows [0, m_loaded), w = 0 there and w > 0 elsewhere;
// q = w − Mz. The support of z has m_loaded > k dependent columns.
DegenerateLcp degenerate_lcp(Index m, Index k, Index m_loaded, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.5, 2.0);
  DenseMatrix J(m, k);
  for (Index i = 0; i < m; ++i)
    for (Index j = 0; j < k; ++j) J(i, j) = normal(gen);
  DegenerateLcp d;
  const DenseMatrix M = J * J.transpose();
  d.M = M.sparseView();
  d.z = Vector::Zero(m);
  d.w = Vector::Zero(m);
  for (Index i = 0; i < m; ++i) (i < m_loaded ? d.z(i) : d.w(i)) = uniform(gen);
  d.q = d.w - M * d.z;
  return d;
}

TEST(LemkePurify, DegenerateSymmetricLcpGetsAVertexSolutionWithoutPivots) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Index m = 40, k = 12;
    const DegenerateLcp d = degenerate_lcp(m, k, 30, seed);
    LemkeSolver lemke;
    lemke.setup(d.M, d.q);
    lemke.warm_start_point(d.z);
    const LcpResult& r = lemke.solve();
    ASSERT_EQ(r.info.status, LcpStatus::solved) << "seed " << seed << ": " << r.info.message;
    EXPECT_TRUE(r.info.warm_started) << "seed " << seed;
    EXPECT_EQ(r.info.pivots, 0) << "seed " << seed;
    Index basic_z = 0;
    for (bool b : r.z_basic) basic_z += b;
    EXPECT_LE(basic_z, k) << "seed " << seed;
    EXPECT_LE(r.info.complementarity, 1e-9 * d.q.lpNorm<Eigen::Infinity>()) << "seed " << seed;
    EXPECT_GE(r.z.minCoeff(), -1e-12);
    EXPECT_LE((r.w - d.w).lpNorm<Eigen::Infinity>(), 1e-9 * d.q.lpNorm<Eigen::Infinity>()) << "seed " << seed;
  }
}

TEST(LemkePurify, BackwardDifferentiatesTheFinalBasis) {
  const test::PMatrixLcp p = test::p_matrix_lcp(60, 7);
  LemkeSolver guess, cold;
  guess.setup(p.M, p.q_guess);
  ASSERT_EQ(guess.solve().info.status, LcpStatus::solved);
  LemkeSettings settings;
  settings.crash_start = true;
  settings.crash_flip_rounds = 0;
  LemkeSolver purified(settings);
  purified.setup(p.M, p.q);
  purified.warm_start_point(guess.result().z);
  const LcpResult& r = purified.solve();
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  ASSERT_GT(r.info.purification_steps, 0);
  ASSERT_GT(r.info.crash_pivots, 0);  // the perturbed point's vertex is not the solution's
  cold.setup(p.M, p.q);
  const LcpResult& r0 = cold.solve();
  ASSERT_EQ(r0.info.status, LcpStatus::solved);
  ASSERT_LE((r.z - r0.z).lpNorm<Eigen::Infinity>(), 1e-10 * (1.0 + r0.z.lpNorm<Eigen::Infinity>()));
  const Vector g = purified.backward(p.w).dq, g0 = cold.backward(p.w).dq;
  EXPECT_LE((g - g0).lpNorm<Eigen::Infinity>(), 1e-10 * (1.0 + g0.lpNorm<Eigen::Infinity>()));
  test::expect_q_gradient_matches_central_differences(p, g);
}

TEST(LemkePurify, Fc2dFilesFromPgsPoints) {
  const std::string dir = std::string(LCPRELAX_TEST_DATA_DIR);
  struct Case {
    const char* file;
    long most_pivots;  // from the purified start
  };
  for (const Case& c : {Case{"/siconos/fc2d/FC2D_SliderCrankLagrangian00000.dat", 0},
                        Case{"/siconos/fc2d/FrictionContactProblem00031.dat", 0},
                        Case{"/siconos/fc2d/FrictionContactProblem00071.dat", 0},
                        Case{"/siconos/fc2d/FrictionContactProblem00374.dat", 0},
                        Case{"/siconos/fc2d/fc2d_granularflowonwall_00667_00000.dat", 0},
                        Case{"/siconos/fc2d/fc2d_granularflowonwall_02020_00213.dat", 199},
                        Case{"/generated/fc2d_pile_00186_b60_s150.dat", -1}}) {
    SCOPED_TRACE(c.file);
    const io::Fc2dData d = io::read_siconos_fc2d(dir + c.file);
    const Fc2dLcp lcp = fc2d_to_lcp(d.W, d.q, d.mu);
    const LcpResult b = solve_fc2d_lemke_crash(d.W, d.q, d.mu, lcp, 50, {}, nullptr, Fc2dCrash::basis);
    const LcpResult r = solve_fc2d_lemke_crash(d.W, d.q, d.mu, lcp, 50, {}, nullptr, Fc2dCrash::purified);
    ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
    EXPECT_LE(test::scaled_fc2d_error(d, r.z), 1e-10);
    EXPECT_GT(r.info.purification_steps, 0);
    EXPECT_LE(r.info.pivots, b.info.pivots);
    if (c.most_pivots >= 0) {
      EXPECT_LE(r.info.pivots, c.most_pivots);
      EXPECT_EQ(r.info.pivots == 0, r.info.warm_started);
    } else {
      EXPECT_EQ(r.info.pivots, b.info.pivots);  // the fallback basis: the same path
    }
  }
}

TEST(LemkePurify, BadPointsAreRejected) {
  const test::PMatrixLcp p = test::p_matrix_lcp(6, 1);
  LemkeSolver lemke;
  EXPECT_THROW(lemke.warm_start_point(Vector::Zero(6)), std::logic_error);
  lemke.setup(p.M, p.q);
  EXPECT_THROW(lemke.warm_start_point(Vector::Zero(5)), InputError);
  Vector nan = Vector::Zero(6);
  nan(2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(lemke.warm_start_point(nan), InputError);
  EXPECT_THROW(lemke.warm_start_point(Vector::Zero(6), std::vector<bool>(5, false)), InputError);
}

}  // namespace
}  // namespace lcprelax
