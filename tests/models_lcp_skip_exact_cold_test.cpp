// run_lcp_model_attempts' skip_exact_cold (models/lcp_model_attempts.hpp): with a perturbed
// solution in hand, step 3 (Lemke on q from the all-w basis) is not run; nothing else of
// the chain changes. Measured on the islands below (settled_pile_island, 80 steps):
// - 60 bodies, seed 1 (267 contacts): the chain ends on the perturbed answer (its polish on q
//   fails and so does step 3): 4 attempts and 3,032 pivots, with the skip 3 attempts and
//   1,476 pivots, the same answer bit for bit;
// - 40 bodies, seed 1 (228 contacts): a polish solves the LCP exactly, step 3 never runs,
//   and the skip changes nothing (2 attempts, 736 pivots either way).
// The hard loss passes the option through (learn/step_loss_hard.hpp): same loss and
// gradient, fewer pivots.
#include <lcprelax/learn/step_loss_hard.hpp>
#include <lcprelax/models/lcp_model_attempts.hpp>

#include "contact_island_fixtures.hpp"

#include <gtest/gtest.h>

namespace lcprelax {
namespace {

constexpr double kDt = 1e-2;

struct Both {
  LcpModelAttempts full, skipped;
};

void run_both(const ContactSystem& s, Both& out) {
  const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), kDt);
  run_lcp_model_attempts(s, lcp, LemkeSettings{}, {}, out.full);
  run_lcp_model_attempts(s, lcp, LemkeSettings{}, {}, out.skipped, /*skip_exact_cold=*/true);
}

const ContactSystem& jammed_island() {
  static const ContactSystem s = testing::settled_pile_island(60, 1, 80);
  return s;
}

TEST(LcpSkipExactCold, DropsOnlyTheExactAttemptAndKeepsThePerturbedAnswer) {
  Both b;
  run_both(jammed_island(), b);
  ASSERT_EQ(b.full.source, LcpModelSource::perturbed) << "fixture: the chain should end on the perturbed answer";
  EXPECT_EQ(b.full.status, ContactStatus::solved_inaccurate);
  EXPECT_EQ(b.skipped.source, LcpModelSource::perturbed);
  EXPECT_EQ(b.skipped.status, ContactStatus::solved_inaccurate);
  EXPECT_EQ(b.skipped.solvers.size() + 1, b.full.solvers.size());
  EXPECT_LT(b.skipped.pivots, b.full.pivots);
  EXPECT_EQ(b.skipped.message, b.full.message);
  ASSERT_TRUE(b.full.used && b.skipped.used);
  EXPECT_EQ(b.skipped.used->result().z, b.full.used->result().z);  // the same arithmetic
  EXPECT_EQ(b.skipped.used->result().z_basic, b.full.used->result().z_basic);
  std::printf("[ measured ] jammed island: %zu attempts, %ld pivots; skipped: %zu attempts, %ld pivots\n",
              b.full.solvers.size(), b.full.pivots, b.skipped.solvers.size(), b.skipped.pivots);
}

TEST(LcpSkipExactCold, ChangesNothingWhereAPolishSolvesTheLcp) {
  Both b;
  run_both(testing::settled_pile_island(40, 1, 80), b);
  ASSERT_EQ(b.full.source, LcpModelSource::exact);
  EXPECT_EQ(b.skipped.source, LcpModelSource::exact);
  EXPECT_EQ(b.skipped.solvers.size(), b.full.solvers.size());
  EXPECT_EQ(b.skipped.pivots, b.full.pivots);
  ASSERT_TRUE(b.full.used && b.skipped.used);
  EXPECT_EQ(b.skipped.used->result().z, b.full.used->result().z);
}

TEST(LcpSkipExactCold, HardLossPassesItThrough) {
  const ContactSystem& s = jammed_island();
  Vector target = s.v_star;
  target(0) += 0.01;
  const learn::StepLossResult full = learn::hard_step_loss(s, target, kDt);
  const learn::StepLossResult skipped = learn::hard_step_loss(s, target, kDt, {}, {}, nullptr, true);
  ASSERT_EQ(full.status, ContactStatus::solved_inaccurate) << full.message;
  EXPECT_EQ(skipped.status, ContactStatus::solved_inaccurate);
  EXPECT_LT(skipped.work, full.work);
  EXPECT_EQ(skipped.loss, full.loss);
  EXPECT_EQ(skipped.grad.v_star, full.grad.v_star);
  EXPECT_EQ(skipped.grad.phi, full.grad.phi);
}

}  // namespace
}  // namespace lcprelax
