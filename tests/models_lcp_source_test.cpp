// The lcp model's LCP with M formed on first use (StewartTrinkleLcpSource,
// models/lcp_model_attempts.hpp) and its q alone (stewart_trinkle_q). Pinned:
// - stewart_trinkle_q is stewart_trinkle_lcp's q bit for bit, rigid, with compliance and
//   erp, and with the per-contact block;
// - on a pile island re-solved from its own final basis, the attempts on a source with a
//   lifted form solve in step 1 without forming M (formed() stays false), with the answer
//   (status, z bit for bit, pivots 0) of the attempts on the formed LCP;
// - without a warm basis, or without a lifted form, the source is formed and the answer is
//   the formed LCP's;
// - a source of one island run against another island's system is refused.
#include "contact_island_fixtures.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/lcp_model_attempts.hpp>

#include <gtest/gtest.h>

#include <cstring>

namespace lcprelax {
namespace {

constexpr double kDt = 0.01;

void expect_same_bits(const Vector& a, const Vector& b) {
  ASSERT_EQ(a.size(), b.size());
  for (Index i = 0; i < a.size(); ++i) ASSERT_EQ(std::memcmp(&a(i), &b(i), sizeof(double)), 0) << "entry " << i;
}

TEST(StewartTrinkleQ, IsTheLcpsQBitForBit) {
  std::vector<ContactSystem> systems{testing::box_stack(4, 0.5), testing::settled_pile_island(40, 1, 80)};
  for (ContactSystem s : systems) {
    expect_same_bits(stewart_trinkle_q(s, kDt), stewart_trinkle_lcp(s, delassus(s), kDt).q);
    s.compliance = Vector::Constant(s.num_contacts(), 1e-4);
    s.erp = Vector::Constant(s.num_contacts(), 0.2);
    s.phi(0) = -1e-3;  // a penetrating contact: the erp term acts
    expect_same_bits(stewart_trinkle_q(s, kDt), stewart_trinkle_lcp(s, delassus(s), kDt).q);
    s.lcp_block.enabled = true;
    s.lcp_block.q << 0.1, -0.2, 0.3, 0.05;
    expect_same_bits(stewart_trinkle_q(s, kDt), stewart_trinkle_lcp(s, delassus(s), kDt).q);
  }
}

TEST(StewartTrinkleLcpSource, AWarmBasisThatSolvesLeavesMUnformed) {
  const ContactSystem s = testing::settled_pile_island(40, 2, 80);
  const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), kDt);
  const LcpLiftedForm lifted = stewart_trinkle_lifted_form(s, kDt);
  LcpModelAttempts cold;
  run_lcp_model_attempts(s, lcp, LemkeSettings{}, {}, cold, false, {}, false, &lifted);
  ASSERT_EQ(cold.status, ContactStatus::solved) << cold.message;
  const std::vector<bool> warm = cold.used->result().z_basic;

  LcpModelAttempts formed, lazy;
  run_lcp_model_attempts(s, lcp, LemkeSettings{}, warm, formed, false, {}, false, &lifted);
  StewartTrinkleLcpSource source(s, kDt);
  run_lcp_model_attempts(s, source, LemkeSettings{}, warm, lazy, false, {}, false, &lifted);
  EXPECT_FALSE(source.formed());
  EXPECT_FALSE(lazy.used->result().info.matrix_formed);
  ASSERT_EQ(lazy.status, ContactStatus::solved) << lazy.message;
  EXPECT_EQ(formed.status, lazy.status);
  EXPECT_EQ(lazy.pivots, 0);
  EXPECT_TRUE(lazy.warm_started);
  expect_same_bits(formed.used->result().z, lazy.used->result().z);
  // The residual Lemke reports (from w = J(d∘Jᵀz) + Hz + q) is the formed LCP's to roundoff.
  const double scale = std::max(1.0, lcp.q.lpNorm<Eigen::Infinity>());
  EXPECT_NEAR(lazy.used->result().info.complementarity, stewart_trinkle_residual(lcp, lazy.used->result().z),
              1e-12 * scale);
  // solve_lcp_model runs the same (its answer at the warm basis).
  const ContactSolution sol = solve_lcp_model(s, kDt, LemkeSettings{}, warm);
  EXPECT_TRUE(sol.warm_started);
  EXPECT_EQ(sol.status, ContactStatus::solved);
  EXPECT_LE(sol.residual, 1e-9 * scale);
}

TEST(StewartTrinkleLcpSource, ColdOrWithoutALiftedFormItIsFormed) {
  const ContactSystem s = testing::settled_pile_island(40, 1, 80);
  const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), kDt);
  const LcpLiftedForm lifted = stewart_trinkle_lifted_form(s, kDt);
  LcpModelAttempts formed, lazy;
  run_lcp_model_attempts(s, lcp, LemkeSettings{}, {}, formed, false, {}, false, &lifted);
  StewartTrinkleLcpSource source(s, kDt);
  EXPECT_FALSE(source.formed());
  run_lcp_model_attempts(s, source, LemkeSettings{}, {}, lazy, false, {}, false, &lifted);
  EXPECT_TRUE(source.formed());
  EXPECT_EQ(formed.status, lazy.status);
  EXPECT_EQ(formed.pivots, lazy.pivots);
  expect_same_bits(formed.used->result().z, lazy.used->result().z);
  // A warm basis but no lifted form: step 1 needs M.
  const std::vector<bool> warm = formed.used->result().z_basic;
  StewartTrinkleLcpSource plain(s, kDt);
  LcpModelAttempts again;
  run_lcp_model_attempts(s, plain, LemkeSettings{}, warm, again);
  EXPECT_TRUE(plain.formed());
  EXPECT_EQ(again.pivots, 0);
}

TEST(StewartTrinkleLcpSource, AnotherIslandsSystemIsRefused) {
  const ContactSystem a = testing::settled_pile_island(40, 1, 80), b = testing::box_stack(3, 0.5);
  StewartTrinkleLcpSource source(b, kDt);
  LcpModelAttempts out;
  EXPECT_THROW(run_lcp_model_attempts(a, source, LemkeSettings{}, {}, out), InputError);
}

}  // namespace
}  // namespace lcprelax
