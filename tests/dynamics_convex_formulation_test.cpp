// The convex model's two formulations (contact_step.hpp ConvexFormulation) solve the same
// problem. `dual` poses each phase in the impulses λ with W = J M⁻¹ Jᵀ; `lifted` adds the
// velocity change Δv as unknowns with M Δv = Jᵀ λ. Their v⁺ is unique and must agree to
// the interior point's tolerance (eps_abs 1e-8 of the simulator's QpSettings, on scaled
// data): asserted |v⁺_dual − v⁺_lifted|∞ ≤ 1e-6 · max(1, |v*|∞) m/s (measured ≤ 6.4e-7
// on settled random piles of 5 to 100 bodies), and the total normal impulse eᵀλn (which
// is unique even where λn is not, e.g. redundant contacts) to 1e-6 relative.
// Scenes: the largest island of a closed pile of 40 random polygons after 80 steps (a
// mix of sliding and resting contacts, above kLiftedMinContacts), a stack of 10 boxes
// (resting, 20 contacts: below it), a box sliding down a 30° incline with μ = 0.3, and a
// box 1,000× heavier resting on two small boxes.
// `automatic` must be bitwise identical to `lifted` from kLiftedMinContacts contacts on
// and to `dual` below.
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

namespace lcprelax {
namespace {

// The largest island of `world` (contacts within the settings' margin).
ContactSystem largest_island(const World& world, const SimulatorSettings& settings) {
  const std::vector<Contact> contacts = find_contacts(world, CollisionSettings{settings.margin});
  const std::vector<Island> islands = find_islands(world, contacts);
  EXPECT_FALSE(islands.empty());
  std::size_t big = 0;
  for (std::size_t i = 0; i < islands.size(); ++i)
    if (islands[i].contacts.size() > islands[big].contacts.size()) big = i;
  return assemble_contact_system(world, contacts, islands.at(big), settings.dt);
}

void expect_same_solution(const ContactSolution& a, const ContactSolution& b, const ContactSystem& s) {
  ASSERT_TRUE(has_solution(a.status)) << a.message;
  ASSERT_TRUE(has_solution(b.status)) << b.message;
  const double scale = std::max(1.0, s.v_star.cwiseAbs().maxCoeff());
  EXPECT_LE((a.v_next - b.v_next).cwiseAbs().maxCoeff(), 1e-6 * scale);
  const double sa = a.lambda_n.sum(), sb = b.lambda_n.sum();
  EXPECT_LE(std::abs(sa - sb), 1e-6 * std::max(1e-12, std::abs(sa)));
  EXPECT_LE(b.residual, 1e-6);
}

void expect_bitwise(const ContactSolution& a, const ContactSolution& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.work, b.work);
  ASSERT_EQ(a.v_next.size(), b.v_next.size());
  for (Index i = 0; i < a.v_next.size(); ++i) EXPECT_EQ(a.v_next(i), b.v_next(i)) << i;
}

struct Solved {
  ContactSolution dual, lifted, automatic;
};

Solved solve_all(const ContactSystem& s, double dt) {
  const QpSettings qp = SimulatorSettings{}.qp;
  return {solve_convex_model(s, dt, qp, 1e-3, ConvexFormulation::dual),
          solve_convex_model(s, dt, qp, 1e-3, ConvexFormulation::lifted),
          solve_convex_model(s, dt, qp, 1e-3, ConvexFormulation::automatic)};
}

TEST(ConvexFormulation, PileIslandAgreesAndAutomaticIsLifted) {
  Simulator sim = make_simulator(test::closed_pile(40, 3, ContactModel::convex));
  for (int k = 0; k < 80; ++k) sim.step();
  const ContactSystem s = largest_island(sim.world(), sim.settings());
  ASSERT_GE(s.num_contacts(), kLiftedMinContacts);
  const Solved r = solve_all(s, sim.settings().dt);
  expect_same_solution(r.dual, r.lifted, s);
  expect_bitwise(r.automatic, r.lifted);
}

TEST(ConvexFormulation, BoxStackAgreesAndAutomaticIsDual) {
  const Scene scene = test::scene_with(test::box_stack(10), 0.5, 1e-2, ContactModel::convex);
  const ContactSystem s = largest_island(scene.world, scene.settings);
  ASSERT_EQ(s.num_contacts(), 20);
  ASSERT_LT(s.num_contacts(), kLiftedMinContacts);
  const Solved r = solve_all(s, scene.settings.dt);
  expect_same_solution(r.dual, r.lifted, s);
  expect_bitwise(r.automatic, r.dual);
  // At rest: v⁺ ≈ 0 (the ρ term makes contact slightly soft).
  EXPECT_LE(r.lifted.v_next.cwiseAbs().maxCoeff(), 1e-6);
}

TEST(ConvexFormulation, SlidingBoxOnInclineAgrees) {
  const double angle = test::kPi / 6.0, mu = 0.3, dt = 1e-2;
  const Scene scene = test::incline_scene(angle, mu, dt, ContactModel::convex);
  const ContactSystem s = largest_island(scene.world, scene.settings);
  const Solved r = solve_all(s, dt);
  expect_same_solution(r.dual, r.lifted, s);
  // Sliding: speed along the slope g(sin α − μ cos α)Δt after one step from rest.
  const double expected = 9.81 * (std::sin(angle) - mu * std::cos(angle)) * dt;
  EXPECT_NEAR(r.lifted.v_next.head<2>().norm(), expected, 1e-3 * expected);
}

TEST(ConvexFormulation, HeavyBoxOnSmallBoxesAgrees) {
  std::vector<RigidBody> bodies = {test::box(0.2, 0.2, 1.0, Vec3(-0.4, 0.1, 0.0)),
                                   test::box(0.2, 0.2, 1.0, Vec3(0.4, 0.1, 0.0)),
                                   test::box(1.2, 0.2, 1000.0, Vec3(0.0, 0.3, 0.0))};
  const Scene scene = test::scene_with(std::move(bodies), 0.5, 1e-2, ContactModel::convex);
  const ContactSystem s = largest_island(scene.world, scene.settings);
  ASSERT_EQ(s.bodies.size(), 3u);
  const Solved r = solve_all(s, scene.settings.dt);
  expect_same_solution(r.dual, r.lifted, s);
}

}  // namespace
}  // namespace lcprelax
