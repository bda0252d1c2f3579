// The convex model's phase solvers kept between steps (convex_solver_cache.hpp): a phase
// QP with the cached pattern is updated in place (symbolic analysis reused), any other is
// set up afresh, and either way the answer is the fresh solve's.
// Stated tolerance: v⁺ of a reused solve within 1e-12·max(1, |v*|∞) m/s of the fresh one,
// and along a 120-step trajectory of a closed pile of 40 random polygons (dropping, then
// resting: contacts come and go), poses and velocities of the simulator with reuse within
// 1e-9 (m, rad, m/s) of the one without (measured: bitwise equal, update() redoes the
// scaling of setup() and the ordering of a pattern is deterministic).
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/convex_solver_cache.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace lcprelax {
namespace {

std::vector<ContactSystem> island_systems(const World& world, const SimulatorSettings& settings) {
  const StepContacts found = find_step_contacts(world, settings);
  std::vector<ContactSystem> out;
  for (const Island& island : found.islands)
    out.push_back(assemble_contact_system(world, found.contacts, island, settings.dt));
  return out;
}

ContactSolution solve(const ContactSystem& s, const SimulatorSettings& st, ConvexSolverCache* cache) {
  return solve_convex_model(s, st.dt, st.qp, st.convex_rho, ConvexFormulation::automatic, st.convex_softening, cache);
}

void expect_same(const ContactSolution& reused, const ContactSolution& fresh, const ContactSystem& s) {
  ASSERT_TRUE(has_solution(fresh.status)) << fresh.message;
  EXPECT_EQ(reused.status, fresh.status);
  EXPECT_EQ(reused.work, fresh.work);
  ASSERT_EQ(reused.v_next.size(), fresh.v_next.size());
  const double scale = std::max(1.0, s.v_star.cwiseAbs().maxCoeff());
  EXPECT_LE((reused.v_next - fresh.v_next).cwiseAbs().maxCoeff(), 1e-12 * scale);
}

TEST(ConvexSolverCache, SameIslandIsUpdatedOtherPatternIsSetUp) {
  Simulator sim = make_simulator(test::closed_pile(40, 3, ContactModel::convex));
  for (int k = 0; k < 80; ++k) sim.step();
  const SimulatorSettings& st = sim.settings();
  std::vector<ContactSystem> systems = island_systems(sim.world(), st);
  ASSERT_FALSE(systems.empty());
  std::size_t big = 0;
  for (std::size_t i = 0; i < systems.size(); ++i)
    if (systems[i].num_contacts() > systems[big].num_contacts()) big = i;
  ContactSystem s = systems[big];
  ASSERT_GE(s.num_contacts(), kLiftedMinContacts);

  ConvexSolverCache cache(st.qp);
  const ContactSolution first = solve(s, st, &cache);
  EXPECT_EQ(cache.stats.setups, 2);  // both phases, fresh
  EXPECT_EQ(cache.stats.updates, 0);
  expect_same(first, solve(s, st, nullptr), s);

  // Same contacts, other values (the bodies move faster downwards): updated in place.
  s.v_star(1) -= 0.5;
  s.phi *= 0.5;
  const ContactSolution second = solve(s, st, &cache);
  EXPECT_EQ(cache.stats.setups, 2);
  EXPECT_EQ(cache.stats.updates, 2);
  expect_same(second, solve(s, st, nullptr), s);

  // One contact fewer: another pattern, set up afresh, still the fresh answer.
  ContactSystem t = systems[big];
  const Index nc = t.num_contacts();
  t.Jn = SparseMatrix(t.Jn.topRows(nc - 1));
  t.phi.conservativeResize(nc - 1);
  t.contacts.pop_back();
  std::vector<int> rows;
  std::vector<Index> keep;
  for (std::size_t f = 0; f < t.friction_rows.size(); ++f)
    if (t.friction_rows[f] < nc - 1) keep.push_back(static_cast<Index>(f));
  SparseMatrix jt(static_cast<Index>(keep.size()), t.Jt.cols());
  std::vector<Triplet> trip;
  Vector mu(static_cast<Index>(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k) {
    rows.push_back(t.friction_rows[keep[k]]);
    mu(static_cast<Index>(k)) = t.mu(keep[k]);
    const SparseMatrix row = t.Jt.row(keep[k]);
    for (Index c = 0; c < row.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(row, c); it; ++it) trip.emplace_back(static_cast<Index>(k), it.col(), it.value());
  }
  jt.setFromTriplets(trip.begin(), trip.end());
  t.Jt = jt;
  t.mu = mu;
  t.friction_rows = rows;
  const ContactSolution third = solve(t, st, &cache);
  EXPECT_EQ(cache.stats.setups, 4);
  EXPECT_EQ(cache.stats.updates, 2);
  expect_same(third, solve(t, st, nullptr), t);
}

TEST(ConvexSolverCache, PileTrajectoryWithReuseMatchesFreshSolves) {
  const Scene scene = test::closed_pile(40, 3, ContactModel::convex);
  SimulatorSettings fresh_settings = scene.settings;
  fresh_settings.reuse_convex_solvers = false;
  ASSERT_TRUE(scene.settings.reuse_convex_solvers);  // the default
  Simulator reused = make_simulator(scene);
  Simulator fresh(scene.world, fresh_settings);
  long updates = 0, setups = 0;
  double worst = 0.0;
  for (int k = 0; k < 120; ++k) {
    const StepStats a = reused.step();
    const StepStats b = fresh.step();
    updates += a.solver_updates;
    setups += a.solver_setups;
    EXPECT_EQ(b.solver_updates, 0);
    EXPECT_EQ(a.failed_islands, b.failed_islands);
    EXPECT_EQ(a.work, b.work) << "step " << k;
    for (std::size_t i = 0; i < scene.world.bodies.size(); ++i) {
      const RigidBody& x = reused.world().bodies[i];
      const RigidBody& y = fresh.world().bodies[i];
      worst = std::max({worst, (x.pose - y.pose).cwiseAbs().maxCoeff(), (x.velocity - y.velocity).cwiseAbs().maxCoeff()});
    }
  }
  EXPECT_LE(worst, 1e-9);
  // The trajectory exercises both paths: patterns that repeat and patterns that change.
  EXPECT_GT(updates, 0);
  EXPECT_GT(setups, 0);
  RecordProperty("solver_updates", std::to_string(updates));
  RecordProperty("solver_setups", std::to_string(setups));
  char worst_text[32];
  std::snprintf(worst_text, sizeof worst_text, "%.3g", worst);
  RecordProperty("worst_difference", worst_text);
}

}  // namespace
}  // namespace lcprelax
