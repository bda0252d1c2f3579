// Step 1c of the lcp model (contact_step.hpp): where step 1b (the crash path on M from the
// warm basis) finds nothing, M + εI is solved from the warm basis before any cold start.
// A warm basis that came from a regularized answer is a basis of M + εI; on M it may be
// singular or its LCP infeasible, so step 1b cannot use it, while on M + εI it solves in a
// few pivots.
//
// Step 1c runs only for a warm basis from an inexact or failed answer (warm_from_regularized).
//
// Scene: tests/models_lcp_regularized_test.cpp's wedged box with a q bias b = −1e-6 m/s on
// its normal rows, whose LCP on M has no solution: the cold attempts end with step 4's
// regularized answer. Expected, warm-started from that answer's basis:
// - the answer is again regularized (solved_inaccurate, residual within
//   kLcpRegularizedResidual·‖q‖∞), found from the warm basis on M + εI (step 1c; step 4
//   is a cold path), step 2 skipped, kept when step 3 fails: fewer pivots than the cold
//   attempts took;
// - with accept_perturbed (an island whose last answer was inexact) step 3 is skipped as
//   well: fewer attempts than without;
// - without warm_from_regularized step 1c runs last (step 6), when everything else failed:
//   with the caller's max_pivots = 1 every cold attempt stops at once (1b and 1c are capped
//   by kLcpWarmCrashPivotsPerUnknown alone), and the answer is 1c's regularized one; without
//   a warm basis the same settings fail, after one seed of step 2 (at its cap, which ends
//   step 2), steps 3, 4 and 5;
// - between exact retries (accept_perturbed) only step 1c's first path runs, in the caller's
//   shared factorization (its symbolic analysis reused on the next call);
// - on an exact retry (accept_perturbed false) step 3 runs last and adds Lemke's
//   covering-vector retries (the caller's covering_retries) to its failed cold path;
// - the same z as the cold attempts' regularized answer (M + εI's solution), to 1e-7
//   relative: z grows like |b|/ε, and M + εI's condition like 1/ε (ε = 1e-8 relative).
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/lcp_model_attempts.hpp>

#include "lcp_wedge_support.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace lcprelax {
namespace {

constexpr double kDt = 1e-2;

// The wedged box's LCP and its cold attempts' regularized answer (the warm basis of the tests).
struct RegularizedWedge {
  ContactSystem s = test::wedged_box_system(-1e-6, 0.5, kDt);
  StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), kDt);
  LcpModelAttempts cold;
  std::vector<bool> warm;
  Vector z_cold;
  RegularizedWedge() {
    run_lcp_model_attempts(s, lcp, LemkeSettings{}, {}, cold);
    if (cold.source != LcpModelSource::regularized || !cold.used) return;
    warm = cold.used->result().z_basic;
    z_cold = cold.used->result().z;
  }
  bool regularized() const { return cold.source == LcpModelSource::regularized && cold.used; }
};

TEST(LcpWarmRegularized, ARegularizedBasisRestartsOnMPlusEpsilonI) {
  const RegularizedWedge wedge;
  ASSERT_TRUE(wedge.regularized()) << wedge.cold.message;
  const auto& [s, lcp, cold, warm, z_cold] = wedge;
  const double qn = lcp.q.lpNorm<Eigen::Infinity>();
  ASSERT_FALSE(cold.used->result().info.crash_started) << "step 4 is a cold path";

  std::size_t attempts_without = 0;
  for (const bool accept : {false, true}) {
    SCOPED_TRACE(accept ? "accept_perturbed" : "every attempt");
    LcpModelAttempts w;
    run_lcp_model_attempts(s, lcp, LemkeSettings{}, warm, w, false, {}, accept, nullptr, /*warm_from_regularized=*/true);
    EXPECT_EQ(w.status, ContactStatus::solved_inaccurate) << w.message;
    ASSERT_EQ(w.source, LcpModelSource::regularized) << w.message;
    const LcpInfo& info = w.used->result().info;
    EXPECT_TRUE(info.warm_started || info.crash_started) << "step 1c: from the warm basis, not step 4's cold path";
    EXPECT_LE(stewart_trinkle_residual(lcp, w.used->result().z), kLcpRegularizedResidual * qn);
    EXPECT_LT(w.pivots, cold.pivots);
    EXPECT_LE((w.used->result().z - z_cold).lpNorm<Eigen::Infinity>(), 1e-7 * z_cold.lpNorm<Eigen::Infinity>());
    if (!accept) attempts_without = w.solvers.size();
    else EXPECT_LT(w.solvers.size(), attempts_without) << "step 3 skipped";
  }
  // Without warm_from_regularized (the warm basis of an exact answer) step 1c does not run: the
  // answer is step 4's, from the all-w basis.
  LcpModelAttempts plain;
  run_lcp_model_attempts(s, lcp, LemkeSettings{}, warm, plain);
  ASSERT_EQ(plain.source, LcpModelSource::regularized) << plain.message;
  EXPECT_FALSE(plain.used->result().info.warm_started || plain.used->result().info.crash_started);
}

