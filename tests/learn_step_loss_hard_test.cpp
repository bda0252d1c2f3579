// The sparse hard loss of one island (learn/step_loss_hard.hpp): central finite differences
// of ℓ against every entry of the cotangent (each Jn/Jt entry on the pattern, φ, μ, M⁻¹, v*)
// and along random directions, on a box on the ground, two stacked boxes and an island of a
// settled 20-body pile; zero ∂ℓ/∂μ when μ is far too large and everything sticks; statuses.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/step_loss_hard.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene.hpp>

#include <gtest/gtest.h>

#include "contact_island_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

namespace lcprelax::learn {
namespace {

using testing::box_stack;
using testing::for_each_entry;
using testing::largest_island;

constexpr double kDt = 1e-2;



// A settled pile of 20 bodies (cached: built once per test binary).
const ContactSystem& pile_island() {
  static const ContactSystem s = testing::settled_pile_island(20, 3, 400);
  return s;
}


double loss(const ContactSystem& s, const Vector& target) {
  const StepLossResult r = hard_step_loss(s, target, kDt);
  EXPECT_TRUE(has_solution(r.status)) << r.message;
  return r.loss;
}

// Central differences for every entry (relative step) and along random directions.
void check_gradient(ContactSystem s, const Vector& target, std::uint64_t seed, int stride = 1) {
  const StepLossResult r = hard_step_loss(s, target, kDt);
  ASSERT_EQ(r.status, ContactStatus::solved) << r.message;
  ASSERT_GT(r.loss, 0.0);
  double gmax = 0.0;
  for_each_entry(s, r.grad, [&](double&, double g, const std::string&) { gmax = std::max(gmax, std::abs(g)); });
  const double floor = 1e-7 * gmax;
  int checked = 0;
  int index = 0;
  for_each_entry(s, r.grad, [&](double& x, double g, const std::string& kind) {
      if (index++ % stride != 0) return;
      const double x0 = x, h = 1e-6 * std::max(1.0, std::abs(x0));
      x = x0 + h;
      const double lp = loss(s, target);
      x = x0 - h;
      const double lm = loss(s, target);
      x = x0;
      const double fd = (lp - lm) / (2 * h);
      EXPECT_LE(std::abs(fd - g), 1e-5 * std::max(std::abs(fd), std::abs(g)) + floor)
          << kind << " value " << x0 << ": fd " << fd << " vs " << g;
      ++checked;
    });
  // Random directions (all entries at once, scaled by each entry's magnitude).
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<double> dir;
    double dot = 0.0;
    for_each_entry(s, r.grad, [&](double& x, double g, const std::string&) {
      dir.push_back(u(rng) * std::max(0.1, std::abs(x)));
      dot += g * dir.back();
    });
    auto shifted = [&](double h) {
      ContactSystem p = s;
      std::size_t i = 0;
      for_each_entry(p, r.grad, [&](double& x, double, const std::string&) { x += h * dir[i++]; });
      return loss(p, target);
    };
    const double h = 1e-6;
    const double fd = (shifted(h) - shifted(-h)) / (2 * h);
    EXPECT_LE(std::abs(fd - dot), 1e-5 * std::max(std::abs(fd), std::abs(dot)) + floor)
        << "direction " << trial << ": fd " << fd << " vs " << dot;
  }
  ::testing::Test::RecordProperty("entries_checked", checked);
}

// A target that is not the solution: the LCP's v⁺ plus noise.
Vector noisy_target(const ContactSystem& s, std::uint64_t seed, double size) {
  const ContactSolution sol = solve_lcp_model(s, kDt, LemkeSettings{});
  EXPECT_TRUE(has_solution(sol.status));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector t = sol.v_next;
  for (Index k = 0; k < t.size(); ++k) t(k) += size * u(rng);
  return t;
}

TEST(StepLossHard, BoxSlidingOnGround) {
  ContactSystem s = box_stack(1, 0.5);
  ASSERT_EQ(s.num_contacts(), 2);
  ASSERT_EQ(s.num_friction(), 2);
  s.v_star << 0.8, -0.3, 0.4;  // sliding, pressing, turning: one corner lifts off
  s.phi << 0.002, 0.001;
  check_gradient(s, noisy_target(s, 1, 0.1), 11);
  s.v_star << 0.8, -0.3, 0.0;  // sliding on both corners
  check_gradient(s, noisy_target(s, 2, 0.1), 12);
}

TEST(StepLossHard, TwoStackedBoxes) {
  ContactSystem s = box_stack(2, 0.3);
  ASSERT_EQ(s.bodies.size(), 2u);
  ASSERT_GE(s.num_contacts(), 4);
  s.v_star << 0.2, -0.2, 0.1, 1.0, -0.4, -0.3;  // the top box slides on the bottom one
  for (Index c = 0; c < s.num_contacts(); ++c) s.phi(c) = 1e-3 * (c + 1);
  check_gradient(s, noisy_target(s, 3, 0.1), 13);
}

TEST(StepLossHard, PileIsland) {
  ContactSystem s = pile_island();
  ASSERT_GE(s.num_contacts(), 50);
  // Kicked: random free velocities move the solution off the degenerate resting one.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Index k = 0; k < s.v_star.size(); ++k) s.v_star(k) += 0.2 * u(rng);
  // Gaps away from the kink of max(φ, 0) at 0 (a settled pile has φ ≈ 0).
  for (Index c = 0; c < s.num_contacts(); ++c) s.phi(c) = 1e-4 * (1.5 + u(rng));
  check_gradient(s, noisy_target(s, 4, 0.05), 14, 3);  // every third entry, all kinds
}

TEST(StepLossHard, StickingWithLargeMuHasZeroMuGradient) {
  ContactSystem s = box_stack(1, 5.0);
  s.v_star << 0.05, -0.1, 0.0;
  const Vector target = Vector::Constant(3, 0.1);
  const StepLossResult r = hard_step_loss(s, target, kDt);
  ASSERT_EQ(r.status, ContactStatus::solved);
  EXPECT_NEAR(r.v_next.norm(), 0.0, 1e-12);  // sticks
  EXPECT_GT(r.loss, 0.0);
  // Zero to roundoff (∂ℓ/∂μ has the loss's units): the lcp model's attempts reach the
  // sticking basis from a perturbed solution's basis (the polish), whose solves leave
  // entries of order 1e-18 where plain Lemke's path on q left exact zeros. With
  // v⁺ = 0 pinned by both contacts the v* gradient vanishes as well (to 1e-29 here).
  for (Index f = 0; f < r.grad.mu.size(); ++f) EXPECT_LE(std::abs(r.grad.mu(f)), 1e-12 * r.loss);
}

TEST(StepLossHard, WarmBasisGivesTheSameResult) {
  ContactSystem s = box_stack(2, 0.3);
  const Vector target = noisy_target(s, 6, 0.1);
  std::vector<bool> basis;
  const StepLossResult cold = hard_step_loss(s, target, kDt, {}, {}, &basis);
  ASSERT_EQ(cold.status, ContactStatus::solved);
  const StepLossResult warm = hard_step_loss(s, target, kDt, {}, basis);
  ASSERT_EQ(warm.status, ContactStatus::solved);
  EXPECT_EQ(warm.work, 0);
  EXPECT_NEAR(warm.loss, cold.loss, 1e-12 * (1 + cold.loss));
  EXPECT_LE((warm.grad.v_star - cold.grad.v_star).norm(), 1e-9 * (1 + cold.grad.v_star.norm()));
}

TEST(StepLossHard, FailedSolveIsReported) {
  ContactSystem s = box_stack(2, 0.3);
  HardStepLossSettings st;
  st.lemke.max_pivots = 1;  // every attempt stops at the pivot limit
  const StepLossResult r = hard_step_loss(s, noisy_target(s, 7, 0.1), kDt, st);
  EXPECT_EQ(r.status, ContactStatus::failed);
  EXPECT_FALSE(has_solution(r.status));
  EXPECT_TRUE(std::isnan(r.loss));
  EXPECT_FALSE(r.message.empty());
}

TEST(StepLossHard, BadInputThrows) {
  ContactSystem s = box_stack(1, 0.3);
  EXPECT_THROW(hard_step_loss(s, Vector::Zero(2), kDt), InputError);
  EXPECT_THROW(hard_step_loss(s, Vector::Zero(3), 0.0), InputError);
  s.phi(0) = std::nan("");
  EXPECT_THROW(hard_step_loss(s, Vector::Zero(3), kDt), InputError);
  HardStepLossSettings st;
  st.lemke.max_pivots = -1;
  EXPECT_FALSE(st.validation_error().empty());
}

}  // namespace
}  // namespace lcprelax::learn
