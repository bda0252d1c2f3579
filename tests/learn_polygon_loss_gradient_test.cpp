// Gradients of the three polygon losses (polygon_objective.hpp: the scene path's step losses
// on the one-body scene of polygon_scene.hpp) against central differences of the same
// objective. Expected behaviour: at a sample whose quadrilateral touches a tilted, raised
// ground with two contacts (one gap positive, one negative: away from the kink of
// max(φ, 0)) while sliding and spinning, with a target velocity that differs from the
// prediction, ∂ℓ/∂θ of each method matches the central difference (step 1e-6 on θ, the
// contacts re-detected at θ ± h by the narrow phase: the same two vertices, no proximal
// centres) for every parameter of the polygon's layout (μ, mass, inertia, each vertex
// coordinate, ground height and angle: the latter two through the half-plane's (ψ, offset)
// of the scene map, polygon_gradient_from_scene) to a relative error of 1e-5 (hard: exact
// Lemke), 1e-4 (relaxed, convex: the interior point's tolerance enters), measured against
// max(|g|∞, 1e-3·|ℓ|). The convex loss's residuals r = v⁺ − v̄ and their Jacobian (for
// Levenberg–Marquardt) give ‖r‖² = ℓ and 2Jᵀr = ∂ℓ/∂θ.
// The hard loss has a zero μ-gradient where the contacts stick (a known limitation,
// docs/formulations.md): |∂ℓ/∂μ| ≤ 1e-12 (roundoff), while the relaxed loss's is not zero there.
#include <lcprelax/learn/polygon_objective.hpp>
#include <lcprelax/models/simulator.hpp>

