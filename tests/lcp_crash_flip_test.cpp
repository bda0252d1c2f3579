// Block principal pivoting rounds on a crash basis (LemkeSettings::crash_flip_rounds,
// lemke_crash.cpp) before Lemke runs from it. Measured (build/apps/lcprelax fc2d, and the
// same solves through LemkeSolver with crash_flip_rounds 0 / 5, 50 PGS sweeps):
// granular 667 contacts 33 pivots against 568, granular 2,020 contacts 1,383 against 1,900;
// from 10 or 200 sweeps the 2,020-contact crash path ends on a ray with and without the
// rounds (then the cold start runs). On fc2d problems exported from `lcprelax pile` the
// crash paths end on a ray either way (no gain, no loss).
// Expected here:
// - 667-contact granular problem (tests/data/siconos/fc2d), crash basis from 50 PGS sweeps:
//   solved to Siconos' fc2d error ≤ 1e-10 (scaled to ‖q‖₂ = 1) with and without the
//   rounds, with fewer than a fifth of the pivots with them, and the same complementary
//   solution (r equal to 1e-8 relative; the bases differ in degenerate entries: a basic
//   z at 0 in one is nonbasic in the other);
// - a generated pile problem (tests/data/generated, 186 contacts) is still solved (the crash
//   path fails there and the cold fallback solves it) to the same error bound;
// - a P-matrix LCP (M = AᵀA + I, n = 60) from the solution basis of a perturbed q: the
//   rounds reach the solution with fewer pivots than the crash path without them, and
//   backward() with that basis equals the cold start's and central differences (h = 1e-6,
//   tolerance 1e-6 relative) at every entry of q;
// - a negative crash_flip_rounds is refused.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/fc2d_pgs.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include "lemke_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace lcprelax {
namespace {

const std::string kData = std::string(LCPRELAX_TEST_DATA_DIR);

struct CrashRun {
  LcpResult result;
  Vector r;
  double error = 0;
};

CrashRun crash_solve(const io::Fc2dData& d, int flip_rounds) {
  const Fc2dLcp lcp = fc2d_to_lcp(d.W, d.q, d.mu);
  LemkeSettings s;
  s.crash_flip_rounds = flip_rounds;
  CrashRun out;
  out.result = solve_fc2d_lemke_crash(d.W, d.q, d.mu, lcp, 50, s);
  Vector u;
  if (out.result.z.size() == lcp.q.size()) fc2d_from_lcp(out.result.z, d.W, d.q, out.r, u);
  io::Fc2dData scaled = d;
  const double qn = d.q.norm() > 0 ? d.q.norm() : 1.0;
  scaled.q /= qn;
  out.error = out.r.size() ? io::fc2d_error(scaled, out.r / qn) : 1.0;
  return out;
}

TEST(LemkeCrashFlip, GranularFewerPivotsSameSolution) {
  const io::Fc2dData d = io::read_siconos_fc2d(kData + "/siconos/fc2d/fc2d_granularflowonwall_00667_00000.dat");
  const CrashRun without = crash_solve(d, 0), with = crash_solve(d, 5);
  ASSERT_EQ(without.result.info.status, LcpStatus::solved);
  ASSERT_EQ(with.result.info.status, LcpStatus::solved);
  EXPECT_TRUE(with.result.info.crash_started);
  EXPECT_LE(without.error, 1e-10);
  EXPECT_LE(with.error, 1e-10);
  EXPECT_LT(5 * with.result.info.pivots, without.result.info.pivots)
      << with.result.info.pivots << " pivots with the rounds, " << without.result.info.pivots << " without";
  EXPECT_LE((with.r - without.r).lpNorm<Eigen::Infinity>(), 1e-8 * without.r.lpNorm<Eigen::Infinity>());
}

TEST(LemkeCrashFlip, GeneratedPileStillSolved) {
  const io::Fc2dData d = io::read_siconos_fc2d(kData + "/generated/fc2d_pile_00186_b60_s150.dat");
  ASSERT_EQ(d.contacts, 186);
  for (int rounds : {0, 5}) {
    const CrashRun run = crash_solve(d, rounds);
    EXPECT_EQ(run.result.info.status, LcpStatus::solved) << rounds << " rounds: " << run.result.info.message;
    EXPECT_LE(run.error, 1e-10) << rounds << " rounds";
  }
}

TEST(LemkeCrashFlip, BackwardWithTheFlippedBasis) {
  const test::PMatrixLcp p = test::p_matrix_lcp(60, 7);
  const SparseMatrix& M = p.M;
  const Vector &q = p.q, &q_guess = p.q_guess, &w = p.w;
  LemkeSolver guess;
  guess.setup(M, q_guess);
  ASSERT_EQ(guess.solve().info.status, LcpStatus::solved);
  long pivots[2] = {0, 0};
  Vector g_flip;
  LemkeSolver cold;
  cold.setup(M, q);
  const LcpResult& r0 = cold.solve();
  ASSERT_EQ(r0.info.status, LcpStatus::solved);
  for (int rounds : {0, 5}) {
    LemkeSettings settings;
    settings.crash_start = true;
    settings.crash_flip_rounds = rounds;
    LemkeSolver crash(settings);
    crash.setup(M, q);
    crash.warm_start(guess.result().z_basic);
    const LcpResult& rc = crash.solve();
    ASSERT_EQ(rc.info.status, LcpStatus::solved) << rc.info.message;
    ASSERT_LE((rc.z - r0.z).lpNorm<Eigen::Infinity>(), 1e-10 * (1.0 + r0.z.lpNorm<Eigen::Infinity>()));
    pivots[rounds ? 1 : 0] = rc.info.pivots;
    if (rounds) g_flip = crash.backward(w).dq;
  }
  EXPECT_LT(pivots[1], pivots[0]);
  const Vector g_cold = cold.backward(w).dq;
  EXPECT_LE((g_flip - g_cold).lpNorm<Eigen::Infinity>(), 1e-10 * (1.0 + g_cold.lpNorm<Eigen::Infinity>()));
  test::expect_q_gradient_matches_central_differences(p, g_flip);
}

TEST(LemkeCrashFlip, NegativeRoundsRefused) {
  LemkeSettings s;
  s.crash_flip_rounds = -1;
  EXPECT_FALSE(s.validation_error().empty());
  EXPECT_THROW(LemkeSolver{s}, InputError);
}

}  // namespace
}  // namespace lcprelax
