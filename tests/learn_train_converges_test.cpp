// train() ends a run once it has converged (trainer.hpp): on the convex toy objective
// ℓᵢ(x) = (x − cᵢ)² (minimum at the mean of cᵢ)
// - full batch, SGD: stops before the cap with converged = true and a "converged" stop
//   reason; the last `patience` records each meet the stated criteria (relative loss change
//   ≤ rel_loss_tol, full-training-set gradient norm ≤ grad_tol, streak counting up to
//   patience) and the record before them does not; x is at the minimum;
// - mini-batches with Adam and a decaying learning rate (the stochastic case; grad_tol 1e-5
//   because θ's jitter shrinks only like the learning rate): stops before the cap, the
//   criteria met on the whole training set at the stop (not on the mini-batch epoch loss),
//   x within 1e-5 of the minimum; the stop epoch and θ are identical for 1 and 2 threads;
// - invalid tolerances are InputErrors.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <gtest/gtest.h>

#include "learn_train_support.hpp"

#include <cmath>
#include <cstring>

namespace lcprelax::learn {
namespace {

using test::all_samples;
using test::Quadratic;
constexpr double kMinimum = test::kQuadraticMinimum;

void expect_stopped_converged(const TrainResult& r, const TrainSettings& t) {
  ASSERT_TRUE(r.converged) << r.stop_reason;
  EXPECT_EQ(r.stop_reason.rfind("converged", 0), 0u) << r.stop_reason;
  ASSERT_LT(static_cast<int>(r.history.size()), t.epochs);
  ASSERT_GT(static_cast<int>(r.history.size()), t.patience);
  for (int k = 0; k < t.patience; ++k) {
    const EpochRecord& e = r.history[r.history.size() - 1 - static_cast<std::size_t>(k)];
    EXPECT_LE(e.relative_loss_change, t.rel_loss_tol) << "epoch " << e.epoch;
    EXPECT_LE(e.full_gradient_norm, t.grad_tol) << "epoch " << e.epoch;
    EXPECT_EQ(e.streak, t.patience - k) << "epoch " << e.epoch;
  }
  // Not earlier: the epoch before the last `patience` did not satisfy the test.
  const EpochRecord& before = r.history[r.history.size() - 1 - static_cast<std::size_t>(t.patience)];
  EXPECT_EQ(before.streak, 0);
  EXPECT_FALSE(before.relative_loss_change <= t.rel_loss_tol && before.full_gradient_norm <= t.grad_tol)
      << "epoch " << before.epoch;
}

TEST(TrainConverges, FullBatchStopsBeforeTheCapWithTheCriteriaMet) {
  Quadratic q;
  ParameterSet theta({Parameter{"x", 0.0}});
  TrainSettings t;
  t.epochs = 5000;
  t.threads = 1;
  t.optimizer.learning_rate = 0.05;
  const TrainResult r = train(q, theta, all_samples(), {}, t);
  expect_stopped_converged(r, t);
  EXPECT_NEAR(theta[0].value, kMinimum, 1e-6);
  // Full batch: the test uses the epoch's own evaluation.
  EXPECT_EQ(r.history.back().full_loss, r.history.back().loss);
  EXPECT_EQ(r.history.back().full_gradient_norm, r.history.back().gradient_norm);
  std::printf("full batch: %zu epochs, %s, x = %.9f\n", r.history.size(), r.stop_reason.c_str(), theta[0].value);
}

TEST(TrainConverges, MiniBatchesWithDecayStopIdenticallyForEveryThreadCount) {
  auto run = [](int threads, ParameterSet& theta) {
    Quadratic q;
    TrainSettings t;
    t.epochs = 20000;
    t.batch = 8;
    t.threads = threads;
    t.optimizer.kind = OptimizerKind::adam;
    t.optimizer.learning_rate = 0.05;
    t.optimizer.decay = 0.05;
    t.grad_tol = 1e-5;  // the jitter of θ under Adam shrinks only like α_k (see trainer.hpp)
    return std::make_pair(train(q, theta, all_samples(), {}, t), t);
  };
  ParameterSet a({Parameter{"x", 0.0}}), b({Parameter{"x", 0.0}});
  const auto [ra, t] = run(1, a);
  const auto rb = run(2, b).first;
  expect_stopped_converged(ra, t);
  EXPECT_NEAR(a[0].value, kMinimum, 1e-5);
  ASSERT_EQ(ra.history.size(), rb.history.size());
  EXPECT_EQ(std::memcmp(&a[0].value, &b[0].value, sizeof(double)), 0);
  std::printf("mini-batch: %zu epochs, %s, x = %.9f\n", ra.history.size(), ra.stop_reason.c_str(), a[0].value);
}

TEST(TrainConverges, InvalidTolerancesAreInputErrors) {
  Quadratic q;
  ParameterSet theta({Parameter{"x", 0.0}});
  for (int field = 0; field < 4; ++field) {
    TrainSettings t;
    if (field == 0) t.rel_loss_tol = -1e-9;
    if (field == 1) t.grad_tol = std::nan("");
    if (field == 2) t.grad_tol = -1.0;
    if (field == 3) t.patience = -1;
    EXPECT_FALSE(t.validation_error().empty()) << field;
    EXPECT_THROW(train(q, theta, all_samples(), {}, t), InputError) << field;
  }
  EXPECT_TRUE(TrainSettings{}.validation_error().empty());
}

}  // namespace
}  // namespace lcprelax::learn
