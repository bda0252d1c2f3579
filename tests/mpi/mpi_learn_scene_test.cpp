// Scene learning (learn/scene_objective.hpp) data-parallel over 2 MPI ranks: a few epochs on
// a 12-body learning pile give bitwise the same learned θ on both ranks and as the same run
// by one process with 1 and with 2 threads, for the hard and the convex loss.
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include "mpi_main.hpp"

#include <cstring>

namespace {

using namespace lcprelax;
using namespace lcprelax::learn;

void check_same_theta(LossMethod method, ContactModel model) {
  ASSERT_EQ(mpi::mpi_size(), 2) << "run under mpiexec -n 2";
  LearningPileOptions po;
  po.bodies = 12;
  po.model = model;
  SceneDatasetSettings ds;
  ds.steps = 30;
  const SceneDataset data = generate_scene_dataset(make_learning_pile(po), ds);
  const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
  const ParameterSet truth = map.parameters(data.scene.world);
  SceneLossSettings ls;
  ls.method = method;
  SceneObjective objective(data, map, ls);
  std::vector<Index> training;
  for (Index i = 0; i < objective.num_samples(); ++i) training.push_back(i);
  TrainSettings t;
  t.epochs = 4;
  t.patience = 0;
  t.optimizer.kind = OptimizerKind::adam;
  t.optimizer.learning_rate = 0.003;
  std::vector<Vector> results;
  for (int threads : {1, 2})
    for (bool distributed : {true, false}) {
      ParameterSet theta = perturb_scene_parameters(truth, map, 0.1, 3);
      t.threads = threads;
      t.distributed = distributed;
      train(objective, theta, training, {}, t);
      results.push_back(theta.values());
    }
  const Index p = results[0].size();
  for (std::size_t k = 1; k < results.size(); ++k)
    EXPECT_EQ(std::memcmp(results[0].data(), results[k].data(), sizeof(double) * p), 0) << "run " << k;
  std::vector<double> mine(results[0].data(), results[0].data() + p);
  const std::vector<double> both = mpi::allgather(mine);
  ASSERT_EQ(both.size(), 2 * static_cast<std::size_t>(p));
  EXPECT_EQ(std::memcmp(both.data(), both.data() + p, sizeof(double) * p), 0);
  EXPECT_NE(results[0], perturb_scene_parameters(truth, map, 0.1, 3).values());  // training moved θ
}

TEST(DistributedSceneLearning, HardGivesTheSameThetaOnEveryRank) { check_same_theta(LossMethod::hard, ContactModel::lcp); }
TEST(DistributedSceneLearning, ConvexGivesTheSameThetaOnEveryRank) {
  check_same_theta(LossMethod::convex, ContactModel::convex);
}

}  // namespace

LCPRELAX_MPI_TEST_MAIN()
