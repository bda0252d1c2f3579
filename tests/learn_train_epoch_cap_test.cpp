// train() with a run that cannot converge within TrainSettings::epochs (trainer.hpp):
// - full batch with a learning rate too small for the cap: exactly `epochs` epochs,
//   converged = false, stop_reason "epoch cap reached (…)";
// - mini-batches with a constant learning rate: θ keeps jittering around the minimum, the
//   full-training-set gradient stays above grad_tol, so the run reaches the cap and says so
//   rather than stopping on a lucky epoch;
// - patience = 0 switches the test off: a run that would converge runs exactly the cap.
#include <lcprelax/learn/trainer.hpp>

#include <gtest/gtest.h>

#include "learn_train_support.hpp"

namespace lcprelax::learn {
namespace {

using test::all_samples;
using test::Quadratic;

void expect_cap(const TrainResult& r, const TrainSettings& t) {
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(static_cast<int>(r.history.size()), t.epochs);
  EXPECT_EQ(r.stop_reason.rfind("epoch cap reached", 0), 0u) << r.stop_reason;
  if (t.patience > 0) {
    EXPECT_LT(r.history.back().streak, t.patience);
  }
}

TEST(TrainEpochCap, SlowFullBatchRunReportsTheCap) {
  Quadratic q;
  ParameterSet theta({Parameter{"x", 0.0}});
  TrainSettings t;
  t.epochs = 50;
  t.threads = 1;
  t.optimizer.learning_rate = 1e-4;
  t.optimizer.momentum = 0.0;
  const TrainResult r = train(q, theta, all_samples(), {}, t);
  expect_cap(r, t);
  EXPECT_GT(r.history.back().full_gradient_norm, t.grad_tol);
  EXPECT_EQ(r.stop_reason, "epoch cap reached (50 epochs)");
}

TEST(TrainEpochCap, ConstantRateMiniBatchesKeepJitteringUntilTheCap) {
  Quadratic q;
  ParameterSet theta({Parameter{"x", 0.0}});
  TrainSettings t;
  t.epochs = 300;
  t.batch = 8;
  t.threads = 1;
  t.optimizer.learning_rate = 0.05;
  const TrainResult r = train(q, theta, all_samples(), {}, t);
  expect_cap(r, t);
  EXPECT_NEAR(theta[0].value, 1.195, 0.05);  // near the minimum, but jittering
  for (std::size_t k = 100; k < r.history.size(); ++k) EXPECT_GT(r.history[k].full_gradient_norm, t.grad_tol);
}

TEST(TrainEpochCap, PatienceZeroRunsExactlyTheCap) {
  Quadratic q;
  ParameterSet theta({Parameter{"x", 0.0}});
  TrainSettings t;
  t.epochs = 3000;
  t.threads = 1;
  t.optimizer.learning_rate = 0.05;
  t.patience = 0;
  const TrainResult r = train(q, theta, all_samples(), {}, t);
  expect_cap(r, t);
  EXPECT_EQ(r.stop_reason, "epoch cap reached (3000 epochs, convergence test off)");
  // It had met the criteria long before (the streak still counts with the test off).
  EXPECT_LE(r.history.back().full_gradient_norm, t.grad_tol);
  EXPECT_GT(r.history.back().streak, 1000);
}

}  // namespace
}  // namespace lcprelax::learn
