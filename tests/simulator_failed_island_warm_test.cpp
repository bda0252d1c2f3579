// A failed island keeps its contacts' warm-start entries (simulator.hpp warm_start_state):
// the next step starts from the last basis that solved, not cold. Expected:
// - a box on eight coincident ground planes is too redundant for the LCP model (16
//   contacts on 3 degrees of freedom): the island fails (convex fallback), and the entries
//   loaded for its contacts on the first plane are in the state after the step, unchanged;
//   its contacts on the other planes, which had none, get none;
// - the same box on one plane solves, and its entries are then the new basis's (a solved
//   island's entries are replaced, not carried).
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace lcprelax {
namespace {

Scene box_on_planes(int planes) {
  Scene scene = test::scene_with({test::box(0.2, 0.2, 1.0, Vec3(0.0, 0.1, 0.0))}, 0.5, 0.01);
  for (int k = 1; k < planes; ++k) scene.world.half_planes.push_back(test::plane(0.0));
  return scene;
}

TEST(FailedIslandWarmStart, AFailedIslandKeepsTheEntriesItStartedFrom) {
  // The entries of the box's two contacts with plane 0, from a step that solved.
  const Scene one = box_on_planes(1);
  Simulator solved(one.world, one.settings);
  for (int k = 0; k < 3; ++k) ASSERT_EQ(solved.step().failed_islands, 0);
  const std::vector<ContactWarmRecord> state = solved.warm_start_state();
  ASSERT_EQ(state.size(), 2u);
  EXPECT_EQ(state[0].normal, 1.0);  // resting: λn basic
  EXPECT_EQ(state[1].normal, 1.0);

  const Scene eight = box_on_planes(8);
  Simulator sim(eight.world, eight.settings);
  sim.set_warm_start_state(state);
  const StepStats stats = sim.step();
  ASSERT_EQ(stats.contacts, 16);
  ASSERT_EQ(stats.failed_islands, 1) << "16 contacts on 3 dofs must be refused by the LCP model";
  const std::vector<ContactWarmRecord> after = sim.warm_start_state();
  ASSERT_EQ(after.size(), state.size()) << "only the contacts that had an entry keep one";
  for (std::size_t i = 0; i < state.size(); ++i) {
    EXPECT_EQ(after[i].key, state[i].key) << i;
    EXPECT_EQ(after[i].normal, state[i].normal) << i;
    EXPECT_EQ(after[i].friction, state[i].friction) << i;
  }
  // Carried again by the next failed step.
  ASSERT_EQ(sim.step().failed_islands, 1);
  EXPECT_EQ(sim.warm_start_state().size(), state.size());
}

TEST(FailedIslandWarmStart, ASolvedIslandReplacesItsEntries) {
  const Scene one = box_on_planes(1);
  Simulator sim(one.world, one.settings);
  // Entries that say the box is lifted off (λn nonbasic): the solved step's basis has λn basic.
  std::vector<ContactWarmRecord> lifted_off;
  {
    Simulator probe(one.world, one.settings);
    probe.step();
    lifted_off = probe.warm_start_state();
  }
  ASSERT_EQ(lifted_off.size(), 2u);
  for (ContactWarmRecord& r : lifted_off) r.normal = 0.0, r.friction = 0.0;
  sim.set_warm_start_state(lifted_off);
  ASSERT_EQ(sim.step().failed_islands, 0);
  const std::vector<ContactWarmRecord> after = sim.warm_start_state();
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(after[0].normal, 1.0);
  EXPECT_EQ(after[1].normal, 1.0);
}

}  // namespace
}  // namespace lcprelax
