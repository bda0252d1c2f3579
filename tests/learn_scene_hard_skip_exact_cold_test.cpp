// The hard method with stored bases skips the exact cold attempt (step 3 of
// models/contact_step.hpp) on a transition whose last evaluation ended solved_inaccurate,
// and retries it on every SceneObjective::kExactRetryEvery-th such evaluation in a row
// (learn/scene_objective.hpp).
// Transition: the last one of a 100-body learning pile after 80 convex-model steps (as
// bench/run_learn_scene), evaluated at the true θ, where the lcp model's answer is the
// perturbed one (its polish on q and the exact cold attempt fail). Measured: 2,090 pivots
// for the first (cold) evaluation, 279 for the ones that skip, 952 for the retry (the skip's
// 279 and the exact attempt's 673), the same loss in all.
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/learn/state_stream.hpp>

#include "learn_scene_pile_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace lcprelax::learn {
namespace {

const SceneDataset& jammed_transition() {
  static const SceneDataset data = [] {
    LearningPileOptions po;
    po.bodies = 100;
    po.model = ContactModel::convex;
    SceneDatasetSettings ds;
    ds.drop_without_contact = false;
    ds.allow_failed_islands = true;
    return test::last_transitions(make_learning_pile(po), 80, 1, ds);
  }();
  return data;
}

struct Evaluations {
  std::vector<long> pivots;
  std::vector<double> losses;
  std::vector<long> inaccurate;  ///< solved_inaccurate islands per evaluation
};

Evaluations evaluate_repeatedly(bool warm_basis, int times) {
  const SceneDataset& data = jammed_transition();
  const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
  const ParameterSet theta = map.parameters(data.scene.world);
  SceneLossSettings ls;
  ls.method = LossMethod::hard;
  ls.hard_warm_basis = warm_basis;
  SceneObjective objective(data, map, ls);
  objective.prepare(theta, 1);
  Evaluations run;
  for (int e = 0; e < times; ++e) {
    objective.reset_stats();
    const SampleResult r = objective.evaluate(0, theta, 0);
    EXPECT_TRUE(r.ok) << r.message;
    run.pivots.push_back(objective.stats().solver_work);
    run.losses.push_back(r.loss);
    run.inaccurate.push_back(objective.stats().inaccurate_islands);
  }
  return run;
}

TEST(SceneHardSkipExactCold, SkipsAfterAPerturbedAnswerAndRetriesOnSchedule) {
  const int every = SceneObjective::kExactRetryEvery;
  const Evaluations warm = evaluate_repeatedly(true, every + 2);
  for (std::size_t e = 0; e < warm.pivots.size(); ++e)
    std::printf("[ measured ] evaluation %zu: %ld pivots, loss %.12g\n", e, warm.pivots[e], warm.losses[e]);
  // Fixture: the cold evaluation ends on the perturbed answer.
  ASSERT_EQ(warm.inaccurate[0], 1);
  for (int e = 1; e < every; ++e) {
    EXPECT_LT(warm.pivots[e] * 4, warm.pivots[0]) << "evaluation " << e << " skips the exact cold attempt";
    EXPECT_NEAR(warm.losses[e], warm.losses[0], 1e-9 * std::abs(warm.losses[0])) << "evaluation " << e;
    EXPECT_EQ(warm.inaccurate[e], 1) << "evaluation " << e;
  }
  EXPECT_GT(warm.pivots[every], 2 * warm.pivots[1]) << "evaluation " << every << " retries it";
  EXPECT_LT(warm.pivots[every + 1] * 4, warm.pivots[0]) << "and the next one skips again";
}

// The counts travel with the stored bases in the objective's state (checkpoints, the
// portfolio's restarts): a restored objective skips as the original would.
TEST(SceneHardSkipExactCold, CountsAreSavedWithTheBases) {
  const SceneDataset& data = jammed_transition();
  const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
  const ParameterSet theta = map.parameters(data.scene.world);
  SceneLossSettings ls;
  ls.method = LossMethod::hard;
  SceneObjective first(data, map, ls);
  first.prepare(theta, 1);
  first.reset_stats();
  ASSERT_TRUE(first.evaluate(0, theta, 0).ok);
  const long cold = first.stats().solver_work;
  StateWriter w;
  first.save_state(w);
  const std::string state = w.take();
  SceneObjective restored(data, map, ls);
  StateReader in(state, "test");
  restored.load_state(in);
  in.expect_end();
  restored.prepare(theta, 1);
  restored.reset_stats();
  ASSERT_TRUE(restored.evaluate(0, theta, 0).ok);
  EXPECT_LT(restored.stats().solver_work * 4, cold) << "the restored objective skips the exact cold attempt";
}

TEST(SceneHardSkipExactCold, NotWithoutStoredBases) {
  const Evaluations cold = evaluate_repeatedly(false, 3);
  ASSERT_EQ(cold.inaccurate[0], 1);
  EXPECT_EQ(cold.pivots[1], cold.pivots[0]);
  EXPECT_EQ(cold.pivots[2], cold.pivots[0]);
}

}  // namespace
}  // namespace lcprelax::learn
