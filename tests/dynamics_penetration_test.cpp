// Time steps from 1e-5 s to 1e-1 s (LCP model; the convex model at 1e-3 and 1e-1).
// Expected at every Δt:
// - a box resting on the ground (1 m, 1 kg, gap 0) stays: over 0.5 s (at most 2,000 steps)
//   no failed island and drift < 1e-6 m;
// - a box dropped from 5 cm lands and comes to rest: no failed island; the penetration at
//   the start of any step stays below 1e-4 m (the slop: the speculative margin and the gap
//   term φ/Δt stop it at the ground); 0.1 s after the landing time √(2h/g) ≈ 0.10 s
//   (Δt = 1e-1: two steps after) its speed is below 1e-9 m/s and its height is
//   0.5 m ± 1e-4 m.
//
// Bodies that start overlapping by 25% are separated by the position-level
// post-stabilization without gaining kinetic energy (both contact models).
// Expected:
// - Two 1 m, 1 kg boxes on the ground, side by side, overlapping horizontally by 0.25 m:
//   after 5 steps of Δt = 1e-2 every penetration is within the slop (1e-4 m, +1e-9 for
//   roundoff), both still rest on the ground (height 0.5 m ± 1e-6), and the kinetic
//   energy at every step stays ≤ its initial value 0 + tol (velocities are never used to
//   push bodies apart, contact_step.hpp); tol = 1e-12 J for the LCP, 1e-8 J for the
//   convex model (its interior point stops at a duality gap of eps_abs = 1e-8 in an
//   objective that is an energy; measured 8.4e-10 J).
// - A box sunk 0.25 m into the ground: the same (penetration within the slop after 5
//   steps, kinetic energy ≤ tol at every step). Its potential energy rises by
//   construction (the projection lifts it by 0.25 m − slop: m·g·0.2499 J); the test
//   checks that rise and nothing more.
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <tuple>

namespace lcprelax {
namespace {

class TimeStep : public ::testing::TestWithParam<std::tuple<ContactModel, double>> {};

TEST_P(TimeStep, RestingBoxStays) {
  const auto [model, dt] = GetParam();
  Simulator sim = make_simulator(test::scene_with({test::box(1.0, 1.0, 1.0, Vec3(0.0, 0.5, 0.0))}, 0.5, dt, model));
  const std::vector<Vec3> start = test::poses(sim.world());
  const int steps = std::min(2000, static_cast<int>(std::lround(0.5 / dt)));
  for (int k = 0; k < steps; ++k) {
    const StepStats st = sim.step();
    ASSERT_EQ(st.failed_islands, 0) << "step " << k << ": " << st.first_failure;
  }
  EXPECT_LT(test::max_drift(sim.world(), start), 1e-6);
}

TEST_P(TimeStep, DroppedBoxLandsAndRests) {
  const auto [model, dt] = GetParam();
  const double h = 0.05, g = 9.81;
  Simulator sim = make_simulator(test::scene_with({test::box(1.0, 1.0, 1.0, Vec3(0.0, 0.5 + h, 0.0))}, 0.5, dt, model));
  const double landing = std::sqrt(2.0 * h / g);
  const int steps = std::max(static_cast<int>(std::ceil((landing + 0.1) / dt)), static_cast<int>(std::ceil(landing / dt)) + 2);
  double penetration = 0.0;
  for (int k = 0; k < steps; ++k) {
    const StepStats st = sim.step();
    ASSERT_EQ(st.failed_islands, 0) << "step " << k << ": " << st.first_failure;
    penetration = std::max(penetration, st.max_penetration);
  }
  const RigidBody& b = sim.world().bodies[0];
  std::printf("[ measured ] %s, dt %g, %d steps: penetration %.3g m, height − 0.5 = %.3g m, speed %.3g m/s\n",
              to_string(model), dt, steps, penetration, b.pose.y() - 0.5, b.velocity.norm());
  EXPECT_LT(penetration, 1e-4);
  EXPECT_LT(b.velocity.norm(), 1e-9);
  EXPECT_NEAR(b.pose.y(), 0.5, 1e-4);
  EXPECT_NEAR(b.pose.x(), 0.0, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Lcp, TimeStep,
                         ::testing::Combine(::testing::Values(ContactModel::lcp),
                                            ::testing::Values(1e-5, 1e-4, 1e-3, 1e-2, 1e-1)));
INSTANTIATE_TEST_SUITE_P(Convex, TimeStep,
                         ::testing::Combine(::testing::Values(ContactModel::convex), ::testing::Values(1e-3, 1e-1)));

constexpr double kSlop = 1e-4;  // SimulatorSettings::penetration_slop default

double ke_tol(ContactModel model) { return model == ContactModel::lcp ? 1e-12 : 1e-8; }

class Overlap : public ::testing::TestWithParam<ContactModel> {};

TEST_P(Overlap, SideBySideBoxesSeparateWithoutKineticEnergy) {
  Simulator sim = make_simulator(test::scene_with({test::box(1.0, 1.0, 1.0, Vec3(0.0, 0.5, 0.0)),
                                  test::box(1.0, 1.0, 1.0, Vec3(0.75, 0.5, 0.0))},
                                 0.5, 1e-2, GetParam()));
  EXPECT_NEAR(test::max_penetration(sim.world()), 0.25, 1e-12);
  const double ke0 = sim.kinetic_energy();
  for (int k = 0; k < 5; ++k) {
    const StepStats st = sim.step();
    ASSERT_EQ(st.failed_islands, 0) << st.first_failure;
    ASSERT_LE(sim.kinetic_energy(), ke0 + ke_tol(GetParam())) << "step " << k;
  }
  const double penetration = test::max_penetration(sim.world());
  std::printf("[ measured ] %s: penetration after 5 steps %.3g m, kinetic energy %.3g J\n", to_string(GetParam()),
              penetration, sim.kinetic_energy());
  EXPECT_LE(penetration, kSlop + 1e-9);
  for (const RigidBody& b : sim.world().bodies) EXPECT_NEAR(b.pose.y(), 0.5, 1e-6);
}

TEST_P(Overlap, SunkBoxRisesWithoutKineticEnergy) {
  Simulator sim = make_simulator(test::scene_with({test::box(1.0, 1.0, 1.0, Vec3(0.0, 0.25, 0.0))}, 0.5, 1e-2, GetParam()));
  const double ke0 = sim.kinetic_energy(), pe0 = sim.potential_energy();
  for (int k = 0; k < 5; ++k) {
    const StepStats st = sim.step();
    ASSERT_EQ(st.failed_islands, 0) << st.first_failure;
    ASSERT_LE(sim.kinetic_energy(), ke0 + ke_tol(GetParam())) << "step " << k;
  }
  const double penetration = test::max_penetration(sim.world());
  std::printf("[ measured ] %s: penetration after 5 steps %.3g m, potential rise %.6g J\n", to_string(GetParam()),
              penetration, sim.potential_energy() - pe0);
  EXPECT_LE(penetration, kSlop + 1e-9);
  EXPECT_NEAR(sim.potential_energy() - pe0, 9.81 * (0.25 - kSlop), 9.81 * 1e-6);
}

INSTANTIATE_TEST_SUITE_P(LcpAndConvex, Overlap, ::testing::Values(ContactModel::lcp, ContactModel::convex));

}  // namespace
}  // namespace lcprelax
