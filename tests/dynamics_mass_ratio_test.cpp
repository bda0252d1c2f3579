// High mass ratios and extreme friction (both contact models unless stated).
// Expected:
// - A plank 1,000× and 1,000,000× heavier than the two 1 kg boxes it rests on (2 m × 0.2 m
//   plank on two 0.2 m boxes on the ground, every gap 0) stays at rest: over 200 steps of
//   Δt = 1e-2 no failed island, every centre within 1e-6 m of its start, penetration
//   < 1e-4 m (measured numbers printed). Exception, a known limitation: with the convex
//   model at 10⁶, phase 2's interior point fails in every step ("no progress": W has
//   eigenvalues from 1e-6 to 4 and the impulses are 10⁶ times q/W; κ loosened to 1e-2
//   and dropping κ do not help. Measured in the first step: the normal rows' optimal
//   multipliers are ~6e7, since the softening's gradient ρ·Wnn·λn ≈ 25 m/s is balanced
//   through rows whose coefficient along the plank's direction is ~1e-6; the gap stays
//   at 24.5 J (1e-6 of its scale 2.4e7; the tolerance is an absolute 1e-8), which with
//   those multipliers is the rows standing ~4e-7 m/s off their bound), so "no failed island" is NOT
//   asserted there; each failed
//   island falls back to the LCP model (Lemke; simulator.hpp), which is asserted (the
//   failure message says "lcp model used"), and keeps the plank at rest (drift < 1e-6 m,
//   penetration < 1e-4 m, asserted; measured 2.6e-8 m and 1.8e-8 m. The earlier fallback,
//   phase 1's frictionless answer, drifted 4.7e-7 m with CHOLMOD and 1.6e-6 m with the
//   dense KKT path: roundoff sliding with no friction to hold it).
// - μ = 0: a box pushed along frictionless ground keeps its horizontal speed exactly
//   (to 1e-12 relative) for 500 steps, and the total energy never increases (each step
//   E_{k+1} ≤ E_k + tol, tol = 1e-12·E_0 for the LCP; 1e-8 J for the convex model: its
//   interior point stops at a duality gap of eps_abs = 1e-8 in its objective, which is an
//   energy (½λᵀWλ + λᵀJv*, J), and leaves the contact that much complementarity: measured
//   7.6e-9 J in the first step, a 7.7e-8 m/s upward speed).
// - μ = 1,000: a flat box (1 m × 0.2 m, 1 kg) sliding at 0.4 m/s stops within one step
//   (|v| < 1e-9 after the first step; at 0.4 m/s the stopping impulse's torque is held by
//   the two normal impulses without lifting the rear edge) and stays stopped for 100 steps.
//   The convex model runs with ρ = 1e-9 and eps_abs = 1e-11 here (as in the incline
//   test) and is held to 1e-7: with the default ρ = 1e-3 its normal impulses are
//   penalized and it trades them for a residual rocking of 6e-5 m/s (measured).
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <tuple>

