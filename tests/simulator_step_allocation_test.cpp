// Heap allocations of a simulator step do not grow with the number of contacts (the step's
// hot loops allocate per step or per island, never per contact).
// Expected: a resting pyramid of unit boxes with the LCP model (one island, every step
// after the first solved by the previous step's basis), threads = 1: the allocations per
// step over steps 3–12 are the same for a base of 5 (15 boxes, 50 contacts) and of 15
// (120 boxes, 450 contacts), up to kSlack allocations (containers that grow by doubling
// reach their size in a few more reallocations for 9× the contacts).
#include <lcprelax/models/simulator.hpp>

#include "allocation_counter.hpp"
#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace lcprelax {
namespace {

constexpr long kSlack = 40;

struct Count {
  long allocations_per_step = 0;
  double contacts = 0;
};

Count step_allocations(int base) {
  Scene scene = test::scene_with(test::box_pyramid(base), 0.5, 1e-2, ContactModel::lcp);
  scene.settings.threads = 1;
  Simulator sim = make_simulator(scene);
  for (int k = 0; k < 3; ++k) sim.step();
  constexpr int kSteps = 10;
  long allocations = 0, contacts = 0;
  for (int k = 0; k < kSteps; ++k) {
    test::AllocationCounter counter;
    const StepStats st = sim.step();
    allocations += counter.stop();
    contacts += st.contacts;
    EXPECT_EQ(st.failed_islands, 0);
  }
  return {allocations / kSteps, static_cast<double>(contacts) / kSteps};
}

TEST(SimulatorStepAllocation, DoesNotGrowWithContacts) {
  const Count small = step_allocations(5), large = step_allocations(15);
  std::printf("[ measured ] allocations per step: %ld with %.0f contacts, %ld with %.0f contacts\n",
              small.allocations_per_step, small.contacts, large.allocations_per_step, large.contacts);
  ASSERT_GT(large.contacts, 5 * small.contacts);
  EXPECT_LE(large.allocations_per_step, small.allocations_per_step + kSlack);
}

}  // namespace
}  // namespace lcprelax
