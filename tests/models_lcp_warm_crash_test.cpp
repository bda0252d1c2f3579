// The LCP contact model's crash path from the previous step's basis (contact_step.hpp,
// step 1b; models/src/lcp_model.cpp). A 60-body closed pile is run for 120 steps with the
// LCP model; its largest island's contact system is solved cold, then its free velocities
// v* are disturbed (N(0, 0.02²) m/s per coordinate, as the next step's would be) so that the
// cold solution's basis is no longer feasible. Expected: with that basis as the warm start,
// solve_lcp_model solves the disturbed system exactly (status solved, complementarity
// residual ≤ 1e-8 relative to ‖q‖) in at most 60% of the pivots of its cold solve (the
// crash path takes 0.2–0.4 pivots per unknown on moving piles, the cold path 0.65–0.8).
// Without step 1b the warm start costs one more pivot than the cold solve. A warm basis
// with no basic z is not tried at all (AllWBasisIsTheColdStart).
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

namespace lcprelax {
namespace {

constexpr double kDt = 1e-2;

struct DisturbedIsland {
  ContactSystem s2;           // the disturbed system
  std::vector<bool> basis;    // the undisturbed system's solution basis
};

void disturbed_pile_island(DisturbedIsland& out) {
  Simulator sim = make_simulator(test::closed_pile(60, 3, ContactModel::lcp));
  for (int k = 0; k < 120; ++k) ASSERT_EQ(sim.step().failed_islands, 0) << "step " << k;
  const World& world = sim.world();
  const std::vector<Contact> contacts = find_contacts(world, CollisionSettings{1e-2});
  const std::vector<Island> islands = find_islands(world, contacts);
  ASSERT_FALSE(islands.empty());
  const Island& island = *std::max_element(islands.begin(), islands.end(), [](const Island& a, const Island& b) {
    return a.contacts.size() < b.contacts.size();
  });
  const ContactSystem s1 = assemble_contact_system(world, contacts, island, kDt);
  const ContactSolution first = solve_lcp_model(s1, kDt, LemkeSettings{}, {});
  ASSERT_EQ(first.status, ContactStatus::solved) << first.message;

  ContactSystem s2 = s1;
  std::mt19937 rng(5);
  std::normal_distribution<double> N(0.0, 0.02);
  for (Index i = 0; i < s2.v_star.size(); ++i) s2.v_star(i) += N(rng);
  out = {s2, first.z_basic};
}

TEST(LcpWarmCrash, PreviousBasisTakesFewerPivotsThanTheColdStart) {
  DisturbedIsland d;
  ASSERT_NO_FATAL_FAILURE(disturbed_pile_island(d));
  const ContactSystem& s2 = d.s2;
  const ContactSolution cold = solve_lcp_model(s2, kDt, LemkeSettings{}, {});
  const ContactSolution warm = solve_lcp_model(s2, kDt, LemkeSettings{}, d.basis);
  ASSERT_EQ(cold.status, ContactStatus::solved) << cold.message;
  ASSERT_EQ(warm.status, ContactStatus::solved) << warm.message;
  EXPECT_FALSE(warm.warm_started);  // the disturbed system needs pivots
  const double qnorm = (s2.Jn * s2.v_star).lpNorm<Eigen::Infinity>() + 1.0;
  EXPECT_LE(warm.residual, 1e-8 * qnorm);
  std::printf("[ measured ] %ld contacts, %zu unknowns: cold %ld pivots, from the previous basis %ld\n",
              static_cast<long>(s2.num_contacts()), d.basis.size(), cold.work, warm.work);
  EXPECT_LE(static_cast<double>(warm.work), 0.6 * static_cast<double>(cold.work));
}

// A warm basis in which no z is basic (every contact new) is the cold start's all-w basis:
// it is not tried (steps 1 and 1b would repeat step 2's cold path), so the solve is the
// cold one, pivot for pivot.
TEST(LcpWarmCrash, AllWBasisIsTheColdStart) {
  DisturbedIsland d;
  ASSERT_NO_FATAL_FAILURE(disturbed_pile_island(d));
  const ContactSolution cold = solve_lcp_model(d.s2, kDt, LemkeSettings{}, {});
  const ContactSolution all_w = solve_lcp_model(d.s2, kDt, LemkeSettings{}, std::vector<bool>(d.basis.size(), false));
  ASSERT_EQ(cold.status, ContactStatus::solved) << cold.message;
  EXPECT_EQ(all_w.status, cold.status);
  EXPECT_EQ(all_w.work, cold.work);
  EXPECT_EQ(all_w.z_basic, cold.z_basic);
  EXPECT_EQ(all_w.lambda_n, cold.lambda_n);
}

}  // namespace
}  // namespace lcprelax
