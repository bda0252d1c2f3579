// 1 vs 2 threads for the polygon objective (polygon_objective.hpp). Expected behaviour: for
// every method (hard, relaxed, convex), the mean loss and gradient over all samples are
// bitwise identical (memcmp) with 1 and 2 threads, on a cold first evaluation, on a second
// evaluation that uses the per-transition proximal centres (relaxed; scene_objective.hpp),
// and after 3 training epochs (θ compared).
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/learn/polygon_objective.hpp>

#include <gtest/gtest.h>

#include <cstring>

namespace lcprelax::learn {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vector& a, const Vector& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

class LearnPolygonThreads : public ::testing::TestWithParam<PolygonMethod> {};

TEST_P(LearnPolygonThreads, OneAndTwoThreadsAreBitwiseIdentical) {
  const PolygonModel truth = reference_polygon_model();
  PolygonDataSettings ds;
  ds.trajectories = 3;
  ds.steps = 50;
  ds.seed = 11;
  const PolygonDataset data = generate_polygon_dataset(truth, ds);
  const PolygonLearnFlags flags{true, true, true, true, true};
  const ParameterSet start = make_polygon_parameters(perturb_polygon_model(truth, flags, 0.2, 5), flags);
  PolygonLossSettings ls;
  ls.method = GetParam();
  PolygonObjective one(data, truth, ls), two(data, truth, ls);
  std::vector<Index> all, none;
  split_samples(one.num_samples(), 0.0, 1, all, none);
  for (int round = 0; round < 2; ++round) {  // cold, then from the stored centres
    const BatchResult r1 = evaluate_mean(one, start, all, 1);
    const BatchResult r2 = evaluate_mean(two, start, all, 2);
    EXPECT_EQ(r1.failed, r2.failed);
    EXPECT_TRUE(same_bits(r1.loss, r2.loss)) << "round " << round << ": " << r1.loss << " vs " << r2.loss;
    EXPECT_TRUE(same_bits(r1.gradient, r2.gradient)) << "round " << round;
  }
  TrainSettings ts;
  ts.epochs = 3;
  ts.batch = 16;
  ts.optimizer.kind = OptimizerKind::adam;
  ts.optimizer.learning_rate = 0.01;
  ParameterSet t1 = start, t2 = start;
  ts.threads = 1;
  const TrainResult a = train(one, t1, all, none, ts);
  ts.threads = 2;
  const TrainResult b = train(two, t2, all, none, ts);
  EXPECT_TRUE(same_bits(t1.values(), t2.values()));
  EXPECT_TRUE(same_bits(a.history.back().loss, b.history.back().loss));
}

INSTANTIATE_TEST_SUITE_P(Methods, LearnPolygonThreads,
                         ::testing::Values(PolygonMethod::hard, PolygonMethod::relaxed, PolygonMethod::convex),
                         [](const ::testing::TestParamInfo<PolygonMethod>& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace lcprelax::learn