#include "learn_polygon_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace lcprelax::learn {
namespace {

using test::quad_model;

constexpr double kDt = 0.01;

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

// The simulator's (LCP model) next velocity from the sample's state: the hard model's prediction.
Vec3 prediction(const PolygonModel& m, const PolygonTransition& s) {
  Scene scene = polygon_scene(m, kDt, Vec2(0.0, -9.81), 0.01);
  scene.settings.model = ContactModel::lcp;
  scene.world.bodies[0].pose = s.q;
  scene.world.bodies[0].velocity = s.v;
  SimulatorSettings ss;
  ss.threads = 1;
  Simulator sim = make_simulator(scene, ss);
  const StepStats stats = sim.step({s.u});
  EXPECT_EQ(stats.failed_islands, 0);
  return sim.world().bodies[0].velocity;
}

// A dataset of the one sample, its target v̄ = v_next.
PolygonDataset one_sample(const PolygonTransition& s) {
  PolygonDataset d;
  d.dt = kDt;
  d.margin = 0.01;
  d.transitions = {s};
  return d;
}

// Relaxed weights a1 = a2 = `relaxed_weight`.
PolygonLossSettings settings(PolygonMethod method, double relaxed_weight) {
  PolygonLossSettings ls;
  ls.method = method;
  ls.candidate_margin = 0.0;  // the simulator's contacts: the two bottom vertices
  ls.relaxed.a1 = ls.relaxed.a2 = relaxed_weight;
  ls.relaxed.regularization = 1e-3;  // a well-conditioned QP: FD sees its exact optimum
  ls.relaxed_warm_center = false;    // every evaluation centred at 0: a function of θ alone
  ls.relaxed.qp.eps_abs = ls.convex.qp.eps_abs = 1e-11;
  ls.relaxed.qp.eps_rel = ls.convex.qp.eps_rel = 1e-11;
  return ls;
}

SampleResult loss(PolygonObjective& objective, const ParameterSet& theta) {
  objective.prepare(theta, 1);
  return objective.evaluate(0, theta, 0);
}

void check_gradient(PolygonMethod method, double tol, double relaxed_weight = 1.0) {
  const PolygonModel m = quad_model();
  PolygonTransition s = sample_near_ground(m, Vec3(0.8, -0.7, 1.3));
  s.v_next = prediction(m, s) + Vec3(0.05, -0.03, 0.2);
  const PolygonDataset data = one_sample(s);
  PolygonObjective objective(data, m, settings(method, relaxed_weight));
  const ParameterSet theta = make_polygon_parameters(m, PolygonLearnFlags{});
  const SampleResult r = loss(objective, theta);
  ASSERT_TRUE(r.ok) << r.message;
  ASSERT_EQ(objective.stats().contacts, 2);
  const double h = 1e-6;
  Vector fd(theta.size());
  for (Index k = 0; k < theta.size(); ++k) {
    ParameterSet tp = theta, tm = theta;
    tp.set_value(theta[k].name, theta[k].value + h);
    tm.set_value(theta[k].name, theta[k].value - h);
    const SampleResult rp = loss(objective, tp), rm = loss(objective, tm);
    ASSERT_TRUE(rp.ok && rm.ok);
    fd(k) = (rp.loss - rm.loss) / (2 * h);
  }
  EXPECT_EQ(objective.stats().contacts, 2 * (1 + 2 * theta.size())) << "the active set changed under θ ± h";
  const double scale = std::max(fd.cwiseAbs().maxCoeff(), 1e-3 * std::abs(r.loss));
  const double err = (r.gradient - fd).cwiseAbs().maxCoeff() / scale;
  for (Index k = 0; k < theta.size(); ++k)
    EXPECT_LE(std::abs(r.gradient(k) - fd(k)), tol * scale) << to_string(method) << " " << theta[k].name
                                                            << " analytic " << r.gradient(k) << " fd " << fd(k);
  // The ground's entries are not trivially zero (a tilted, raised ground in contact).
  const PolygonLayout layout{static_cast<Index>(m.shape.vertices.size())};
  EXPECT_GT(std::abs(fd(layout.ground_height())), 1e-6);
  EXPECT_GT(std::abs(fd(layout.ground_angle())), 1e-6);
  std::printf("%s: loss %.6e, max |g - fd| / max|fd| = %.3e\n", to_string(method), r.loss, err);
}

TEST(LearnPolygonLossGradient, HardMatchesCentralDifferences) { check_gradient(PolygonMethod::hard, 1e-5); }
TEST(LearnPolygonLossGradient, RelaxedMatchesCentralDifferences) {
  // The lifted relaxed QP's convexity shift b_f = a2 μ_f S_f depends on the data and is
  // part of the objective (step_loss_relaxed.hpp), so without a proximal centre the envelope
  // gradient is exact: checked with small weights a1 = a2 = 0.01 and with unit weights.
  check_gradient(PolygonMethod::relaxed, 1e-4, 0.01);
  check_gradient(PolygonMethod::relaxed, 1e-4, 1.0);
}
TEST(LearnPolygonLossGradient, ConvexMatchesCentralDifferences) { check_gradient(PolygonMethod::convex, 1e-4); }

TEST(LearnPolygonLossGradient, ConvexResidualsGiveTheLossAndItsGradient) {
  // The convex loss is a sum of squares ℓ = ‖r‖², r = v⁺ − v̄ (SceneObjective's residuals,
  // their Jacobian pulled back to the polygon's θ like the gradient): ‖r‖² = ℓ and
  // 2 Jᵀ r = ∂ℓ/∂θ, the gradient checked against central differences above.
  const PolygonModel m = quad_model();
  PolygonTransition s = sample_near_ground(m, Vec3(0.8, -0.7, 1.3));
  s.v_next = prediction(m, s) + Vec3(0.05, -0.03, 0.2);
  const PolygonDataset data = one_sample(s);
  PolygonObjective objective(data, m, settings(PolygonMethod::convex, 1.0));
  ASSERT_TRUE(objective.residuals_unavailable().empty());
  const ParameterSet theta = make_polygon_parameters(m, PolygonLearnFlags{});
  const SampleResult r = loss(objective, theta);
  const ResidualResult res = objective.evaluate_residuals(0, theta, 0);
  ASSERT_TRUE(r.ok && res.ok) << r.message << res.message;
  ASSERT_EQ(res.jacobian.cols(), theta.size());
  EXPECT_NEAR(res.residual.squaredNorm(), r.loss, 1e-12 * (1 + r.loss));
  const Vector g = 2.0 * res.jacobian.transpose() * res.residual;
  EXPECT_LE((g - r.gradient).cwiseAbs().maxCoeff(), 1e-8 * r.gradient.cwiseAbs().maxCoeff());
  PolygonObjective hard(data, m, settings(PolygonMethod::hard, 1.0));
  EXPECT_FALSE(hard.residuals_unavailable().empty());
}

TEST(LearnPolygonLossGradient, HardGradientInMuVanishesWhenSticking) {
  // A slow tangential velocity with a large μ: the contacts stick, so the hard loss does
  // not depend on μ locally, whatever the target says.
  PolygonModel m = quad_model();
  m.mu = 2.0;
  PolygonTransition s = sample_near_ground(m, Vec3(0.05, -0.3, 0.0));
  s.v_next = prediction(m, s) + Vec3(0.3, 0.0, 0.0);  // the data slid on
  const PolygonDataset data = one_sample(s);
  const ParameterSet theta = make_polygon_parameters(m, PolygonLearnFlags{});
  PolygonObjective hard_objective(data, m, settings(PolygonMethod::hard, 1.0));
  PolygonObjective relaxed_objective(data, m, settings(PolygonMethod::relaxed, 1.0));
  const SampleResult hard = loss(hard_objective, theta), relaxed = loss(relaxed_objective, theta);
  ASSERT_TRUE(hard.ok && relaxed.ok);
  EXPECT_NEAR(hard.gradient(PolygonLayout::kMu), 0.0, 1e-12);
  EXPECT_GT(std::abs(relaxed.gradient(PolygonLayout::kMu)), 1e-6);
}

}  // namespace
}  // namespace lcprelax::learn
