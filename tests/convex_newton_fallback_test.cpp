// Fallback of the convex model's active-set Newton solve (contact_step.hpp
// solve_convex_model_newton) to the interior point: when a phase cannot reach a repeated
// active set within its iteration cap (here: 1 factorization from a wrong, all-inactive
// warm start), the island's answer is the interior point's, bitwise, flagged
// newton_fallback, with the Newton factorizations added to `work`; the same island with
// the default cap converges without fallback (a 6-box stack) to the interior point's v⁺
// within 1e-6 m/s, KKT residual ≤ 1e-7.
// Also: an active-set QP whose cap is hit reports converged = false with a message, and
// wrong state sizes throw InputError.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/active_set_qp.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

namespace lcprelax {
namespace {

ContactSystem largest_island(const Scene& scene, int steps) {
  Simulator sim = make_simulator(scene);
  for (int k = 0; k < steps; ++k) sim.step();
  const StepContacts found = find_step_contacts(sim.world(), sim.settings());
  EXPECT_FALSE(found.islands.empty());
  std::size_t big = 0;
  for (std::size_t i = 0; i < found.islands.size(); ++i)
    if (found.islands[i].contacts.size() > found.islands[big].contacts.size()) big = i;
  return assemble_contact_system(sim.world(), found.contacts, found.islands[big], sim.settings().dt);
}

// With every contact claimed inactive last step (λn = 0: wrong for a resting island) and a
// cap of 1 factorization, the island falls back; returns the interior point's answer.
ContactSolution check_capped(const ContactSystem& s, const SimulatorSettings& st) {
  const ContactSolution ipm =
      solve_convex_model(s, st.dt, st.qp, st.convex_rho, ConvexFormulation::automatic, st.convex_softening);
  EXPECT_TRUE(has_solution(ipm.status)) << ipm.message;
  std::vector<signed char> wrong(static_cast<std::size_t>(s.num_contacts() + s.num_friction()), 0);
  const ContactSolution capped = solve_convex_model_newton(s, st.dt, st.qp, st.convex_rho, ConvexFormulation::automatic,
                                                           st.convex_softening, nullptr, wrong, /*max_iterations=*/1);
  EXPECT_TRUE(capped.newton_fallback);
  EXPECT_NE(capped.message.find("active-set Newton"), std::string::npos) << capped.message;
  EXPECT_EQ(capped.status, ipm.status);
  EXPECT_EQ(capped.v_next, ipm.v_next);  // the interior point's answer, bitwise
  EXPECT_EQ(capped.work, ipm.work + 1);  // one Newton factorization, then the IPM's iterations
  EXPECT_TRUE(capped.z_basic.empty());
  return ipm;
}

TEST(ConvexNewtonFallback, CapHitGivesInteriorPointAnswerOnPile) {
  const Scene scene = test::closed_pile(40, 3, ContactModel::convex);
  const ContactSystem s = largest_island(scene, 80);
  ASSERT_GE(s.num_contacts(), 10);
  check_capped(s, scene.settings);
}

TEST(ConvexNewtonFallback, StackCappedFallsBackUncappedConverges) {
  const Scene scene = test::scene_with(test::box_stack(6), 0.5, 1e-2, ContactModel::convex);
  const ContactSystem s = largest_island(scene, 20);
  ASSERT_GE(s.num_contacts(), 10);
  const SimulatorSettings& st = scene.settings;
  const ContactSolution ipm = check_capped(s, st);
  std::vector<signed char> wrong(static_cast<std::size_t>(s.num_contacts() + s.num_friction()), 0);
  const ContactSolution full = solve_convex_model_newton(s, st.dt, st.qp, st.convex_rho, ConvexFormulation::automatic,
                                                         st.convex_softening, nullptr, wrong);
  EXPECT_FALSE(full.newton_fallback) << full.message;
  EXPECT_EQ(full.status, ContactStatus::solved);
  EXPECT_LE(full.residual, 1e-7);
  EXPECT_LE((full.v_next - ipm.v_next).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(full.z_basic.size(), static_cast<std::size_t>(s.num_contacts() + 3 * s.num_friction()));
}

TEST(ActiveSetQpFallback, CapHitIsReportedNotConverged) {
  // min ½|x|² − 2·eᵀx, 0 ≤ x ≤ 1: optimum at the upper bounds; from all-inactive one
  // factorization cannot see it.
  const Index n = 4;
  QpProblem p(n);
  std::vector<Triplet> t;
  for (Index i = 0; i < n; ++i) t.emplace_back(i, i, 1.0);
  p.P.resize(n, n);
  p.P.setFromTriplets(t.begin(), t.end());
  p.q = Vector::Constant(n, -2.0);
  p.xl = Vector::Zero(n);
  p.xu = Vector::Ones(n);
  detail::ActiveSetSettings as;
  as.max_iterations = 1;
  const std::vector<detail::ActiveState> none(static_cast<std::size_t>(n), 0);
  const detail::ActiveSetResult capped = detail::solve_active_set_qp(p, {}, none, as);
  EXPECT_FALSE(capped.converged);
  EXPECT_FALSE(capped.message.empty());
  as.max_iterations = 3;
  const detail::ActiveSetResult ok = detail::solve_active_set_qp(p, {}, none, as);
  ASSERT_TRUE(ok.converged) << ok.message;
  EXPECT_EQ(ok.iterations, 2);
  EXPECT_LE((ok.x - Vector::Ones(n)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE((ok.z_bounds - Vector::Ones(n)).cwiseAbs().maxCoeff(), 1e-9);  // ν = 2 − x = 1 at the upper bound
  EXPECT_THROW(detail::solve_active_set_qp(p, {}, {}, as), InputError);
}

}  // namespace
}  // namespace lcprelax
