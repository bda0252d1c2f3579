// The hard method's stored final bases (SceneLossSettings::hard_warm_basis,
// learn/scene_objective.hpp): each transition keeps its islands' final Lemke basis, matched
// contact by contact, and the next evaluation starts Lemke from it.
// Expected, on the last 10 transitions of a 12-body pile dropped with the lcp model
// (make_learning_pile, 60 steps), θ 5% off the truth:
// - a second evaluation of a transition at the same θ takes 0 pivots (the stored basis is
//   the solution's) and gives the same loss and gradient as the first, to 1e-12 relative;
// - at θ moved by 1e-4 relative, the evaluations starting from the stored bases take fewer
//   pivots in all than cold ones, and give the loss of a cold evaluation to 1e-9 relative;
// - with hard_warm_basis = false, every evaluation takes as many pivots as the first, and
//   no contact has a stored basis (all counted in stats().cold_contacts);
// - a regularized island's basis is stored marked and restarts on M + εI (last test).
#include <lcprelax/learn/scene_objective.hpp>

#include "dynamics_support.hpp"
#include "learn_scene_pile_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lcprelax::learn {
namespace {

const SceneDataset& dropped_pile() {
  static const SceneDataset data = [] {
    SceneDatasetSettings ds;
    ds.drop_without_contact = false;
    return test::last_transitions(make_learning_pile(test::learning_pile_options(12, 3, ContactModel::lcp)), 60, 10, ds);
  }();
  return data;
}

SceneLossSettings hard_settings(bool warm) {
  SceneLossSettings ls;
  ls.method = LossMethod::hard;
  ls.hard_warm_basis = warm;
  return ls;
}

struct Pass {
  double loss = 0.0;
  long pivots = 0, cold_contacts = 0, contacts = 0;
  std::vector<Vector> gradients;
  std::vector<double> losses;
};

// Every transition once at θ, in order.
Pass evaluate_all(SceneObjective& objective, const ParameterSet& theta) {
  objective.prepare(theta, 1);
  objective.reset_stats();
  Pass p;
  for (Index i = 0; i < objective.num_samples(); ++i) {
    const SampleResult r = objective.evaluate(i, theta, 0);
    EXPECT_TRUE(r.ok) << "transition " << i << ": " << r.message;
    p.loss += r.loss;
    p.losses.push_back(r.loss);
    p.gradients.push_back(r.gradient);
  }
  const SceneObjectiveStats st = objective.stats();
  p.pivots = st.solver_work;
  p.cold_contacts = st.cold_contacts;
  p.contacts = st.contacts;
  return p;
}

struct PileTheta {
  SceneParameterMap map;
  ParameterSet theta;
  PileTheta() : map(dropped_pile().scene.world, SceneParameterSettings{}) {
    theta = perturb_scene_parameters(map.parameters(dropped_pile().scene.world), map, 0.05, 3);
  }
};

TEST(SceneHardWarmBasis, RepeatedEvaluationTakesNoPivotsAndGivesTheSameGradient) {
  PileTheta su;
  SceneObjective objective(dropped_pile(), su.map, hard_settings(true));
  const Pass first = evaluate_all(objective, su.theta);
  const Pass second = evaluate_all(objective, su.theta);
  std::printf("[ measured ] pivots: first pass %ld, second %ld (%ld contacts, %ld without a stored basis)\n",
              first.pivots, second.pivots, second.contacts, second.cold_contacts);
  ASSERT_GT(first.pivots, 0) << "the first pass must pivot (a cold start)";
  EXPECT_EQ(first.cold_contacts, first.contacts);
  EXPECT_EQ(second.cold_contacts, 0);
  EXPECT_EQ(second.pivots, 0);
  for (std::size_t i = 0; i < first.losses.size(); ++i) {
    EXPECT_NEAR(second.losses[i], first.losses[i], 1e-12 * std::max(1.0, std::abs(first.losses[i]))) << i;
    const double scale = std::max(1e-300, first.gradients[i].lpNorm<Eigen::Infinity>());
    EXPECT_LE((second.gradients[i] - first.gradients[i]).lpNorm<Eigen::Infinity>(), 1e-12 * scale) << i;
  }
}

TEST(SceneHardWarmBasis, NearbyThetaStartsFromTheStoredBasesWithTheColdLoss) {
  PileTheta su;
  SceneObjective warm(dropped_pile(), su.map, hard_settings(true));
  SceneObjective cold(dropped_pile(), su.map, hard_settings(false));
  (void)evaluate_all(warm, su.theta);
  const Pass cold_first = evaluate_all(cold, su.theta);
  ParameterSet moved = su.theta;
  Vector values = moved.values();
  for (Index k = 0; k < moved.size(); ++k)
    if (moved[k].learn) values(k) *= 1.0 + 1e-4;
  moved.set_values(values);
  const Pass w = evaluate_all(warm, moved), c = evaluate_all(cold, moved);
  std::printf("[ measured ] pivots at the moved theta: from the stored bases %ld, cold %ld\n", w.pivots, c.pivots);
  EXPECT_LT(w.pivots, c.pivots);
  EXPECT_NEAR(w.loss, c.loss, 1e-9 * std::abs(c.loss));
  EXPECT_EQ(c.cold_contacts, c.contacts);
  EXPECT_GT(c.pivots, 0);
  const Pass cold_again = evaluate_all(cold, su.theta);
  EXPECT_EQ(cold_again.pivots, cold_first.pivots) << "without stored bases every pass starts cold";
}

// A transition whose island's answer is regularized (the wedged box of lcp_wedge_support.hpp,
// with a q bias b = −1e-6 m/s whose LCP on M has no solution) stores its basis marked, and
// the next evaluation starts from it on M + εI (step 1c), as the simulator would: fewer
// pivots than the first (cold) evaluation and than an evaluation without the mark would
// take (hard_step_loss from the unmarked basis), the same loss to 1e-7 relative.
TEST(SceneHardWarmBasis, ARegularizedIslandRestartsOnMPlusEpsilonI) {
  Scene scene;
  scene.world.bodies.push_back(lcprelax::test::box(0.1, 0.1, 10.0, Vec3(0.0, 1.0, 0.0)));
  scene.world.half_planes.push_back(HalfPlane{Vec2(1.0, 0.0), -0.0499, 0});
  scene.world.half_planes.push_back(HalfPlane{Vec2(-1.0, 0.0), -0.0499, 0});
  scene.world.friction.default_mu = 0.5;
  scene.world.lcp_block.enabled = true;
  scene.world.lcp_block.q = Vec4(-1e-6, 0.0, 0.0, 0.0);
  scene.settings.dt = 1e-2;
  scene.settings.model = ContactModel::lcp;
  scene.settings.margin = 1e-2;
  SceneDatasetSettings ds;
  ds.steps = 2;
  ds.push_fraction = 0.0;
  ds.drop_without_contact = false;
  const SceneDataset data = generate_scene_dataset(scene, ds);
  ASSERT_GE(data.transitions.size(), 1u);
  const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
  const ParameterSet theta = map.parameters(data.scene.world);
  SceneObjective objective(data, map, hard_settings(true));
  objective.prepare(theta, 1);
  objective.reset_stats();
  const SampleResult first = objective.evaluate(0, theta, 0);
  ASSERT_TRUE(first.ok) << first.message;
  const SceneObjectiveStats a = objective.stats();
  ASSERT_EQ(a.inaccurate_islands, 1) << "the wedge's answer is regularized";
  objective.reset_stats();
  const SampleResult second = objective.evaluate(0, theta, 0);
  ASSERT_TRUE(second.ok) << second.message;
  const SceneObjectiveStats b = objective.stats();
  std::printf("[ measured ] wedge pivots: cold %ld, from the marked basis %ld\n", a.solver_work, b.solver_work);
  EXPECT_EQ(b.inaccurate_islands, 1);
  EXPECT_EQ(b.cold_contacts, 0);
  EXPECT_LT(b.solver_work, a.solver_work);
  EXPECT_NEAR(second.loss, first.loss, 1e-7 * std::abs(first.loss));
}

}  // namespace
}  // namespace lcprelax::learn
