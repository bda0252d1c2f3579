// Gradients of the three polygon losses (polygon_losses.hpp) against central differences.
// Expected behaviour: at a sample whose quadrilateral touches a tilted ground with two
// contacts (one gap positive, one negative: away from the kink of max(φ, 0)) while sliding
// and spinning, with a target velocity that differs from the prediction, ∂ℓ/∂θ of each
// method matches the central difference (step 1e-6 on θ, active set held fixed, no warm
// starts) for every parameter (μ, mass, inertia, each vertex coordinate, ground height and
// angle) to a relative error of 1e-5 (hard: exact Lemke), 1e-4 (relaxed, convex: the
// interior point's tolerance enters), measured against max(|g|∞, 1e-3·|ℓ|).
// The hard loss has a zero μ-gradient where the contacts stick (a known limitation,
// docs/formulations.md): |∂ℓ/∂μ| ≤ 1e-12 (roundoff), while the relaxed loss's is not zero there.
#include <lcprelax/learn/polygon_losses.hpp>
#include <lcprelax/learn/polygon_lcp.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include "learn_polygon_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace lcprelax::learn {
namespace {

using test::quad_model;

PolygonTransition sample_near_ground(const PolygonModel& m, const Vec3& v) {
  PolygonTransition s;
  const HalfPlane g = ground_half_plane(m.ground_height, m.ground_angle);
  const double theta = m.ground_angle + 0.004;
  s.q = Vec3(0.1, 0.0, theta);
  const Vec2 b = m.shape.vertices[1];
  const double c = std::cos(theta), sn = std::sin(theta);
  const Vec2 rb(c * b.x() - sn * b.y(), sn * b.x() + c * b.y());
  s.q.y() = (g.offset - 0.001 - g.normal.x() * (s.q.x() + rb.x())) / g.normal.y() - rb.y();
  s.v = v;
  s.u = Vec3(2.0, -3.0, 0.15);
  return s;
}

PolygonDataset dataset() {
  PolygonDataset d;
  d.dt = 0.01;
  d.margin = 0.01;
  return d;
}

// Relaxed weights a1 = a2 = `relaxed_weight` (see RelaxedMatchesCentralDifferences).
SampleResult loss(PolygonMethod method, const PolygonModel& m, const std::vector<int>& active,
                  const PolygonTransition& s, const Vec3& target, double relaxed_weight = 1.0) {
  PolygonLossSettings settings;
  settings.method = method;
  settings.relaxed.a1 = settings.relaxed.a2 = relaxed_weight;
  settings.relaxed.regularization = 1e-3;  // a well-conditioned QP: FD sees its exact optimum
  settings.warm_start = false;
  settings.qp.eps_abs = 1e-11;
  settings.qp.eps_rel = 1e-11;
  PolygonAssembly a;
  assemble_polygon(m, active, s, dataset(), a);
  PolygonWarmStart warm;
  PolygonLossTimes times;
  RelaxedLcpSolver relaxed(settings.relaxed, settings.qp);
  switch (method) {
    case PolygonMethod::hard: return polygon_hard_loss(a, target, 0.01, settings, warm, times);
    case PolygonMethod::relaxed: return polygon_relaxed_loss(a, target, 0.01, settings, relaxed, warm, times);
    case PolygonMethod::convex: return polygon_convex_loss(a, target, 0.01, settings, warm, times);
  }
  return {};
}

// The hard model's prediction at the model (for targets near it).
Vec3 prediction(const PolygonModel& m, const std::vector<int>& active, const PolygonTransition& s) {
  PolygonAssembly a;
  assemble_polygon(m, active, s, dataset(), a);
  PolygonLcp lcp;
  polygon_lcp(a.value, 0.01, lcp);
  LemkeSolver solver;
  solver.setup(full_pattern(lcp.M), lcp.q);
  const LcpResult& r = solver.solve();
  EXPECT_EQ(r.info.status, LcpStatus::solved);
  return lcp.P * r.z + lcp.p;
}

void check_gradient(PolygonMethod method, double tol, double relaxed_weight = 1.0) {
  const PolygonModel m = quad_model();
  const PolygonTransition s = sample_near_ground(m, Vec3(0.8, -0.7, 1.3));
  const std::vector<int> active = polygon_active_vertices(m, s, dataset());
  ASSERT_EQ(active.size(), 2u);
  const Vec3 target = prediction(m, active, s) + Vec3(0.05, -0.03, 0.2);
  const SampleResult r = loss(method, m, active, s, target, relaxed_weight);
  ASSERT_TRUE(r.ok) << r.message;
  const ParameterSet theta = make_polygon_parameters(m, PolygonLearnFlags{});
  const double h = 1e-6;
  Vector fd(theta.size());
  for (Index k = 0; k < theta.size(); ++k) {
    ParameterSet tp = theta, tm = theta;
    tp.set_value(theta[k].name, theta[k].value + h);
    tm.set_value(theta[k].name, theta[k].value - h);
    const SampleResult rp = loss(method, polygon_model(tp), active, s, target, relaxed_weight);
    const SampleResult rm = loss(method, polygon_model(tm), active, s, target, relaxed_weight);
    ASSERT_TRUE(rp.ok && rm.ok);
    fd(k) = (rp.loss - rm.loss) / (2 * h);
  }
  const double scale = std::max(fd.cwiseAbs().maxCoeff(), 1e-3 * std::abs(r.loss));
  const double err = (r.gradient - fd).cwiseAbs().maxCoeff() / scale;
  for (Index k = 0; k < theta.size(); ++k)
    EXPECT_LE(std::abs(r.gradient(k) - fd(k)), tol * scale) << to_string(method) << " " << theta[k].name
                                                            << " analytic " << r.gradient(k) << " fd " << fd(k);
  std::printf("%s: loss %.6e, max |g - fd| / max|fd| = %.3e\n", to_string(method), r.loss, err);
}

TEST(LearnPolygonLossGradient, HardMatchesCentralDifferences) { check_gradient(PolygonMethod::hard, 1e-5); }
TEST(LearnPolygonLossGradient, RelaxedMatchesCentralDifferences) {
  // The Stewart–Trinkle M is not monotone, so the relaxed QP is convexified by a diagonal
  // shift δ = 10ᵏ·max(ε, 1e-8) (relaxed_lcp.hpp, NonconvexPolicy::shift), independent of
  // the data, and its envelope gradient is that of the shifted problem at fixed δ: exact
  // wherever θ ± h keeps the same k. Checked with small weights a1 = a2 = 0.01 and with
  // unit weights (before δ was made data-independent it scaled with ‖H(θ)‖∞ and the
  // unit-weight case failed: the quotient contains ½‖λ‖²·dδ/dθ).
  check_gradient(PolygonMethod::relaxed, 1e-4, 0.01);
  check_gradient(PolygonMethod::relaxed, 1e-4, 1.0);
}
TEST(LearnPolygonLossGradient, ConvexMatchesCentralDifferences) { check_gradient(PolygonMethod::convex, 1e-4); }

TEST(LearnPolygonLossGradient, HardGradientInMuVanishesWhenSticking) {
  // A slow tangential velocity with a large μ: the contacts stick, so the hard loss does
  // not depend on μ locally, whatever the target says.
  PolygonModel m = quad_model();
  m.mu = 2.0;
  const PolygonTransition s = sample_near_ground(m, Vec3(0.05, -0.3, 0.0));
  const std::vector<int> active = polygon_active_vertices(m, s, dataset());
  const Vec3 target = prediction(m, active, s) + Vec3(0.3, 0.0, 0.0);  // the data slid on
  const SampleResult hard = loss(PolygonMethod::hard, m, active, s, target);
  const SampleResult relaxed = loss(PolygonMethod::relaxed, m, active, s, target);
  ASSERT_TRUE(hard.ok && relaxed.ok);
  EXPECT_NEAR(hard.gradient(PolygonLayout::kMu), 0.0, 1e-12);
  EXPECT_GT(std::abs(relaxed.gradient(PolygonLayout::kMu)), 1e-6);
}

}  // namespace
}  // namespace lcprelax::learn
