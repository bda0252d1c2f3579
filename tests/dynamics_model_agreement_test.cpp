// Agreement between the two contact models and between the two LCP solvers.
//
// 1. Lemke and the interior point on the same LCP. Frictionless contact problems are
//    monotone LCPs (M = Wnn = Jn M⁻¹ Jnᵀ, positive semidefinite): 0 ≤ λn ⊥ Wnn λn + q ≥ 0,
//    q = Jn v* + max(φ, 0)/Δt. Expected: on every island of a frictionless closed pile
//    of 30 polygons, taken at several steps while it falls and settles, Lemke
//    (lcp/lemke.hpp) solves the LCP to complementarity ≤ 1e-9·max(1, ‖q‖∞), the
//    interior point (lcp/lcp_ipm.hpp, eps_abs = 1e-12) to ≤ 1e-6·max(1, ‖q‖∞) (on
//    degenerate LCPs, resting polygons with more contacts than needed, its
//    zᵀ(Mz + q) objective reaches only about √eps per component; lcp_ipm.hpp then reports
//    numerical_error, which is accepted here with that residual), and both give the same
//    post-impact velocities
//    v⁺ = v* + M⁻¹Jnᵀλn to 1e-6·max(1, ‖v*‖∞) (v⁺ is unique even where λn is not: it is
//    the M-projection of v* onto the cone Jn v + q' ≥ 0).
// 2. Stick/slip outcome of simple scenes. A 1 m × 0.2 m box of 1 kg rests on the ground
//    (μ = 0.5) and is pushed horizontally through its centre by F. Coulomb: it sticks iff
//    F ≤ μ m g; when it slides, its acceleration is (F − μ m g)/m. Expected: for
//    F/(μ m g) ∈ {0.5, 0.9, 1.1, 2}, the LCP model and the convex model (ρ = 1e-9,
//    eps_abs = 1e-11, as in the incline test) both give the Coulomb outcome: speed
//    < 1e-7 m/s after 50 steps when sticking, else the acceleration over steps 10..50 to
//    1e-5 relative; and the two models' velocities agree to 1e-6 m/s.
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/lcp/lcp_ipm.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace lcprelax {
namespace {

double complementarity(const SparseMatrix& M, const Vector& q, const Vector& z) {
  if (z.size() == 0) return 0.0;
  return z.cwiseMin(M * z + q).cwiseAbs().maxCoeff();
}

TEST(LemkeVsInteriorPoint, FrictionlessPileIslandsGiveTheSameVelocities) {
  Simulator sim = make_simulator(test::closed_pile(30, 5, ContactModel::lcp, 0.0));
  const double dt = sim.settings().dt;
  int compared = 0, degenerate = 0;
  double worst = 0.0;
  for (int k = 1; k <= 150; ++k) {
    ASSERT_EQ(sim.step().failed_islands, 0);
    if (k % 15 != 0) continue;
    const World& world = sim.world();
    const std::vector<Contact> contacts = find_contacts(world, CollisionSettings{1e-2});
    for (const Island& island : find_islands(world, contacts)) {
      const ContactSystem s = assemble_contact_system(world, contacts, island, dt);
      ASSERT_EQ(s.num_friction(), 0);
      const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), dt);  // μ = 0: the normal LCP
      const double scale = std::max(1.0, lcp.q.lpNorm<Eigen::Infinity>());
      LemkeSolver lemke;
      lemke.setup(lcp.M, lcp.q);
      const LcpResult& a = lemke.solve();
      ASSERT_EQ(a.info.status, LcpStatus::solved) << a.info.message;
      QpSettings tight;
      tight.eps_abs = 1e-12;
      const LcpResult b = solve_lcp_ipm(lcp.M, lcp.q, tight);
      ASSERT_TRUE(b.info.status == LcpStatus::solved || b.info.status == LcpStatus::numerical_error)
          << b.info.message;
      ASSERT_EQ(b.z.size(), lcp.q.size()) << b.info.message;
      degenerate += b.info.status == LcpStatus::numerical_error;
      EXPECT_LE(complementarity(lcp.M, lcp.q, a.z), 1e-9 * scale);
      EXPECT_LE(complementarity(lcp.M, lcp.q, b.z), 1e-6 * scale);
      const Vector va = s.v_star + s.minv.cwiseProduct(s.Jn.transpose() * a.z);
      const Vector vb = s.v_star + s.minv.cwiseProduct(s.Jn.transpose() * b.z);
      const double diff = (va - vb).lpNorm<Eigen::Infinity>() / std::max(1.0, s.v_star.lpNorm<Eigen::Infinity>());
      EXPECT_LE(diff, 1e-6) << "step " << k << ", island of " << s.num_contacts() << " contacts";
      worst = std::max(worst, diff);
      ++compared;
    }
  }
  std::printf("[ measured ] %d island LCPs compared (%d solved by the interior point only to √eps), largest relative "
              "velocity difference %.3g\n", compared, degenerate, worst);
  EXPECT_GE(compared, 10);
}

class PushedBox : public ::testing::TestWithParam<double> {};

Vec3 pushed_box_velocity(ContactModel model, double force, int steps, double& accel) {
  SimulatorSettings settings;
  settings.convex_rho = 1e-9;
  settings.qp.eps_abs = 1e-11;
  Simulator sim = make_simulator(test::scene_with({test::box(1.0, 0.2, 1.0, Vec3(0.0, 0.1, 0.0))}, 0.5, 1e-2, model), settings);
  const std::vector<Vec3> push = {Vec3(force, 0.0, 0.0)};
  double v10 = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const StepStats st = sim.step(push);
    EXPECT_EQ(st.failed_islands, 0) << st.first_failure;
    if (k == 10) v10 = sim.world().bodies[0].velocity.x();
  }
  accel = (sim.world().bodies[0].velocity.x() - v10) / ((steps - 10) * 1e-2);
  return sim.world().bodies[0].velocity;
}

TEST_P(PushedBox, BothModelsGiveTheCoulombOutcome) {
  const double mu = 0.5, g = 9.81, ratio = GetParam(), force = ratio * mu * g;
  double a_lcp = 0.0, a_convex = 0.0;
  const Vec3 v_lcp = pushed_box_velocity(ContactModel::lcp, force, 50, a_lcp);
  const Vec3 v_convex = pushed_box_velocity(ContactModel::convex, force, 50, a_convex);
  EXPECT_LT((v_lcp - v_convex).norm(), 1e-6);
  if (ratio <= 1.0) {
    EXPECT_LT(v_lcp.norm(), 1e-7);
    EXPECT_LT(v_convex.norm(), 1e-7);
  } else {
    const double expected = force - mu * g;  // m = 1 kg
    EXPECT_NEAR(a_lcp, expected, 1e-5 * expected);
    EXPECT_NEAR(a_convex, expected, 1e-5 * expected);
  }
}

INSTANTIATE_TEST_SUITE_P(ForceOverMuMg, PushedBox, ::testing::Values(0.5, 0.9, 1.1, 2.0));

}  // namespace
}  // namespace lcprelax