namespace lcprelax {
namespace {

class MassRatio : public ::testing::TestWithParam<std::tuple<ContactModel, double>> {};

TEST_P(MassRatio, HeavyPlankOnSmallBoxesStaysAtRest) {
  const auto [model, ratio] = GetParam();
  Simulator sim = make_simulator(test::scene_with({test::box(0.2, 0.2, 1.0, Vec3(-0.8, 0.1, 0.0)),
                                  test::box(0.2, 0.2, 1.0, Vec3(0.8, 0.1, 0.0)),
                                  test::box(2.0, 0.2, ratio, Vec3(0.0, 0.3, 0.0))},
                                 0.5, 1e-2, model));
  const std::vector<Vec3> start = test::poses(sim.world());
  const bool known_failure = model == ContactModel::convex && ratio > 1e5;
  double penetration = 0.0, drift = 0.0;
  int failed = 0;
  for (int k = 0; k < 200; ++k) {
    const StepStats st = sim.step();
    if (!known_failure) {
      ASSERT_EQ(st.failed_islands, 0) << "step " << k << ": " << st.first_failure;
    } else if (st.failed_islands > 0) {
      ASSERT_NE(st.first_failure.find("lcp model used"), std::string::npos) << "step " << k << ": " << st.first_failure;
    }
    ASSERT_EQ(st.solved_islands + st.inaccurate_islands + st.failed_islands, st.islands) << "step " << k;
    failed += st.failed_islands;
    penetration = std::max(penetration, st.max_penetration);
    drift = std::max(drift, test::max_drift(sim.world(), start));
  }
  std::printf("[ measured ] %s, mass ratio %g: drift %.3g m, penetration %.3g m, failed islands %d\n",
              to_string(model), ratio, drift, penetration, failed);
  EXPECT_LT(drift, 1e-6);
  EXPECT_LT(penetration, 1e-4);
  if (known_failure) {
    EXPECT_GT(failed, 0) << "the known phase-2 failure no longer occurs: update this test";
  }
}

INSTANTIATE_TEST_SUITE_P(LcpAndConvex, MassRatio,
                         ::testing::Combine(::testing::Values(ContactModel::lcp, ContactModel::convex),
                                            ::testing::Values(1e3, 1e6)));

// The convex model at mass ratio 10⁶ with the lifted formulation and ρ = 1e-6
// (SimulatorSettings::convex_formulation): every island solved, the plank at rest. The dual
// formulation of the same QPs fails (asserted, so that the documented advice is checked), and
// lifted with the default ρ = 1e-3 solves but lets the boxes slip (the softening artifact
// documented in simulator.hpp; asserted as a drift above 1e-3 m).
struct PlankRun {
  int failed = 0;
  double drift = 0.0, penetration = 0.0;
};

PlankRun run_heavy_plank(ConvexFormulation formulation, double rho) {
  SimulatorSettings settings;
  settings.convex_formulation = formulation;
  settings.convex_rho = rho;
  Simulator sim = make_simulator(test::scene_with({test::box(0.2, 0.2, 1.0, Vec3(-0.8, 0.1, 0.0)),
                                  test::box(0.2, 0.2, 1.0, Vec3(0.8, 0.1, 0.0)),
                                  test::box(2.0, 0.2, 1e6, Vec3(0.0, 0.3, 0.0))},
                                 0.5, 1e-2, ContactModel::convex),
                                 settings);
  const std::vector<Vec3> start = test::poses(sim.world());
  PlankRun r;
  for (int k = 0; k < 200; ++k) {
    const StepStats st = sim.step();
    r.failed += st.failed_islands;
    r.penetration = std::max(r.penetration, st.max_penetration);
    r.drift = std::max(r.drift, test::max_drift(sim.world(), start));
  }
  return r;
}

TEST(MassRatioFormulation, LiftedWithSmallSofteningSolvesAPlankOneMillionTimesHeavier) {
  const PlankRun lifted = run_heavy_plank(ConvexFormulation::lifted, 1e-6);
  const PlankRun dual = run_heavy_plank(ConvexFormulation::dual, 1e-6);
  const PlankRun soft = run_heavy_plank(ConvexFormulation::lifted, 1e-3);
  std::printf("[ measured ] ratio 1e6: lifted rho 1e-6 failed %d drift %.3g m; dual rho 1e-6 failed %d; "
              "lifted rho 1e-3 failed %d drift %.3g m\n",
              lifted.failed, lifted.drift, dual.failed, soft.failed, soft.drift);
  EXPECT_EQ(lifted.failed, 0);
  EXPECT_LT(lifted.drift, 1e-6);
  EXPECT_LT(lifted.penetration, 1e-4);
  EXPECT_GT(dual.failed, 100) << "the dual formulation now solves this: revise simulator.hpp's advice";
  EXPECT_GT(soft.drift, 1e-3) << "the softening artifact is gone: revise simulator.hpp's note";
}

TEST(MassRatioFormulation, RefusesAnUnknownFormulation) {
  SimulatorSettings settings;
  settings.convex_formulation = static_cast<ConvexFormulation>(7);
  EXPECT_NE(settings.validation_error().find("convex_formulation"), std::string::npos);
}

class ExtremeFriction : public ::testing::TestWithParam<ContactModel> {};

TEST_P(ExtremeFriction, FrictionlessBoxSlidesForeverWithoutEnergyGain) {
  Scene scene = test::scene_with({test::box(1.0, 0.2, 1.0, Vec3(0.0, 0.1, 0.0))}, 0.0, 1e-2, GetParam());
  scene.world.bodies[0].velocity = Vec3(2.0, 0.0, 0.0);
  Simulator sim = make_simulator(scene);
  const double e0 = sim.total_energy(), tol = GetParam() == ContactModel::lcp ? 1e-12 * e0 : 1e-8;
  double e = e0;
  for (int k = 0; k < 500; ++k) {
    const StepStats st = sim.step();
    ASSERT_EQ(st.failed_islands, 0) << st.first_failure;
    ASSERT_NEAR(sim.world().bodies[0].velocity.x(), 2.0, 2e-12) << "step " << k;
    const double next = sim.total_energy();
    ASSERT_LE(next, e + tol) << "step " << k;
    e = next;
  }
  EXPECT_NEAR(sim.world().bodies[0].pose.x(), 500 * 1e-2 * 2.0, 1e-9);
}

TEST_P(ExtremeFriction, MuOneThousandStopsASlidingBoxInOneStep) {
  Scene scene = test::scene_with({test::box(1.0, 0.2, 1.0, Vec3(0.0, 0.1, 0.0))}, 1000.0, 1e-2, GetParam());
  scene.world.bodies[0].velocity = Vec3(0.4, 0.0, 0.0);
  SimulatorSettings settings;
  settings.convex_rho = 1e-9;
  settings.qp.eps_abs = 1e-11;
  Simulator sim = make_simulator(scene, settings);
  const double tol = GetParam() == ContactModel::lcp ? 1e-9 : 1e-7;
  for (int k = 0; k < 100; ++k) {
    const StepStats st = sim.step();
    ASSERT_EQ(st.failed_islands, 0) << st.first_failure;
    ASSERT_LT(sim.world().bodies[0].velocity.norm(), tol) << "step " << k;
  }
  EXPECT_NEAR(sim.world().bodies[0].pose.x(), 0.0, tol);
}

INSTANTIATE_TEST_SUITE_P(LcpAndConvex, ExtremeFriction, ::testing::Values(ContactModel::lcp, ContactModel::convex));

}  // namespace
}  // namespace lcprelax
