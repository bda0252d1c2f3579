// The sparse lifted relaxed loss of one island (learn/step_loss_relaxed.hpp): central
// finite differences of ℓ against every entry of the envelope-theorem cotangent and along
// random directions (box on the ground, two stacked boxes, an island of a settled 20-body
// pile), the same directional derivatives by the QP adjoint (QpSolver::backward), the
// workspace's update path, and statuses.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/learn/step_loss_relaxed.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene.hpp>

#include <gtest/gtest.h>

#include "contact_island_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <random>

namespace lcprelax::learn {
namespace {

using testing::box_stack;
using testing::for_each_entry;
using testing::largest_island;

constexpr double kDt = 1e-2;

RelaxedStepLossSettings tight() {
  RelaxedStepLossSettings st;
  st.qp.eps_abs = 1e-12;
  return st;
}

// For the finite-difference checks: ε = 1e-3 (relaxed_lcp.hpp's default, the seeds' value).
// With the polygon's ε = 1e-6 the weakly regularized unknowns (β⁻ of a sticking contact,
// λn of redundant contacts) put an active-set change within 1e-7..1e-5 of typical data,
// where the value function's curvature is O(1/ε): central differences with h ≥ 1e-6 then
// straddle it and disagree with the (correct) one-point derivative by up to 1e-2 relative.
RelaxedStepLossSettings fd_settings() {
  RelaxedStepLossSettings st = tight();
  st.regularization = 1e-3;
  return st;
}



const ContactSystem& pile_island() {
  static const ContactSystem s = testing::settled_pile_island(20, 3, 400);
  return s;
}


Vector noisy_target(const ContactSystem& s, std::uint64_t seed, double size) {
  const ContactSolution sol = solve_lcp_model(s, kDt, LemkeSettings{});
  EXPECT_TRUE(has_solution(sol.status));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector t = sol.v_next;
  for (Index k = 0; k < t.size(); ++k) t(k) += size * u(rng);
  return t;
}

// Random direction in data space, scaled by each entry's magnitude.
std::vector<double> random_direction(ContactSystem& s, const ContactSystemCotangent& g, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> dir;
  for_each_entry(s, g, [&](double& x, double, const std::string&) { dir.push_back(u(rng) * std::max(0.1, std::abs(x))); });
  return dir;
}

ContactSystem moved(ContactSystem s, const ContactSystemCotangent& g, const std::vector<double>& dir, double h) {
  std::size_t i = 0;
  for_each_entry(s, g, [&](double& x, double, const std::string&) { x += h * dir[i++]; });
  return s;
}

// Finite differences (every entry if asked; random directions always) and the adjoint check.
// With `center`, the shift is centred there (held fixed under the differences).
void check_gradient(ContactSystem s, const Vector& target, std::uint64_t seed, int stride = 1,
                    const RelaxedStepLossSettings& settings = fd_settings(), const Vector* center = nullptr,
                    double h = 1e-6, double adjoint_tol = 1e-5) {
  RelaxedStepLossWorkspace ws(settings);
  const StepLossResult r = ws.evaluate(s, target, kDt, center);
  ASSERT_EQ(r.status, ContactStatus::solved) << r.message;
  RelaxedStepLossWorkspace probe(settings);
  auto loss = [&](const ContactSystem& p) {
    const StepLossResult rp = probe.evaluate(p, target, kDt, center);
    EXPECT_EQ(rp.status, ContactStatus::solved) << rp.message;
    return rp.loss;
  };
  double gmax = 0.0;
  for_each_entry(s, r.grad, [&](double&, double g, const std::string&) { gmax = std::max(gmax, std::abs(g)); });
  const double floor = 1e-8 * gmax;
  double worst = 0.0;
  int index = 0;
  for_each_entry(s, r.grad, [&](double& x, double g, const std::string& kind) {
      if (index++ % stride != 0) return;
      const double x0 = x, hx = h * std::max(1.0, std::abs(x0));
      x = x0 + hx;
      const double lp = loss(s);
      x = x0 - hx;
      const double lm = loss(s);
      x = x0;
      const double fd = (lp - lm) / (2 * hx);
      const double err = std::abs(fd - g) / (std::max(std::abs(fd), std::abs(g)) + 1e3 * floor);
      worst = std::max(worst, err);
      EXPECT_LE(std::abs(fd - g), 1e-5 * std::max(std::abs(fd), std::abs(g)) + floor) << kind << " value " << x0 << ": fd " << fd << " vs " << g;
    });
  std::mt19937_64 rng(seed);
  const QpProblem qp0 = relaxed_step_qp(s, target, kDt, settings, center);
  QpSolver solver(settings.qp);
  solver.setup(qp0);
  const QpResult& res = solver.solve();
  ASSERT_TRUE(has_solution(res.info.status));
  const Vector x = res.x;
  const SparseMatrix Pfull = SparseMatrix(qp0.P.selfadjointView<Eigen::Upper>());
  const QpGradient qg = solver.backward(Pfull * x + qp0.q);
  auto inner = [](const SparseMatrix& G, const SparseMatrix& D) {
    double sum = 0.0;
    for (Index j = 0; j < G.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(G, j); it; ++it) sum += it.value() * D.coeff(it.row(), j);
    return sum;
  };
  for (int trial = 0; trial < 4; ++trial) {
    const std::vector<double> dir = random_direction(s, r.grad, rng);
    double dot = 0.0;
    std::size_t i = 0;
    for_each_entry(s, r.grad, [&](double&, double g, const std::string&) { dot += g * dir[i++]; });
    const double fd = (loss(moved(s, r.grad, dir, h)) - loss(moved(s, r.grad, dir, -h))) / (2 * h);
    EXPECT_LE(std::abs(fd - dot), 1e-5 * std::max(std::abs(fd), std::abs(dot)) + floor)
        << "direction " << trial << ": fd " << fd << " vs " << dot;
    // Adjoint: dℓ = ½xᵀdPx + dqᵀx + dr + ⟨∂ℓ/∂(P, q, A, G, l), d(P, q, A, G, l)⟩ with the
    // QP's data derivative by central differences of the (smooth) assembly.
    const double ha = 1e-6;
    const QpProblem qpp = relaxed_step_qp(moved(s, r.grad, dir, ha), target, kDt, settings, center);
    const QpProblem qpm = relaxed_step_qp(moved(s, r.grad, dir, -ha), target, kDt, settings, center);
    const SparseMatrix dP = (qpp.P - qpm.P) / (2 * ha), dA = (qpp.A - qpm.A) / (2 * ha);
    const SparseMatrix dG = (qpp.G - qpm.G) / (2 * ha);
    const Vector dq = (qpp.q - qpm.q) / (2 * ha), dl = (qpp.l - qpm.l) / (2 * ha);
    const double dr = (qpp.r - qpm.r) / (2 * ha);
    const SparseMatrix dPfull = SparseMatrix(dP.selfadjointView<Eigen::Upper>());
    const double adj = 0.5 * x.dot(dPfull * x) + dq.dot(x) + dr + inner(qg.dP, dP) + qg.dq.dot(dq) +
                       inner(qg.dA, dA) + inner(qg.dG, dG) + qg.dl.dot(dl);
    EXPECT_LE(std::abs(adj - dot), adjoint_tol * std::max(std::abs(adj), std::abs(dot)) + floor)
        << "adjoint, direction " << trial << ": " << adj << " vs envelope " << dot
        << " (adjoint residual " << qg.adjoint_residual << ")";
  }
  ::testing::Test::RecordProperty("worst_relative_error", std::to_string(worst));
  std::cout << "worst relative error " << worst << " (" << s.num_contacts() << " contacts)\n";
}

TEST(StepLossRelaxed, BoxOnGround) {
  ContactSystem s = box_stack(1, 0.5);
  ASSERT_EQ(s.num_contacts(), 2);
  s.v_star << 0.8, -0.3, 0.4;
  s.phi << 0.002, 0.001;
  check_gradient(s, noisy_target(s, 1, 0.1), 11);
  check_gradient(s, noisy_target(s, 1, 0.1), 11, 1, tight());  // the polygon's ε = 1e-6
  s.v_star << 0.05, -0.1, 0.0;  // nearly resting
  check_gradient(s, noisy_target(s, 2, 0.1), 12);
}

TEST(StepLossRelaxed, TwoStackedBoxes) {
  ContactSystem s = box_stack(2, 0.3);
  ASSERT_EQ(s.bodies.size(), 2u);
  s.v_star << 0.2, -0.2, 0.1, 1.0, -0.4, -0.3;
  for (Index c = 0; c < s.num_contacts(); ++c) s.phi(c) = 1e-3 * (c + 1);
  check_gradient(s, noisy_target(s, 3, 0.1), 13);
}

TEST(StepLossRelaxed, PileIsland) {
  ContactSystem s = pile_island();
  ASSERT_GE(s.num_contacts(), 50);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Kicked, as in the hard test: random free velocities move the solution off the resting
  // one, where many constraints are weakly active (kinks of the relaxed loss).
  for (Index k = 0; k < s.v_star.size(); ++k) s.v_star(k) += 0.2 * u(rng);
  // Gaps away from the kink of max(φ, 0) at 0 (a settled pile has φ ≈ 0).
  for (Index c = 0; c < s.num_contacts(); ++c) s.phi(c) = 1e-4 * (1.5 + u(rng));
  check_gradient(s, noisy_target(s, 4, 0.05), 14, 3);  // every third entry, all kinds
}

// A proximal centre: the gradient of ℓ_c(data) with c held fixed, on the box and the pile
// island, centred where training puts it: at an earlier proximal iterate (two iterations
// from the centre 0, so that the shift term is still active).
TEST(StepLossRelaxed, CentredShiftGradient) {
  std::mt19937_64 rng(21);
  auto centre_near_solution = [&](const ContactSystem& s, const Vector& target) {
    RelaxedStepLossSettings st = fd_settings();
    st.centred_shift_in_gradient = true;
    st.proximal_iterations = 2;
    st.proximal_tolerance = 0.0;
    RelaxedStepLossWorkspace ws(st);
    EXPECT_EQ(ws.evaluate(s, target, kDt).status, ContactStatus::solved);
    return ws.proximal_point();
  };
  ContactSystem box = box_stack(1, 0.5);
  box.v_star << 0.8, -0.3, 0.4;
  box.phi << 0.002, 0.001;
  const Vector tb = noisy_target(box, 1, 0.1);
  const Vector cb = centre_near_solution(box, tb);
  // The QP adjoint (the cross-check by QpSolver::backward) agrees to 1.8e-5 here, the central
  // differences of ℓ itself to 4e-7: at this iterate a bound is weakly active.
  RelaxedStepLossSettings exact = fd_settings();
  exact.centred_shift_in_gradient = true;  // the exact ∂ℓ_c
  check_gradient(box, tb, 31, 1, exact, &cb, 1e-6, 3e-5);
  ContactSystem pile = pile_island();
  std::uniform_real_distribution<double> w(-1.0, 1.0);
  for (Index k = 0; k < pile.v_star.size(); ++k) pile.v_star(k) += 0.2 * w(rng);
  for (Index c = 0; c < pile.num_contacts(); ++c) pile.phi(c) = 1e-4 * (1.5 + w(rng));
  const Vector tp = noisy_target(pile, 4, 0.05);
  const Vector cp = centre_near_solution(pile, tp);
  // h = 1e-7: the centred pile QP has constraints within 1e-6 of switching (kinks).
  check_gradient(pile, tp, 32, 3, exact, &cp, 1e-7);
}

// The shift's bias and its removal: on LCP data (the target is the Stewart–Trinkle LCP's
// own next velocity) the unshifted loss is ≈ 0 at the true data; the shift centred at 0
// makes it large, and proximal iterations bring it back to the ε level, decreasing
// monotonically (each centred loss is ≤ the unshifted objective at the previous solution).
TEST(StepLossRelaxed, ProximalIterationsRemoveTheShiftBias) {
  const ContactSystem s = pile_island();
  const ContactSolution sol = solve_lcp_model(s, kDt, LemkeSettings{});
  ASSERT_TRUE(has_solution(sol.status));
  RelaxedStepLossSettings st = tight();
  RelaxedStepLossWorkspace ws(st);
  const StepLossResult cold = ws.evaluate(s, sol.v_next, kDt);
  ASSERT_EQ(cold.status, ContactStatus::solved) << cold.message;
  double previous = cold.loss;
  Vector c = ws.proximal_point();
  for (int k = 0; k < 60; ++k) {
    const StepLossResult r = ws.evaluate(s, sol.v_next, kDt, &c);
    ASSERT_TRUE(has_solution(r.status)) << r.message;
    EXPECT_LE(r.loss, previous * (1 + 1e-6) + 1e-12) << "iteration " << k;
    previous = r.loss;
    c = ws.proximal_point();
  }
  std::cout << "pile island (" << s.num_contacts() << " contacts): loss at the true data, shift at 0: " << cold.loss
            << ", after 60 proximal iterations: " << previous << "\n";
  EXPECT_GT(cold.loss, 1e-3);
  EXPECT_LT(previous, 1e-3 * cold.loss);
  // At the fixed point the default gradient (the unshifted Lagrangian's) is the exact one.
  RelaxedStepLossSettings exact = st;
  exact.centred_shift_in_gradient = true;
  RelaxedStepLossWorkspace we(exact), wd(st);
  const StepLossResult ge = we.evaluate(s, sol.v_next, kDt, &c), gd = wd.evaluate(s, sol.v_next, kDt, &c);
  EXPECT_LE((ge.grad.mu - gd.grad.mu).norm(), 1e-4 * (ge.grad.mu.norm() + 1e-6));
  EXPECT_LE((ge.grad.minv - gd.grad.minv).norm(), 1e-4 * (ge.grad.minv.norm() + 1e-6));
  // The same in one call: proximal_iterations = 60 ends where the loop ended.
  st.proximal_iterations = 61;
  st.proximal_tolerance = 0.0;
  RelaxedStepLossWorkspace ws2(st);
  const StepLossResult r = ws2.evaluate(s, sol.v_next, kDt);
  EXPECT_NEAR(r.loss, previous, 1e-6 * (1 + previous));
  EXPECT_EQ(ws2.proximal_solves(), 61);
  EXPECT_THROW(ws2.evaluate(s, sol.v_next, kDt, &cold.v_next), InputError);  // wrong size
}

// normalize_by_mass: a2/σ with σ the island's mean mass. The gradient (with the chain
// through σ) against central differences, and the invariance it buys: scaling every mass
// and inertia by 3 leaves ℓ unchanged, while the plain loss grows with the masses.
TEST(StepLossRelaxed, MassNormalizedGradientAndScaleInvariance) {
  RelaxedStepLossSettings st = fd_settings();
  st.normalize_by_mass = true;
  ContactSystem box = box_stack(1, 0.5);
  box.v_star << 0.8, -0.3, 0.4;
  box.phi << 0.002, 0.001;
  check_gradient(box, noisy_target(box, 1, 0.1), 41, 1, st);
  ContactSystem two = box_stack(2, 0.3);
  two.minv.tail(3) *= 0.4;  // unequal masses, so that σ is not the bodies' own mass
  two.v_star << 0.2, -0.2, 0.1, 1.0, -0.4, -0.3;
  for (Index c = 0; c < two.num_contacts(); ++c) two.phi(c) = 1e-3 * (c + 1);
  const Vector target = noisy_target(two, 3, 0.1);
  check_gradient(two, target, 42, 1, st);
  ContactSystem pile = pile_island();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Index k = 0; k < pile.v_star.size(); ++k) pile.v_star(k) += 0.2 * u(rng);
  for (Index c = 0; c < pile.num_contacts(); ++c) pile.phi(c) = 1e-4 * (1.5 + u(rng));
  check_gradient(pile, noisy_target(pile, 4, 0.05), 43, 3, st);

