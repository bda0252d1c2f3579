// The simulator marks the warm-start entries of a regularized or failed island
// (ContactWarmRecord::regularized), and an island with a marked contact runs the lcp
// model's step 1c (M + εI from the warm basis) first (contact_step.hpp). The mark is part
// of the warm-start state, so that a simulator loaded with that state (a saved scene)
// steps as the one that saved it.
//
// Scene: the wedged box of tests/lcp_wedge_support.hpp (a box wedged 0.1 mm into two
// walls) with a q bias b = −1e-6 m/s on its normal rows, whose LCP on M has no solution:
// every step's answer is regularized. Expected:
// - after a step, the state's entries are all marked regularized; with b = 0 (an LCP that
//   has a solution) none is;
// - a simulator made from the first one's world and warm-start state takes the same next
//   step, bit for bit (velocities, poses, work);
// - the same state with the marks cleared takes another path (step 1b and the cold
//   attempts before step 4's cold M + εI path): more work;
// - the marks survive a scene file (write_scene / parse_scene).
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/scene_json.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace lcprelax {
namespace {

constexpr double kDt = 1e-2;

Scene wedged_scene(double bias) {
  Scene scene;
  scene.world.bodies.push_back(test::box(0.1, 0.1, 10.0, Vec3(0.0, 1.0, 0.0)));
  scene.world.half_planes.push_back(HalfPlane{Vec2(1.0, 0.0), -0.0499, 0});   // solid x < −0.0499
  scene.world.half_planes.push_back(HalfPlane{Vec2(-1.0, 0.0), -0.0499, 0});  // solid x > 0.0499
  scene.world.friction.default_mu = 0.5;
  scene.world.lcp_block.enabled = bias != 0.0;
  scene.world.lcp_block.q = Vec4(bias, 0.0, 0.0, 0.0);
  scene.settings.dt = kDt;
  scene.settings.model = ContactModel::lcp;
  scene.settings.margin = 1e-2;
  return scene;
}

TEST(SimulatorRegularizedWarm, ARegularizedIslandMarksItsEntries) {
  for (const double bias : {-1e-6, 0.0}) {
    SCOPED_TRACE(bias);
    const Scene scene = wedged_scene(bias);
    Simulator sim(scene.world, scene.settings);
    const StepStats stats = sim.step();
    ASSERT_EQ(stats.failed_islands, 0) << stats.first_failure;
    EXPECT_EQ(stats.inaccurate_islands, bias != 0.0 ? 1 : 0) << stats.first_inaccurate;
    const std::vector<ContactWarmRecord> state = sim.warm_start_state();
    ASSERT_EQ(state.size(), 4u);
    for (const ContactWarmRecord& r : state) EXPECT_EQ(r.regularized, bias != 0.0);
  }
}

TEST(SimulatorRegularizedWarm, ALoadedStateStepsAsTheSimulatorThatSavedIt) {
  const Scene scene = wedged_scene(-1e-6);
  Simulator original(scene.world, scene.settings);
  ASSERT_EQ(original.step().inaccurate_islands, 1);
  const std::vector<ContactWarmRecord> state = original.warm_start_state();

  Simulator loaded(original.world(), scene.settings);
  loaded.set_warm_start_state(state);
  std::vector<ContactWarmRecord> unmarked = state;
  for (ContactWarmRecord& r : unmarked) r.regularized = false;
  Simulator unmarked_sim(original.world(), scene.settings);
  unmarked_sim.set_warm_start_state(unmarked);
  // Through a scene file as well.
  Scene saved = scene;
  saved.world = original.world();
  saved.warm_start = state;
  Scene reread = parse_scene(write_scene(saved));
  reread.world.lcp_block = scene.world.lcp_block;  // not a scene-file field
  ASSERT_EQ(reread.warm_start.size(), state.size());
  for (std::size_t i = 0; i < state.size(); ++i) EXPECT_TRUE(reread.warm_start[i].regularized) << i;
  Simulator from_file = make_simulator(reread);

  const StepStats a = original.step();
  const StepStats b = loaded.step();
  const StepStats c = unmarked_sim.step();
  const StepStats d = from_file.step();
  EXPECT_EQ(a.inaccurate_islands, 1);
  EXPECT_EQ(b.work, a.work);
  EXPECT_EQ(d.work, a.work);
  const RigidBody& ba = original.world().bodies[0];
  for (const Simulator* other : {&loaded, &from_file}) {
    const RigidBody& bb = other->world().bodies[0];
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(bb.velocity(k), ba.velocity(k)) << k;
      EXPECT_EQ(bb.pose(k), ba.pose(k)) << k;
    }
  }
  EXPECT_GT(c.work, a.work) << "without the marks the step starts with step 1b and the cold attempts";
}

}  // namespace
}  // namespace lcprelax
