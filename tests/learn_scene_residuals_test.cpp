// The convex scene loss as a least-squares objective (SceneObjective::evaluate_residuals,
// convex_step_jacobian; least_squares.hpp), on one transition of a settled 12-body pile of
// convex-model data:
// - ‖r‖² equals evaluate()'s loss and 2Jᵀr its gradient (the rows of ∂v⁺/∂data combine to
//   the loss's adjoint), for the default and the unbiased (phase 1 without the deviation,
//   r = 1e-6) loss settings;
// - every column of J (μ, each class's mass, inertia and vertices, ground and walls)
//   against central differences of the residual through the whole pipeline (θ → world →
//   collision → islands → assembly → both phases), ≤ 1e-5 relative away from kinks;
// - the hard and relaxed methods say why they have no residuals.
#include <lcprelax/learn/scene_objective.hpp>

#include "learn_scene_pile_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lcprelax::learn {
namespace {

const SceneDataset& settled_convex_pile() {
  static const SceneDataset data = [] {
    SceneDatasetSettings ds;
    ds.drop_without_contact = false;
    return test::last_transitions(make_learning_pile(test::learning_pile_options(12, 3, ContactModel::convex)), 70, 10, ds);
  }();
  return data;
}

SceneLossSettings convex_settings(bool unbiased) {
  SceneLossSettings ls;
  ls.method = LossMethod::convex;
  ls.convex.qp.eps_abs = 1e-14;
  ls.convex.qp.eps_rel = 0.0;
  if (unbiased) {
    ls.convex.phase1_deviation = false;
    ls.convex.phase1_regularization = 1e-6;
  }
  return ls;
}

void check_residuals(bool unbiased) {
  const SceneDataset& data = settled_convex_pile();
  SceneParameterSettings ps;
  ps.learn.ground = true;
  const SceneParameterMap map(data.scene.world, ps);
  const ParameterSet theta = perturb_scene_parameters(map.parameters(data.scene.world), map, 0.05, 5);
  SceneObjective objective(data, map, convex_settings(unbiased));
  EXPECT_TRUE(objective.residuals_unavailable().empty());
  objective.prepare(theta, 1);
  Index sample = 0;
  long most = -1;
  for (Index i = 0; i < objective.num_samples(); ++i) {
    objective.reset_stats();
    objective.evaluate(i, theta, 0);
    if (objective.stats().contacts > most) most = objective.stats().contacts, sample = i;
  }
  ASSERT_GE(most, 20);
  const SampleResult g = objective.evaluate(sample, theta, 0);
  const ResidualResult rr = objective.evaluate_residuals(sample, theta, 0);
  ASSERT_TRUE(g.ok) << g.message;
  ASSERT_TRUE(rr.ok) << rr.message;
  ASSERT_EQ(rr.residual.size(), 3 * static_cast<Index>(data.scene.world.bodies.size()));
  ASSERT_EQ(rr.jacobian.cols(), theta.size());
  EXPECT_NEAR(rr.residual.squaredNorm(), g.loss, 1e-12 * g.loss);
  const Vector from_rows = 2.0 * rr.jacobian.transpose() * rr.residual;
  const double gmax = g.gradient.cwiseAbs().maxCoeff();
  ASSERT_GT(gmax, 0.0);
  EXPECT_LE((from_rows - g.gradient).cwiseAbs().maxCoeff(), 1e-9 * gmax);

  auto residual_at = [&](Index k, double step) {
    Vector v = theta.values();
    v(k) += step;
    ParameterSet at = theta;
    at.set_values(v);
    objective.prepare(at, 1);
    const ResidualResult r = objective.evaluate_residuals(sample, at, 0);
    EXPECT_TRUE(r.ok) << theta[k].name << ": " << r.message;
    return r.residual;
  };
  const double jmax = rr.jacobian.cwiseAbs().maxCoeff();
  int checked = 0, kinks = 0;
  double worst = 0.0;
  for (Index k = 0; k < theta.size(); ++k) {
    const double h = 1e-5 * (map.kind(k) == SceneParameterMap::Kind::angle
                                 ? 1.0
                                 : std::max(map.length_scale(k), std::abs(theta[k].value)));
    const Vector p1 = residual_at(k, h), m1 = residual_at(k, -h), p2 = residual_at(k, h / 2), m2 = residual_at(k, -h / 2);
    const Vector fd = (p2 - m2) / h, fd_h = (p1 - m1) / (2 * h);
    const Vector column = rr.jacobian.col(k);
    const double scale = std::max(fd.cwiseAbs().maxCoeff(), 1e-3 * jmax);
    // A kink within ±h (a contact changing mode or feature): the two step sizes disagree.
    if ((fd - fd_h).cwiseAbs().maxCoeff() > 1e-4 * scale) {
      ++kinks;
      std::printf("kink: %s\n", theta[k].name.c_str());
      continue;
    }
    const double noise = 2.0 * (fd - fd_h).cwiseAbs().maxCoeff();
    const double error = (column - fd).cwiseAbs().maxCoeff();
    EXPECT_LE(error, 1e-5 * scale + noise) << theta[k].name << ": column of J vs central differences";
    worst = std::max(worst, error / scale);
    ++checked;
  }
  std::printf("%s settings: %d columns compared (largest relative error %.2e), %d on kinks, %ld contacts\n",
              unbiased ? "unbiased" : "default", checked, worst, kinks, most);
  EXPECT_LE(kinks * 5, static_cast<int>(theta.size()));
}

TEST(SceneResiduals, ConvexDefaultSettingsMatchLossGradientAndCentralDifferences) { check_residuals(false); }
TEST(SceneResiduals, ConvexUnbiasedSettingsMatchLossGradientAndCentralDifferences) { check_residuals(true); }

TEST(SceneResiduals, HardAndRelaxedSayWhyTheyHaveNone) {
  const SceneDataset& data = settled_convex_pile();
  const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
  for (LossMethod method : {LossMethod::hard, LossMethod::relaxed}) {
    SceneLossSettings ls;
    ls.method = method;
    SceneObjective objective(data, map, ls);
    const std::string why = objective.residuals_unavailable();
    EXPECT_NE(why.find("--method convex"), std::string::npos) << why;
  }
}

}  // namespace
}  // namespace lcprelax::learn
