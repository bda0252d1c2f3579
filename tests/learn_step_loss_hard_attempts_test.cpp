// The hard loss (learn/step_loss_hard.hpp) solves with the lcp model's attempts
// (models/lcp_model_attempts.hpp), the simulator's: the same answer as solve_lcp_model, also
// where only the regularized attempt M + εI (step 4 of contact_step.hpp) gives one, with
// a gradient that matches central differences of that regularized LCP's loss.
//
// Scene (tests/lcp_wedge_support.hpp): a 0.1 m box (10 kg) wedged 0.1 mm into
// two walls, with a per-contact q bias b = −1e-6 m/s on the normal rows (world.hpp
// ContactLcpBlock): the LCP has no solution, every path on M ends on a ray, and the
// solution on M + εI is kept as solved_inaccurate (StepLossResult::regularized).
#include <lcprelax/learn/step_loss_hard.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>

#include "lcp_wedge_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

constexpr double kDt = 1e-2;

ContactSystem wedged_box(double bias, double mu = 0.5) {
  return test::wedged_box_system(bias, mu, kDt);
}

Vector target_of(const ContactSystem& s) {
  Vector t = s.v_star;
  t(0) += 0.01, t(1) += 0.02, t(2) -= 0.03;
  return t;
}

TEST(HardLossAttempts, RegularizedStepMatchesTheSimulatorsModel) {
  const ContactSystem s = wedged_box(-1e-6);
  const ContactSolution model = solve_lcp_model(s, kDt, LemkeSettings{}, {});
  ASSERT_EQ(model.status, ContactStatus::solved_inaccurate) << model.message;
  std::vector<bool> basis;
  const learn::StepLossResult r = learn::hard_step_loss(s, target_of(s), kDt, {}, {}, &basis);
  EXPECT_EQ(r.status, ContactStatus::solved_inaccurate) << r.message;
  EXPECT_NE(r.message.find("M + εI"), std::string::npos) << r.message;
  EXPECT_TRUE(std::isfinite(r.loss));
  EXPECT_EQ(r.v_next, model.v_next);  // the same attempts, the same arithmetic
  EXPECT_EQ(r.work, model.work);
  EXPECT_EQ(basis, model.z_basic);
}

// From the regularized answer's basis, marked as such (warm_from_regularized: the
// simulator's ContactWarmRecord::regularized), the hard loss takes the simulator's path
// (step 1c first): the same answer and pivots as solve_lcp_model given the same flag, fewer
// pivots than the cold attempts, still regularized.
TEST(HardLossAttempts, ARegularizedWarmBasisTakesTheSimulatorsPath) {
  const ContactSystem s = wedged_box(-1e-6);
  std::vector<bool> basis;
  const learn::StepLossResult cold = learn::hard_step_loss(s, target_of(s), kDt, {}, {}, &basis);
  ASSERT_TRUE(cold.regularized) << cold.message;
  const ContactSolution model = solve_lcp_model(s, kDt, LemkeSettings{}, basis, nullptr, false, true);
  ASSERT_EQ(model.status, ContactStatus::solved_inaccurate) << model.message;
  std::vector<bool> final_basis;
  const learn::StepLossResult r =
      learn::hard_step_loss(s, target_of(s), kDt, {}, basis, &final_basis, false, /*warm_from_regularized=*/true);
  EXPECT_TRUE(r.regularized) << r.message;
  EXPECT_EQ(r.v_next, model.v_next);
  EXPECT_EQ(r.work, model.work);
  EXPECT_EQ(final_basis, model.z_basic);
  EXPECT_LT(r.work, cold.work);
  const learn::StepLossResult unmarked = learn::hard_step_loss(s, target_of(s), kDt, {}, basis);
  EXPECT_GT(unmarked.work, r.work) << "without the mark: step 1b and the cold attempts first";
}

// ∂ℓ/∂b (the q bias of the normal rows) and ∂ℓ/∂v* against central differences. Neither
// changes M, so ε = kLcpRegularization·max(1, ‖M‖∞) is the same in every evaluation, and
// the regularized solution (z ≈ |b|/ε) is smooth in both where its basis holds. With
// μ = 1e-3 the squeeze's friction (μ·|b|/ε) slows the box's fall without holding it, so
// the loss depends on b (with μ = 0.5 the box sticks and ℓ does not change with b).
TEST(HardLossAttempts, RegularizedGradientMatchesCentralDifferences) {
  const double b = -1e-6, mu = 1e-3;
  const ContactSystem s = wedged_box(b, mu);
  const Vector target = target_of(s);
  const learn::StepLossResult r = learn::hard_step_loss(s, target, kDt);
  ASSERT_EQ(r.status, ContactStatus::solved_inaccurate) << r.message;
  auto loss_at = [&](const ContactSystem& x) {
    const learn::StepLossResult e = learn::hard_step_loss(x, target, kDt);
    EXPECT_EQ(e.status, ContactStatus::solved_inaccurate) << e.message;
    return e.loss;
  };
  const double hb = 1e-9;  // m/s, 0.1% of b
  const double fd_b = (loss_at(wedged_box(b + hb, mu)) - loss_at(wedged_box(b - hb, mu))) / (2.0 * hb);
  ASSERT_GT(std::abs(fd_b), 1.0) << "the sliding box's loss depends on b";
  EXPECT_NEAR(r.grad.lcp_block_q(0), fd_b, 1e-4 * std::abs(fd_b)) << "fd " << fd_b;
  // The regularized solve amplifies roundoff by about ‖M‖/ε = 1e8 (z ≈ 36 N·s), so the loss
  // carries noise of order 1e-11 and a step below 1e-6 measures noise (at 1e-10 the v*_y
  // difference was 5% off). Measured: ∂ℓ/∂b 163.0022 against 163.0023, ∂ℓ/∂v*_y −0.0113979
  // against −0.0113980; the x and θ components are zero to 2e-8.
  const double hv = 1e-6;  // m/s and rad/s
  for (Index k = 0; k < s.v_star.size(); ++k) {
    ContactSystem plus = s, minus = s;
    plus.v_star(k) += hv;
    minus.v_star(k) -= hv;
    const double fd = (loss_at(plus) - loss_at(minus)) / (2.0 * hv);
    EXPECT_NEAR(r.grad.v_star(k), fd, 1e-4 * std::abs(fd) + 1e-6) << "v* component " << k;
  }
}

}  // namespace
}  // namespace lcprelax