  ContactSystem heavy = two;
  heavy.minv /= 3.0;
  RelaxedStepLossSettings plain = fd_settings();
  const double ln = relaxed_step_loss(two, target, kDt, st).loss, lh = relaxed_step_loss(heavy, target, kDt, st).loss;
  EXPECT_NEAR(lh, ln, 1e-7 * ln);
  const double pn = relaxed_step_loss(two, target, kDt, plain).loss, ph = relaxed_step_loss(heavy, target, kDt, plain).loss;
  EXPECT_GT(ph, 1.1 * pn) << "the plain loss was expected to grow with the masses";
}

TEST(StepLossRelaxed, WorkspaceUpdateMatchesFreshSetup) {
  ContactSystem s = box_stack(2, 0.3);
  const Vector target = noisy_target(s, 5, 0.1);
  RelaxedStepLossWorkspace ws(tight());
  ws.evaluate(s, target, kDt);
  s.v_star(0) += 0.1;
  s.mu(0) = 0.4;
  const StepLossResult a = ws.evaluate(s, target, kDt);
  EXPECT_EQ(ws.setups(), 1);
  EXPECT_EQ(ws.updates(), 1);
  const StepLossResult b = relaxed_step_loss(s, target, kDt, tight());
  ASSERT_EQ(a.status, ContactStatus::solved);
  EXPECT_NEAR(a.loss, b.loss, 1e-9 * (1 + b.loss));
  EXPECT_LE((a.grad.v_star - b.grad.v_star).norm(), 1e-6 * (1 + b.grad.v_star.norm()));
  ASSERT_EQ(ws.shifts().size(), s.num_friction());
  const double S = 1.0 / s.minv(0);  // contact 0 is the bottom box's, on the ground
  EXPECT_NEAR(ws.shifts()(0), 0.1 * 0.4 * S, 1e-12 * S);
}

TEST(StepLossRelaxed, FailedSolveIsReported) {
  ContactSystem s = box_stack(2, 0.3);
  RelaxedStepLossSettings st;
  st.qp.max_iter = 1;
  st.qp.polish = false;  // polishing can finish a 1-iteration run (QpSettings::polish)
  const StepLossResult r = relaxed_step_loss(s, noisy_target(s, 7, 0.1), kDt, st);
  EXPECT_EQ(r.status, ContactStatus::failed);
  EXPECT_TRUE(std::isnan(r.loss));
  EXPECT_FALSE(r.message.empty());
}

TEST(StepLossRelaxed, SettingsAndInputAreValidated) {
  RelaxedStepLossSettings st;
  EXPECT_TRUE(st.validation_error().empty());
  st.a1 = 0.0;
  EXPECT_NE(st.validation_error().find("a1"), std::string::npos);
  EXPECT_THROW(RelaxedStepLossWorkspace{st}, InputError);
  ContactSystem s = box_stack(1, 0.3);
  EXPECT_THROW(relaxed_step_loss(s, Vector::Zero(4), kDt), InputError);
  s.minv(2) = -1.0;
  EXPECT_THROW(relaxed_step_loss(s, Vector::Zero(3), kDt), InputError);
  RelaxedStepLossSettings bad;
  bad.proximal_iterations = 0;
  EXPECT_THROW(RelaxedStepLossWorkspace{bad}, InputError);
}

}  // namespace
}  // namespace lcprelax::learn
