// The convex model by the warm-started active-set Newton method (contact_step.hpp
// solve_convex_model_newton, active_set_qp.hpp) against the interior point on the same QPs.
// Stated tolerances:
// - per island and step of a dropping-then-settling closed pile (40 random polygons, 120
//   steps, the interior-point simulator's states) and of a 6-box stack (60 steps): v⁺ of
//   the Newton solve (warm-started from its own previous step, contacts matched by the
//   simulator's key) within kVTol = 1e-5·max(1, |v*|∞) m/s of the interior point's
//   (measured 6.7e-6 pile, 1.5e-7 stack), its phase-2 KKT residual (checked by the solver,
//   re-checked here) ≤ kKktTol (measured 8e-9), and a fallback's v⁺ bitwise the interior
//   point's;
// - trajectories of the simulator with ConvexSolver::active_set_newton (warm-started) and
//   with the interior point: the 6-box stack's poses within 1e-6 (m, rad) after 200 steps;
//   the pile's poses within kPileTol after 30 steps (contacts come and go while it drops).
// - generated bound-constrained QPs (M-matrix Hessians, where the method provably converges,
//   Hintermüller et al. 2002): x within 1e-7 of the interior point's, KKT residuals ≤ 1e-9.
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/models/active_set_qp.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <array>
#include <map>
#include <random>