// A regularized island between its exact retries (warm_from_regularized and
// accept_perturbed): step 1 and step 1c's polish are skipped, so the answer is 1c's first
// attempt, started from the warm basis in the caller's warm_factorization; a second call
// with the same basis reuses that factorization's symbolic analysis.
TEST(LcpWarmRegularized, AtRestOnlyStepOneCRunsInTheSharedFactorization) {
  const RegularizedWedge wedge;
  ASSERT_TRUE(wedge.regularized()) << wedge.cold.message;
  const auto& [s, lcp, cold, warm, z_cold] = wedge;
  const std::shared_ptr<LemkeSharedFactorization> lu = make_lemke_shared_factorization();
  LemkeSettings sparse;  // the shared factorization is the sparse method's (automatic: dense at n = 8)
  sparse.method = LemkeMethod::sparse;
  for (int call = 0; call < 2; ++call) {
    SCOPED_TRACE(call);
    LcpModelAttempts rest;
    run_lcp_model_attempts(s, lcp, sparse, warm, rest, false, lu, /*accept_perturbed=*/true, nullptr,
                           /*warm_from_regularized=*/true);
    ASSERT_EQ(rest.source, LcpModelSource::regularized) << rest.message;
    EXPECT_EQ(rest.solvers.size(), 1u) << "step 1c's path alone";
    EXPECT_EQ(rest.used, &rest.solvers.front());
    EXPECT_TRUE(rest.used->result().info.warm_started || rest.used->result().info.crash_started);
    EXPECT_LE((rest.used->result().z - z_cold).lpNorm<Eigen::Infinity>(), 1e-7 * z_cold.lpNorm<Eigen::Infinity>());
    EXPECT_EQ(lu->factorizations, call + 1) << "1c's basis is factorized in the shared factorization";
    EXPECT_EQ(lu->analyses, 1) << "its pattern repeats: one symbolic analysis";
  }
  // Not skipped on a retry step (accept_perturbed false): step 1 runs first, in the shared
  // factorization.
  LcpModelAttempts retry;
  run_lcp_model_attempts(s, lcp, sparse, warm, retry, false, lu, false, nullptr, true);
  EXPECT_GT(retry.solvers.size(), 1u);
  EXPECT_EQ(retry.solvers.front().result().info.crash_started, false) << "step 1: the warm basis alone";
}

// An exact retry of a regularized island (warm_from_regularized, accept_perturbed false):
// step 3's exact cold path runs last (1c's regularized answer is in hand, so steps 1b, 2, 4
// and 5 do not run), and where it fails (here on a ray: this LCP has no solution) Lemke's
// covering-vector retries follow, as many as the caller's settings allow: more pivots in
// step 3 with covering_retries = 2 than with 0, the same attempts and the same answer.
TEST(LcpWarmRegularized, AnExactRetryAddsLemkesCoveringRetriesToStepThree) {
  const RegularizedWedge wedge;
  ASSERT_TRUE(wedge.regularized()) << wedge.cold.message;
  const auto& [s, lcp, cold, warm, z_cold] = wedge;
  long step3_pivots[2] = {0, 0};
  std::size_t attempts[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    LemkeSettings settings;
    settings.covering_retries = k ? 2 : 0;
    LcpModelAttempts retry;
    run_lcp_model_attempts(s, lcp, settings, warm, retry, false, {}, /*accept_perturbed=*/false, nullptr,
                           /*warm_from_regularized=*/true);
    ASSERT_EQ(retry.source, LcpModelSource::regularized) << retry.message;
    EXPECT_LE((retry.used->result().z - z_cold).lpNorm<Eigen::Infinity>(), 1e-7 * z_cold.lpNorm<Eigen::Infinity>());
    const LemkeSolver& step3 = retry.solvers.back();
    EXPECT_NE(&step3, retry.used);
    EXPECT_FALSE(step3.result().info.warm_started || step3.result().info.crash_started) << "a cold path";
    EXPECT_FALSE(has_solution(step3.result().info.status));
    step3_pivots[k] = step3.result().info.pivots;
    attempts[k] = retry.solvers.size();
  }
  EXPECT_EQ(attempts[0], attempts[1]);
  EXPECT_GT(step3_pivots[1], step3_pivots[0]) << "the covering-vector retries ran";
}

TEST(LcpWarmRegularized, StepSixTurnsAFailureIntoTheRegularizedAnswer) {
  const RegularizedWedge wedge;
  ASSERT_TRUE(wedge.regularized()) << wedge.cold.message;
  const auto& [s, lcp, cold, warm, z_cold] = wedge;

  LemkeSettings one_pivot;
  one_pivot.max_pivots = 1;
  LcpModelAttempts failed;
  run_lcp_model_attempts(s, lcp, one_pivot, {}, failed);
  EXPECT_EQ(failed.status, ContactStatus::failed) << failed.message;
  // Step 2's first seed stops at its cap, which ends step 2 (no second or third seed).
  EXPECT_EQ(failed.solvers.size(), 4u) << "step 2 (one seed), steps 3, 4 and 5";

  LcpModelAttempts last;
  run_lcp_model_attempts(s, lcp, one_pivot, warm, last);
  EXPECT_EQ(last.status, ContactStatus::solved_inaccurate) << last.message;
  ASSERT_EQ(last.source, LcpModelSource::regularized) << last.message;
  const LcpInfo& info = last.used->result().info;
  EXPECT_TRUE(info.warm_started || info.crash_started);
  // 1c ran after every other attempt had failed (the ones after it are its polishes).
  std::size_t before = 0;
  for (const LemkeSolver& x : last.solvers) {
    if (&x == last.used) break;
    EXPECT_FALSE(has_solution(x.result().info.status)) << "attempt " << before;
    ++before;
  }
  EXPECT_GE(before, 5u) << "steps 1, 1b, 2, 3, 4 and 5 before it";
  EXPECT_LE(stewart_trinkle_residual(lcp, last.used->result().z), kLcpRegularizedResidual * lcp.q.lpNorm<Eigen::Infinity>());
}

}  // namespace
}  // namespace lcprelax
