// Scene learning end to end (learn/scene_objective.hpp): on one transition of a settled
// 20-body pile with ≥ 60 contacts, ∂ℓ/∂θ of every parameter kind (μ, each class's mass,
// inertia and vertices, the ground's angle and offset, the walls' end points) for the hard,
// relaxed and convex losses against central differences of the whole pipeline (θ → world →
// collision → islands → assembly → loss), relative error ≤ 1e-5 away from kinks.
#include "learn_scene_fd_support.hpp"
#include "learn_scene_pile_support.hpp"

#include <lcprelax/learn/scene_objective.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lcprelax::learn {
namespace {

struct Pile {
  SceneDataset data;
  Index sample = 0;
};

// A settled 20-body pile; the transition with the most contacts among the last ones.
const Pile& settled_pile(ContactModel model) {
  static Pile piles[2];
  static bool made[2] = {false, false};
  const int k = model == ContactModel::lcp ? 0 : 1;
  if (!made[k]) {
    SceneDatasetSettings ds;
    ds.drop_without_contact = false;
    piles[k].data = test::last_transitions(make_learning_pile(test::learning_pile_options(20, 4, model)), 90, 40, ds);
    made[k] = true;
  }
  return piles[k];
}

// tolerance: 1e-5 relative for all three (the convex loss's solves at 1e-14:
// test::fd_loss_settings).
void check_gradient(LossMethod method, ContactModel data_model, double tolerance = 1e-5) {
  const Pile& pile = settled_pile(data_model);
  SceneParameterSettings ps;
  ps.learn.ground = true;
  const SceneParameterMap map(pile.data.scene.world, ps);
  const ParameterSet truth = map.parameters(pile.data.scene.world);
  // Away from the truth (where the hard loss and its gradient vanish): 5% off.
  const ParameterSet theta = perturb_scene_parameters(truth, map, 0.05, 11);
  SceneObjective objective(pile.data, map, test::fd_loss_settings(method));
  long most = 0;
  const Index sample = test::sample_with_most_contacts(objective, theta, most);
  ASSERT_GE(most, 60) << "the pile should rest on >= 60 contacts";
  // Every parameter; settled piles have kinks (a degenerate contact: λ = 0 and w = 0, or two
  // exactly parallel faces whose incident edge flips), where the adjoint must equal one of
  // the one-sided derivatives (learn_scene_fd_support.hpp). At most 20% of them on kinks.
  std::vector<Index> all(static_cast<std::size_t>(theta.size()));
  for (Index k = 0; k < theta.size(); ++k) all[static_cast<std::size_t>(k)] = k;
  const test::FdReport report = test::compare_with_central_differences(
      objective, map, theta, sample, all, std::string(to_string(method)) + ", " + std::to_string(most) + " contacts",
      tolerance);
  EXPECT_LE(report.kinks * 5, static_cast<int>(theta.size()));
}

// A settled pile without pushes sticks everywhere; from μ₀ = 10× the truth every contact
// still sticks, the LCP's basis does not change with μ, and the hard loss's ∂ℓ/∂μ is zero
// (the weakness the relaxed loss removes: its ∂ℓ/∂μ is not zero there). Zero up to the
// roundoff of the final basis' solution, which Lemke returns unclipped where clipping
// would move w more (6.7e-31 here): required below 1e-12 of the relaxed loss's.
TEST(SceneGradient, HardHasZeroMuGradientFromTenTimesTheTruthOnStickingData) {
  LearningPileOptions po;
  po.bodies = 20;
  SceneDatasetSettings ds;
  ds.push_fraction = 0.0;
  const SceneDataset data = test::last_transitions(make_learning_pile(po), 120, 5, ds);
  const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
  ParameterSet theta = map.parameters(data.scene.world);
  theta.set_value("mu", 10 * theta.value("mu"));
  double hard_gradient = 0.0;
  for (LossMethod method : {LossMethod::hard, LossMethod::relaxed}) {
    SceneLossSettings ls;
    ls.method = method;
    SceneObjective objective(data, map, ls);
    objective.prepare(theta, 1);
    double mu_gradient = 0.0;
    for (Index i = 0; i < objective.num_samples(); ++i) {
      const SampleResult r = objective.evaluate(i, theta, 0);
      ASSERT_TRUE(r.ok) << r.message;
      mu_gradient += std::abs(r.gradient(0));
    }
    if (method == LossMethod::hard) {
      hard_gradient = mu_gradient;
    } else {
      EXPECT_GT(mu_gradient, 0.0);
      EXPECT_LE(hard_gradient, 1e-12 * mu_gradient);
    }
  }
}

TEST(SceneGradient, RelaxedMatchesCentralDifferences) { check_gradient(LossMethod::relaxed, ContactModel::lcp); }
TEST(SceneGradient, HardMatchesCentralDifferences) { check_gradient(LossMethod::hard, ContactModel::lcp); }
TEST(SceneGradient, ConvexMatchesCentralDifferences) { check_gradient(LossMethod::convex, ContactModel::convex); }

}  // namespace
}  // namespace lcprelax::learn
