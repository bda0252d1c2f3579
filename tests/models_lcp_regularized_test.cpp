// The lcp model's regularized attempt (contact_step.hpp, step 4): where Lemke's paths on q
// and on q + δu end without a solution, M + εI (strictly copositive, so its LCP always has
// one) gives the step a solution, kept as solved_inaccurate only if its residual on the
// LCP is within kLcpRegularizedResidual·‖q‖∞.
//
// Scene: a 0.1 m box (10 kg) wedged between two walls, 0.1 mm into each, in the air. Its
// four wall contacts can push against each other with forces that cancel (Jnᵀλ = 0), so
// the LCP is feasible only because those contacts' normal velocities q_n sum to zero
// (Jn v* cancels, and φ < 0 gives no gap term). A per-contact q bias b < 0 on the normal
// rows (world.hpp ContactLcpBlock, as a learned correction can be) breaks that: the
// cancelling forces then do negative work against q, and the LCP has no solution. The
// solution on M + εI squeezes the box with forces of about |b|/ε; its residual on the LCP
// is about |b|.
// - b = −1e-6 m/s: larger than every perturbation of step 2 (δ ≤ 1e-5·‖q‖∞ ≈ 1e-6), so
//   every path on M ends on a ray, and within the acceptance bound (1e-4·‖q‖∞ ≈ 1e-5):
//   solved_inaccurate from M + εI;
// - b = −1e-3 m/s: beyond the bound, failed;
// - b = 0: Lemke solves the LCP itself (status solved).
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>

#include "lcp_wedge_support.hpp"

#include <gtest/gtest.h>

#include <string>

namespace lcprelax {
namespace {

constexpr double kDt = 1e-2;

ContactSystem wedged_box(double bias) {
  return test::wedged_box_system(bias, 0.5, kDt);
}

double q_norm(const ContactSystem& s) {
  return stewart_trinkle_lcp(s, delassus(s), kDt).q.lpNorm<Eigen::Infinity>();
}

TEST(LcpRegularized, UnbiasedWedgeIsSolvedExactly) {
  const ContactSystem s = wedged_box(0.0);
  ASSERT_EQ(s.num_contacts(), 4);
  const ContactSolution r = solve_lcp_model(s, kDt, LemkeSettings{}, {});
  EXPECT_EQ(r.status, ContactStatus::solved) << r.message;
  EXPECT_LE(r.residual, 1e-9 * q_norm(s));
}

TEST(LcpRegularized, SmallInfeasibleBiasGivesTheRegularizedSolution) {
  const ContactSystem s = wedged_box(-1e-6);
  const double qn = q_norm(s);
  ASSERT_LT(1e-5 * qn, 1e-6) << "a perturbation of step 2 would cover the bias";
  const ContactSolution r = solve_lcp_model(s, kDt, LemkeSettings{}, {});
  EXPECT_EQ(r.status, ContactStatus::solved_inaccurate) << r.message;
  EXPECT_NE(r.message.find("M + εI"), std::string::npos) << r.message;
  EXPECT_LE(r.residual, kLcpRegularizedResidual * qn);
  EXPECT_GE(r.residual, 1e-7) << "the LCP has no solution: the residual cannot vanish";
  ASSERT_TRUE(r.v_next.allFinite());
  // The squeeze holds the box against gravity (friction up to μ·|b|/ε).
  EXPECT_NEAR(r.v_next(1), 0.0, 1e-6);
  EXPECT_GT(r.lambda_n.minCoeff(), 1.0);  // N·s, far above the box's weight impulse 0.98
}

TEST(LcpRegularized, LargeInfeasibleBiasFails) {
  const ContactSystem s = wedged_box(-1e-3);
  const ContactSolution r = solve_lcp_model(s, kDt, LemkeSettings{}, {});
  EXPECT_EQ(r.status, ContactStatus::failed) << r.message;
}

}  // namespace
}  // namespace lcprelax
