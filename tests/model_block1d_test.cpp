// The 1-D frictional block (models/block1d.hpp): Lemke on the Stewart–Trinkle LCP, the
// interior point on the convex model (ρ = 0) and the closed-form maximum-dissipation impulse
// agree to 1e-7 (impulses; velocities 1e-7/m) on 400 random steps (masses 0.1–10 kg, μ 0–3, sticking and slipping);
// sticking gives v⁺ = 0 and slipping |λ| = μmg with friction opposing the motion; with
// ρ > 0 the convex model's sticking impulse shrinks by 1/(1+ρ); bad input is an InputError.
#include <lcprelax/models/block1d.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace lcprelax {
namespace {

TEST(Block1d, LcpConvexAndClosedFormAgree) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int stick = 0, slip = 0;
  for (int i = 0; i < 400; ++i) {
    Block1d b;
    b.mass = std::pow(10.0, -1.0 + 2.0 * U(rng));
    b.mg = b.mass * (0.5 + U(rng));
    b.mu = i % 10 == 0 ? 0.0 : 3.0 * U(rng);
    const double v = 4.0 * U(rng) - 2.0, u = b.mass * (4.0 * U(rng) - 2.0);
    const double exact = block1d_exact_impulse(b, v, u);
    const Block1dStep lcp = block1d_step_lcp(b, v, u);
    const Block1dStep cvx = block1d_step_convex(b, v, u);
    ASSERT_TRUE(has_solution(lcp.status)) << lcp.message;
    ASSERT_TRUE(has_solution(cvx.status)) << cvx.message;
    EXPECT_NEAR(lcp.lambda, exact, 1e-7 * std::max(1.0, std::abs(exact))) << i;
    EXPECT_NEAR(cvx.lambda, exact, 1e-7 * std::max(1.0, std::abs(exact))) << i;
    EXPECT_NEAR(lcp.v_next, cvx.v_next, 1e-7 / b.mass) << i;  // λ to 1e-7, v⁺ = v* + λ/m
    const double vstar = v + u / b.mass;
    if (std::abs(vstar) < b.mu * b.mg / b.mass) {
      ++stick;
      EXPECT_NEAR(lcp.v_next, 0.0, 1e-9);
    } else {
      ++slip;
      EXPECT_NEAR(std::abs(lcp.lambda), b.mu * b.mg, 1e-9 * std::max(1.0, b.mu * b.mg));
      EXPECT_LE(lcp.lambda * vstar, 0.0);  // friction opposes the motion
      EXPECT_NEAR(lcp.z(2), std::abs(lcp.v_next), 1e-9);  // γ is the sliding speed
    }
  }
  EXPECT_GT(stick, 50);
  EXPECT_GT(slip, 50);
}

TEST(Block1d, ConvexPenaltySoftensSticking) {
  const Block1d b{2.0, 2.0, 1.0};
  const Block1dStep s = block1d_step_convex(b, 0.1, 0.2, 0.5);  // v* = 0.2, sticks
  ASSERT_TRUE(has_solution(s.status));
  EXPECT_NEAR(s.lambda, -2.0 * 0.2 / 1.5, 1e-8);
  EXPECT_GT(s.v_next, 0.0);  // creeps
}

TEST(Block1d, BadInputIsAnInputError) {
  EXPECT_THROW(block1d_lcp(Block1d{0.0, 1.0, 0.5}, 0, 0), InputError);
  EXPECT_THROW(block1d_lcp(Block1d{1.0, -1.0, 0.5}, 0, 0), InputError);
  EXPECT_THROW(block1d_lcp(Block1d{1.0, 1.0, std::nan("")}, 0, 0), InputError);
  EXPECT_THROW(block1d_step_convex(Block1d{}, std::nan(""), 0), InputError);
  EXPECT_THROW(block1d_convex_qp(Block1d{}, 0, 0, -1.0), InputError);
}

}  // namespace
}  // namespace lcprelax
