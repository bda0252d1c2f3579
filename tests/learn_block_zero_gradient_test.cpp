// The seeds' point (Parmar, Halm & Posa, IROS 2021), shown, not hidden: with data from
// μ = 0.1 (half the samples slipping, |v*| ≤ 9·μmg/m) and the prior μ = 1 (10× the truth),
// every sample sticks under the prior, so
// - the hard loss is positive but its gradient ∂loss/∂μ is exactly 0.0, and 30 epochs of
//   SGD leave μ exactly at 1 (bitwise);
// - the convex loss's gradient is ~0 too (≤ 1e-6: the bound is inactive when sticking;
//   not exactly 0 because the interior point's inactive bound multipliers are ~1e-9);
// - the relaxed loss's gradient is positive (it points towards the truth) and training
//   moves μ down.
#include <lcprelax/learn/block_losses.hpp>

#include <gtest/gtest.h>

namespace lcprelax::learn {
namespace {

struct Fixture {
  BlockDataset data;
  std::vector<Index> all;
  Fixture() {
    BlockDataSettings s;
    s.truth = Block1d{1.0, 1.0, 0.1};
    s.samples = 60;
    data = generate_block_dataset(s);
    for (Index i = 0; i < data.size(); ++i) all.push_back(i);
  }
};

TEST(BlockZeroGradient, HardGradientIsExactlyZeroAndMuDoesNotMove) {
  Fixture f;
  EXPECT_EQ(count_sticking(f.data, Block1d{1.0, 1.0, 1.0}), f.data.size());  // all stick at μ = 1
  auto hard = make_block_objective(BlockMethod::hard, f.data);
  ParameterSet theta = block_parameters(1.0, 1.0, 1.0);
  const BatchResult r = evaluate_mean(*hard, theta, f.all, 1);
  EXPECT_GT(r.loss, 1e-3);
  EXPECT_EQ(r.gradient(theta.index("mu")), 0.0);
  TrainSettings t;
  t.epochs = 30;
  t.batch = 10;
  t.threads = 1;
  t.optimizer.kind = OptimizerKind::sgd;
  t.optimizer.learning_rate = 0.5;
  t.patience = 0;  // all 30 epochs: the exactly-zero gradient would pass the convergence test
  const TrainResult run = train(*hard, theta, f.all, {}, t);
  EXPECT_EQ(run.history.size(), 30u);
  EXPECT_EQ(theta.value("mu"), 1.0);
}

TEST(BlockZeroGradient, ConvexIsFlatRelaxedIsNot) {
  Fixture f;
  const ParameterSet theta = block_parameters(1.0, 1.0, 1.0);
  auto convex = make_block_objective(BlockMethod::convex, f.data);
  EXPECT_LE(std::abs(evaluate_mean(*convex, theta, f.all, 1).gradient(0)), 1e-6);
  auto relaxed = make_block_objective(BlockMethod::relaxed, f.data);
  EXPECT_GT(evaluate_mean(*relaxed, theta, f.all, 1).gradient(0), 1e-3);
  ParameterSet learned = theta;
  TrainSettings t;
  t.epochs = 20;
  t.threads = 1;
  t.optimizer.kind = OptimizerKind::adam;
  t.optimizer.learning_rate = 0.1;
  train(*relaxed, learned, f.all, {}, t);
  EXPECT_LT(learned.value("mu"), 0.5);
}

}  // namespace
}  // namespace lcprelax::learn
