// Nonlinear post-stabilization (SimulatorSettings::post_stabilization_passes): the first
// pass projects positions on the step's contacts with their linearized gaps φ + Δt·Jn v⁺;
// rotating polygons then still overlap through vertices and edges that the linearization
// did not follow, and further passes re-detect contacts at the projected positions and
// project on their true gaps.
// Expected, on a dropping pile of 30 random polygons (make_pile_scene, seed 1, convex model,
// Δt = 1e-2, 150 steps; the largest overlap at the start of any step, StepStats::
// max_penetration):
// - one pass (the linearized projection alone): more than 4 mm (measured 6.6 mm), so the
//   test can tell the passes apart;
// - five passes: at most 2.5 mm (measured 0.1 mm, the slop), no failed island, and the
//   total energy never above the previous step's plus 1e-9 of the initial total (the
//   passes move positions only; lifting a body out of an overlap can only be paid by the
//   dissipation of the step, as in ClosedPile.TotalEnergyNeverIncreases).
// - the default is five passes (a user's drop stays below the 5 mm of overlap that a pile
//   benchmark asks for).
// - post_stabilization_passes = 0 is refused with a message naming the field.
// - Overlaps deeper than the slop by at most a millionth of it (the roundoff of contacts a
//   projection left at exactly −slop) are left alone: a box sunk 1e-8 m beyond the slop is
//   projected back to the slop, one sunk 1e-11 m beyond it (below 1e-6·slop = 1e-10 m) is
//   not moved, and a 60-body LCP pile at rest (seed 1, 300 settle steps) projects no island in its
//   next 20 steps (before this margin each of them ran all 5 passes, on overlaps 3e-18 m
//   beyond the slop).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

namespace lcprelax {
namespace {

struct DropOutcome {
  double max_penetration = 0.0;
  double largest_energy_gain = -1e300;  // over the steps, relative to the initial total
  int failed_islands = 0;
};

DropOutcome drop_pile(int passes) {
  Simulator sim = test::pile_simulator(30, 1, ContactModel::convex, passes);
  DropOutcome out;
  const double e0 = sim.total_energy();
  double e = e0;
  for (int k = 0; k < 150; ++k) {
    const StepStats st = sim.step();
    const double next = sim.total_energy();
    out.largest_energy_gain = std::max(out.largest_energy_gain, (next - e) / std::abs(e0));
    e = next;
    out.max_penetration = std::max(out.max_penetration, st.max_penetration);
    out.failed_islands += st.failed_islands;
  }
  return out;
}

TEST(PostStabilizationPasses, FurtherPassesRemoveTheOverlapsOfRotatingPolygons) {
  EXPECT_EQ(SimulatorSettings{}.post_stabilization_passes, 5);
  const int passes = 5;
  const DropOutcome one = drop_pile(1), more = drop_pile(passes);
  std::printf("[ measured ] max penetration: 1 pass %.3g m, %d passes %.3g m; largest energy gain %.3g E0\n",
              one.max_penetration, passes, more.max_penetration, more.largest_energy_gain);
  EXPECT_GT(one.max_penetration, 4e-3);
  EXPECT_LE(more.max_penetration, 2.5e-3);
  EXPECT_EQ(more.failed_islands, 0);
  EXPECT_LE(more.largest_energy_gain, 1e-9);
}

// A 1 m box resting on the ground (LCP model), sunk `beyond` m deeper than the slop: the
// projection count of one step and the depth at the start of the next.
std::pair<int, double> sunk_box_step(double beyond) {
  const double slop = SimulatorSettings{}.penetration_slop;
  Simulator sim = make_simulator(test::scene_with({test::box(1.0, 1.0, 1.0, Vec3(0.0, 0.5 - slop - beyond, 0.0))}, 0.5, 1e-2));
  const StepStats first = sim.step();
  EXPECT_EQ(first.failed_islands, 0) << first.first_failure;
  EXPECT_NEAR(first.max_penetration, slop + beyond, 1e-14);
  return {first.projected_islands, sim.step().max_penetration};
}

TEST(PostStabilizationPasses, OverlapsWithinAMillionthOfTheSlopAreLeftAlone) {
  const double slop = SimulatorSettings{}.penetration_slop;
  ASSERT_EQ(slop, 1e-4);
  const auto [projected_deep, depth_deep] = sunk_box_step(1e-8);
  EXPECT_GE(projected_deep, 1);
  EXPECT_NEAR(depth_deep, slop, 1e-13);  // projected back to the slop
  const auto [projected_shallow, depth_shallow] = sunk_box_step(1e-11);
  EXPECT_EQ(projected_shallow, 0);
  EXPECT_NEAR(depth_shallow, slop + 1e-11, 1e-14);  // not moved
}

TEST(PostStabilizationPasses, APileAtRestIsNotProjected) {
  Simulator sim = test::pile_simulator(60, 1, ContactModel::lcp);
  const double slop = sim.settings().penetration_slop;
  for (int k = 0; k < 300; ++k) ASSERT_EQ(sim.step().failed_islands, 0) << "settle step " << k;
  for (int k = 0; k < 20; ++k) {
    const StepStats st = sim.step();
    EXPECT_EQ(st.projected_islands, 0) << "step " << k;
    EXPECT_GT(st.contacts, 60);
    EXPECT_LE(st.max_penetration, slop * (1.0 + 1e-6)) << "step " << k;
  }
}

TEST(PostStabilizationPasses, ZeroPassesAreRefused) {
  SimulatorSettings settings;
  settings.post_stabilization_passes = 0;
  const std::string e = settings.validation_error();
  EXPECT_NE(e.find("post_stabilization_passes"), std::string::npos) << e;
}

}  // namespace
}  // namespace lcprelax