namespace lcprelax {
namespace {

constexpr double kVTol = 1e-5;
constexpr double kPileTol = 1e-4;
constexpr double kKktTol = 1e-7;  // max(primal, dual) of phase 2 (dual ≤ eps_abs·max(1, ‖q‖∞))
// Measured: 134 of 323 island solves fell back (the primal phase needs > 20 factorizations
// where many friction rows change; see active_set_qp.hpp), 0 of 60 on the stack.
constexpr double kPileFallbackShare = 0.5;

using Key = std::array<int, 5>;
// Per contact: λn > 0 last step, and the friction state (+1, −1, 0), keyed like the simulator.
using WarmMap = std::map<Key, std::array<signed char, 2>>;

std::vector<Key> keys_of(const std::vector<Contact>& contacts) {
  std::vector<Key> keys(contacts.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    keys[i] = {c.body_a, c.body_b, static_cast<int>(c.static_kind), c.static_index, 0};
    if (i > 0 && std::equal(keys[i].begin(), keys[i].begin() + 4, keys[i - 1].begin())) keys[i][4] = keys[i - 1][4] + 1;
  }
  return keys;
}

struct Tally {
  int solves = 0, fallbacks = 0;
  double worst = 0.0;      // max |Δv⁺| / max(1, |v*|∞) over converged Newton solves
  double worst_kkt = 0.0;  // max ContactSolution::residual of converged Newton solves
};

// Every island of `world`'s next step by the interior point and by Newton (warm-started
// from `warm`, which is then replaced by this step's final states).
void compare_islands(const World& world, const SimulatorSettings& st, WarmMap& warm, Tally& t) {
  const StepContacts found = find_step_contacts(world, st);
  const std::vector<Key> keys = keys_of(found.contacts);
  WarmMap next;
  for (const Island& island : found.islands) {
    const ContactSystem s = assemble_contact_system(world, found.contacts, island, st.dt);
    const Index nc = s.num_contacts(), nf = s.num_friction();
    std::vector<signed char> w(static_cast<std::size_t>(nc + nf), 0);
    for (Index c = 0; c < nc; ++c) {
      auto it = warm.find(keys[s.contacts[c]]);
      w[c] = it == warm.end() ? -1 : it->second[0];
    }
    for (Index f = 0; f < nf; ++f) {
      auto it = warm.find(keys[s.contacts[s.friction_rows[f]]]);
      if (it != warm.end()) w[nc + f] = it->second[1];
    }
    const ContactSolution ipm =
        solve_convex_model(s, st.dt, st.qp, st.convex_rho, ConvexFormulation::automatic, st.convex_softening);
    const ContactSolution nt = solve_convex_model_newton(s, st.dt, st.qp, st.convex_rho, ConvexFormulation::automatic,
                                                         st.convex_softening, nullptr, w);
    if (!has_solution(ipm.status)) continue;
    EXPECT_TRUE(has_solution(nt.status)) << nt.message;
    ++t.solves;
    if (nt.newton_fallback) {
      if (t.fallbacks < 3) std::printf("fallback: %s\n", nt.message.c_str());
      ++t.fallbacks;
      EXPECT_EQ(nt.v_next, ipm.v_next);  // the interior point's answer
      continue;
    }
    t.worst_kkt = std::max(t.worst_kkt, nt.residual);
    const double scale = std::max(1.0, s.v_star.cwiseAbs().maxCoeff());
    t.worst = std::max(t.worst, (nt.v_next - ipm.v_next).cwiseAbs().maxCoeff() / scale);
    if (static_cast<Index>(nt.z_basic.size()) != nc + 3 * nf) continue;
    for (Index c = 0; c < nc; ++c) next[keys[s.contacts[c]]][0] = nt.z_basic[c] ? 1 : 0;
    for (Index f = 0; f < nf; ++f)
      next[keys[s.contacts[s.friction_rows[f]]]][1] = nt.z_basic[nc + f] ? 1 : (nt.z_basic[nc + nf + f] ? -1 : 0);
  }
  warm.swap(next);
}

TEST(ConvexNewton, PerStepAgreementOnPile) {
  Simulator sim = make_simulator(test::closed_pile(40, 5, ContactModel::convex));
  WarmMap warm;
  Tally t;
  for (int k = 0; k < 120; ++k) {
    compare_islands(sim.world(), sim.settings(), warm, t);
    sim.step();
  }
  std::printf("pile: %d island solves, %d fallbacks, worst |dv|/scale %.3g, worst KKT residual %.3g\n", t.solves,
              t.fallbacks, t.worst, t.worst_kkt);
  EXPECT_GT(t.solves, 120);
  EXPECT_LE(t.fallbacks, kPileFallbackShare * t.solves);
  EXPECT_LE(t.worst, kVTol);
  EXPECT_LE(t.worst_kkt, kKktTol);
}

TEST(ConvexNewton, PerStepAgreementOnStack) {
  Simulator sim = make_simulator(test::scene_with(test::box_stack(6), 0.5, 1e-2, ContactModel::convex));
  WarmMap warm;
  Tally t;
  for (int k = 0; k < 60; ++k) {
    compare_islands(sim.world(), sim.settings(), warm, t);
    sim.step();
  }
  std::printf("stack: %d island solves, %d fallbacks, worst |dv|/scale %.3g, worst KKT residual %.3g\n", t.solves,
              t.fallbacks, t.worst, t.worst_kkt);
  EXPECT_GT(t.solves, 50);
  EXPECT_EQ(t.fallbacks, 0);
  EXPECT_LE(t.worst, kVTol);
  EXPECT_LE(t.worst_kkt, kKktTol);
}

// One post-stabilization pass: further passes re-detect contacts at projected positions, a
// discontinuous map that turns the solvers' roundoff differences into larger trajectory
// differences (pile: 2.3e-4 m with the default 5 passes); this compares the velocity solvers.
double trajectory_gap(Scene scene, int steps, int& fallbacks) {
  scene.settings.post_stabilization_passes = 1;
  Simulator ipm = make_simulator(scene);
  SimulatorSettings ns = scene.settings;
  ns.convex_solver = ConvexSolver::active_set_newton;
  Simulator nt(scene.world, ns);
  fallbacks = 0;
  for (int k = 0; k < steps; ++k) {
    ipm.step();
    const StepStats st = nt.step();
    EXPECT_EQ(st.failed_islands, 0) << st.first_failure;
    fallbacks += st.newton_fallbacks;
  }
  double gap = 0.0;
  for (std::size_t b = 0; b < scene.world.bodies.size(); ++b)
    gap = std::max(gap, (ipm.world().bodies[b].pose - nt.world().bodies[b].pose).cwiseAbs().maxCoeff());
  return gap;
}

TEST(ConvexNewton, TrajectoriesAgree) {
  int fallbacks = 0;
  const double stack = trajectory_gap(test::scene_with(test::box_stack(6), 0.5, 1e-2, ContactModel::convex), 200, fallbacks);
  std::printf("stack trajectory gap %.3g (fallbacks %d)\n", stack, fallbacks);
  EXPECT_LE(stack, 1e-6);
  const double pile = trajectory_gap(test::closed_pile(40, 5, ContactModel::convex), 30, fallbacks);
  std::printf("pile trajectory gap %.3g (fallbacks %d)\n", pile, fallbacks);
  EXPECT_LE(pile, kPileTol);
}

TEST(ActiveSetQp, GeneratedBoundConstrainedQpsMatchInteriorPoint) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Index n = 30;
    QpProblem p(n);
    std::vector<Triplet> t;
    for (Index i = 0; i < n; ++i) {
      t.emplace_back(i, i, 3.0 + u(rng));
      if (i + 1 < n) t.emplace_back(i, i + 1, -0.5 - 0.4 * std::abs(u(rng)));  // M-matrix: off-diagonals ≤ 0
    }
    p.P.resize(n, n);
    p.P.setFromTriplets(t.begin(), t.end());
    for (Index i = 0; i < n; ++i) {
      p.q(i) = 3.0 * u(rng);
      p.xl(i) = -0.5 + 0.3 * u(rng);
      p.xu(i) = 0.5 + 0.3 * u(rng);
    }
    QpSettings qs;
    qs.eps_abs = 1e-11;
    QpSolver qp(qs);
    qp.setup(p);
    const QpResult& r = qp.solve();
    ASSERT_TRUE(has_solution(r.info.status));
    detail::ActiveSetSettings as;
    as.eps_abs = 1e-9;
    as.max_iterations = 40;
    const Vector start = Vector::Zero(n);  // xl < 0 < xu: feasible
    const detail::ActiveSetResult a = detail::solve_active_set_qp(
        p, {}, std::vector<detail::ActiveState>(static_cast<std::size_t>(n), 0), as, &start);
    ASSERT_TRUE(a.converged) << a.message;
    EXPECT_LE(a.primal_residual, 1e-9);
    EXPECT_LE(a.dual_residual, 1e-9 * std::max(1.0, p.q.cwiseAbs().maxCoeff()));
    EXPECT_LE((a.x - r.x).cwiseAbs().maxCoeff(), 1e-7);
  }
}

}  // namespace
}  // namespace lcprelax
