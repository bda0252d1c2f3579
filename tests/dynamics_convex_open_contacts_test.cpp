// The convex model's release of open contacts (SimulatorSettings::convex_release_open_contacts,
// models/convex_phase_qp.hpp release_open_contacts): phase 2 may not put normal impulse on a
// contact with a positive gap that phase 1's frictionless answer leaves open.
// Expected, on a dropping pile of 60 random polygons (make_pile_scene, seed 1, convex model,
// Δt = 1e-2, margin 1 cm, 200 steps), with the "support gap" of a body = the smallest gap
// φ over the contacts posed for it at the last step (a body resting on the pile has one
// ≤ 0, up to the slop):
// - without the release some bodies are held above every support: the largest support gap
//   exceeds 3 mm (measured 11.3 mm, 5 bodies beyond 1 mm), so the test tells the two apart;
// - with it, by the interior point and by the active-set Newton method, no body is more
//   than 1 mm from a support (measured 6e-9 m by the interior point, 3e-9 m by Newton) and
//   no island fails.
// A 30-body pile (seed 1, one post-stabilization pass) with the release: no island fails
// over 60 steps, and every island of its 41st step is solved with the release. With the
// release's gap threshold (kOpenContactMinGap, convex_phase_qp.hpp) set to 0, a contact
// left just touching was released there and phase 2 stopped with "no progress" at every κ
// slack (measured: the island failed before phase 2 was also solved again without the
// release, ContactSolution::open_contacts_held).
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace lcprelax {
namespace {

struct SettledPile {
  double largest_support_gap = 0.0;  // m, over the dynamic bodies with a posed contact
  int failed_islands = 0;
};

SettledPile drop_pile(bool release, ConvexSolver solver) {
  SimulatorSettings settings;
  settings.threads = 1;
  settings.convex_solver = solver;
  settings.convex_release_open_contacts = release;
  Simulator sim = test::pile_simulator(60, 1, ContactModel::convex, settings);
  SettledPile out;
  for (int k = 0; k < 200; ++k) out.failed_islands += sim.step().failed_islands;
  const World& world = sim.world();
  std::vector<double> support(world.bodies.size(), 1e300);
  for (const Contact& c : sim.contacts())
    for (int b : {c.body_a, c.body_b})
      if (b >= 0) support[static_cast<std::size_t>(b)] = std::min(support[static_cast<std::size_t>(b)], c.gap);
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    if (!world.bodies[i].is_static && support[i] < 1e300)
      out.largest_support_gap = std::max(out.largest_support_gap, support[i]);
  std::printf("[ measured ] release %d, %s: largest support gap %.3g m, failed islands %d\n", release ? 1 : 0,
              solver == ConvexSolver::interior_point ? "interior point" : "active-set Newton", out.largest_support_gap,
              out.failed_islands);
  return out;
}

TEST(ConvexOpenContacts, WithoutReleaseBodiesHoverAboveTheirSupports) {
  const SettledPile pile = drop_pile(false, ConvexSolver::interior_point);
  EXPECT_GT(pile.largest_support_gap, 3e-3);
}

TEST(ConvexOpenContacts, InteriorPointRestsEveryBodyOnASupport) {
  const SettledPile pile = drop_pile(true, ConvexSolver::interior_point);
  EXPECT_LE(pile.largest_support_gap, 1e-3);
  EXPECT_EQ(pile.failed_islands, 0);
}

TEST(ConvexOpenContacts, ActiveSetNewtonRestsEveryBodyOnASupport) {
  const SettledPile pile = drop_pile(true, ConvexSolver::active_set_newton);
  EXPECT_LE(pile.largest_support_gap, 1e-3);
  EXPECT_EQ(pile.failed_islands, 0);
}

TEST(ConvexOpenContacts, DefaultIsOff) {
  EXPECT_FALSE(SimulatorSettings().convex_release_open_contacts);
}

TEST(ConvexOpenContacts, JustTouchingContactsAreNotReleased) {
  SimulatorSettings settings;
  settings.threads = 1;
  settings.post_stabilization_passes = 1;
  settings.convex_release_open_contacts = true;
  Simulator sim = test::pile_simulator(30, 1, ContactModel::convex, settings);
  int failed = 0;
  for (int k = 0; k < 40; ++k) failed += sim.step().failed_islands;
  EXPECT_EQ(failed, 0);
  // The 41st step's islands, solved as the simulator does (fresh solvers).
  const StepContacts sc = find_step_contacts(sim.world(), sim.settings());
  int held = 0;
  for (const Island& island : sc.islands) {
    const ContactSystem s = assemble_contact_system(sim.world(), sc.contacts, island, settings.dt);
    const ContactSolution sol = solve_convex_model(s, settings.dt, settings.qp, settings.convex_rho,
                                                   settings.convex_formulation, settings.convex_softening, nullptr, true);
    EXPECT_TRUE(has_solution(sol.status)) << sol.message;
    held += sol.open_contacts_held ? 1 : 0;
  }
  EXPECT_EQ(held, 0);
  for (int k = 40; k < 60; ++k) failed += sim.step().failed_islands;
  EXPECT_EQ(failed, 0);
}

}  // namespace
}  // namespace lcprelax
