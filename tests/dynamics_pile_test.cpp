// Total energy never increases in a closed pile without inputs.
// Expected: 30 random convex polygons (tests/dynamics_support.hpp closed_pile: 3-8
// vertices, 0.1-0.2 m, 100 kg/m², at rest 5-15 cm apart on a grid up to 1.9 m high)
// fall into a container (ground + two walls) and settle. Over 300 steps of Δt = 1e-2
// (3 s: all have landed, up to 115 contacts), with both contact models:
// - no failed island;
// - the total energy (kinetic + potential, Simulator::total_energy) of step k + 1 is at
//   most that of step k plus 1e-9·E₀ (E₀ the initial total, 1.63 kJ here; measured: the
//   energy falls in every step, by at least 2e-7·E₀ (LCP) and 2e-6·E₀ (convex));
// - the energy lost in total is positive (contacts dissipate; measured 66% and 71%).
//
// Determinism over threads: islands are solved in parallel with OpenMP, each on its own
// data, and gathered in island order. Expected: the closed pile of 30 random polygons
// (dynamics_support.hpp) stepped 50 times (it falls and splits into several islands)
// with SimulatorSettings::threads = 1 and = 2 gives bitwise identical poses and
// velocities, with both contact models.
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

namespace lcprelax {
namespace {

class ClosedPile : public ::testing::TestWithParam<ContactModel> {};

TEST_P(ClosedPile, TotalEnergyNeverIncreases) {
  Simulator sim = make_simulator(test::closed_pile(30, 7, GetParam()));
  const double e0 = sim.total_energy();
  double e = e0, largest_gain = -1e300;
  int worst_step = -1, contacts_max = 0;
  for (int k = 0; k < 300; ++k) {
    const StepStats st = sim.step();
    ASSERT_EQ(st.failed_islands, 0) << "step " << k << ": " << st.first_failure;
    ASSERT_EQ(st.solved_islands + st.inaccurate_islands + st.failed_islands, st.islands) << "step " << k;
    contacts_max = std::max(contacts_max, st.contacts);
    const double next = sim.total_energy();
    if (next - e > largest_gain) {
      largest_gain = next - e;
      worst_step = k;
    }
    EXPECT_LE(next, e + 1e-9 * e0) << "step " << k << ": gain " << (next - e) / e0 << " of E0";
    e = next;
  }
  std::printf("[ measured ] %s: E0 %.6g J, largest one-step change %.3g·E0 (step %d), lost %.3g·E0, %d contacts max\n",
              to_string(GetParam()), e0, largest_gain / e0, worst_step, (e0 - e) / e0, contacts_max);
  EXPECT_LT(e, e0);
}

INSTANTIATE_TEST_SUITE_P(LcpAndConvex, ClosedPile, ::testing::Values(ContactModel::lcp, ContactModel::convex));

World run(ContactModel model, int threads, int& islands_max) {
  SimulatorSettings settings;
  settings.threads = threads;
  Simulator sim = make_simulator(test::closed_pile(30, 11, model), settings);
  islands_max = 0;
  for (int k = 0; k < 50; ++k) {
    const StepStats st = sim.step();
    EXPECT_EQ(st.failed_islands, 0) << st.first_failure;
    islands_max = std::max(islands_max, st.islands);
  }
  return sim.world();
}

class Threads : public ::testing::TestWithParam<ContactModel> {};

TEST_P(Threads, OneAndTwoThreadsGiveBitwiseIdenticalStates) {
  int islands1 = 0, islands2 = 0;
  const World a = run(GetParam(), 1, islands1), b = run(GetParam(), 2, islands2);
  EXPECT_GT(islands1, 1) << "the test needs several islands at once";
  EXPECT_EQ(islands1, islands2);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(std::memcmp(a.bodies[i].pose.data(), b.bodies[i].pose.data(), 3 * sizeof(double)), 0) << "body " << i;
    EXPECT_EQ(std::memcmp(a.bodies[i].velocity.data(), b.bodies[i].velocity.data(), 3 * sizeof(double)), 0)
        << "body " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(LcpAndConvex, Threads, ::testing::Values(ContactModel::lcp, ContactModel::convex));

}  // namespace
}  // namespace lcprelax
