// Step 1b's restarts after an early ray (contact_step.hpp kLcpWarmRayRestarts):
// their bound (lcp_warm_ray_restart_allowed), and reset_warm_contacts_on_ray, which takes
// back in the warm basis the contacts that a crash path's pivots touched, friction first
// and the whole contact when it is touched again.
// Checked on a hand-made system of 4 contacts, 3 of them with friction rows (so that the
// row → contact map of z = [λn, β⁺, β⁻, γ] is not the identity).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/lcp_model_attempts.hpp>

#include <gtest/gtest.h>

#include <vector>

namespace lcprelax {
namespace {

// nc = 4 contacts; friction rows on contacts 0, 2 and 3 (nf = 3), so n = 4 + 9 = 13:
// rows 0–3 λn, 4–6 β⁺, 7–9 β⁻, 10–12 γ; friction row f belongs to contact {0, 2, 3}[f].
ContactSystem four_contacts() {
  ContactSystem s;
  s.contacts = {0, 1, 2, 3};
  s.friction_rows = {0, 2, 3};
  return s;
}

// Trace numbering (LemkeSolver::set_pivot_trace): w_i = i, z_j = n + j, z₀ = 2n.
constexpr Index kN = 13;
Index w(Index i) { return i; }
Index z(Index j) { return kN + j; }

TEST(LcpWarmRayReset, FrictionFirstThenTheWholeContact) {
  const ContactSystem s = four_contacts();
  std::vector<bool> warm(kN, true);
  std::vector<signed char> level(4, 0);
  // z₀ enters and w_8 leaves (row 8: β⁻ of friction row 1, contact 2); the next to enter,
  // the complement z_8, is in contact 2 as well.
  std::vector<Index> trace = {2 * kN, w(8)};
  EXPECT_EQ(reset_warm_contacts_on_ray(s, trace, level, warm), 1);
  EXPECT_EQ(level, (std::vector<signed char>{0, 0, 1, 0}));
  for (Index i = 0; i < kN; ++i) {
    const bool friction_of_contact_2 = i == 5 || i == 8 || i == 11;
    EXPECT_EQ(warm[i], !friction_of_contact_2) << "row " << i;
  }
  // Touched again (through its normal row 2) together with contact 3's γ (row 12), and
  // the next entering variable is the complement of z_0, i.e. w_0: contact 0.
  trace = {z(2), z(12), w(12), z(0)};
  EXPECT_EQ(reset_warm_contacts_on_ray(s, trace, level, warm), 3);
  EXPECT_EQ(level, (std::vector<signed char>{1, 0, 2, 1}));
  std::vector<bool> expected(kN, true);
  expected[2] = false;  // contact 2 whole: λn too
  for (Index f = 0; f < 3; ++f)  // friction rows of contacts 0, 2, 3: rows nc + k·nf + f
    for (Index k = 0; k < 3; ++k) expected[4 + 3 * k + f] = false;
  EXPECT_EQ(warm, expected);
  // Contact 1 (no friction row) goes to level 1 without a change in warm; a contact at
  // level 2 stays there and counts no more: nothing raised, nothing changed.
  trace = {z(1), w(1)};
  EXPECT_EQ(reset_warm_contacts_on_ray(s, trace, level, warm), 1);
  EXPECT_EQ(warm, expected);
  level = {2, 2, 2, 2};
  EXPECT_EQ(reset_warm_contacts_on_ray(s, trace, level, warm), 0);
  EXPECT_EQ(reset_warm_contacts_on_ray(s, {}, level, warm), 0);
}

// The restarts are bounded by their count and by the pivots of the rayed paths together
// (contact_step.hpp kLcpWarmRayRestarts, kLcpWarmRayBudgetPerUnknown), not by either alone.
TEST(LcpWarmRayReset, RestartsBoundedByCountAndPivots) {
  const Index n = 20000;
  const long budget = static_cast<long>(kLcpWarmRayBudgetPerUnknown * n);
  EXPECT_TRUE(lcp_warm_ray_restart_allowed(0, 1, n));
  EXPECT_TRUE(lcp_warm_ray_restart_allowed(5, 343, n));  // the 1,000-body step's 6th restart
  EXPECT_TRUE(lcp_warm_ray_restart_allowed(kLcpWarmRayRestarts - 1, budget, n));
  EXPECT_FALSE(lcp_warm_ray_restart_allowed(kLcpWarmRayRestarts, 1, n));
  EXPECT_FALSE(lcp_warm_ray_restart_allowed(0, budget + 1, n));
  // Early rays (each within kLcpWarmRayPivotsPerUnknown·n) allow at least
  // budget / (that many) restarts, so the pivot budget alone never stops fewer than 5.
  const long longest_early_ray = static_cast<long>(kLcpWarmRayPivotsPerUnknown * n);
  EXPECT_TRUE(lcp_warm_ray_restart_allowed(4, 5 * longest_early_ray, n));
  EXPECT_GE(kLcpWarmRayRestarts, 5);
}

TEST(LcpWarmRayReset, RefusesInconsistentSizes) {
  const ContactSystem s = four_contacts();
  std::vector<bool> warm(kN, true), short_warm(kN - 1, true);
  std::vector<signed char> level(4, 0), short_level(3, 0);
  EXPECT_THROW(reset_warm_contacts_on_ray(s, {}, short_level, warm), InputError);
  EXPECT_THROW(reset_warm_contacts_on_ray(s, {}, level, short_warm), InputError);
}

}  // namespace
}  // namespace lcprelax
