// The learning infrastructure (learn/parameters, optimizer, batch, trainer):
// - log-transformed parameters: ξ = log θ, chain_gradient multiplies by θ, set_free clamps
//   to the bounds, learn = false zeroes the gradient, invalid parameters are InputErrors;
// - SGD with momentum and Adam minimize ½‖ξ − c‖² to 1e-6; gradient clipping caps the first
//   SGD step at clip_norm·α; the schedule gives α/(1 + decay·k); a NaN gradient throws;
// - evaluate_batch sums in sample order: 1 and 2 threads give bitwise-identical sums, a
//   throwing sample is counted as failed and left out;
// - train() on a quadratic objective is reproducible (two runs, and 1 vs 2 threads, give
//   bitwise-identical histories) and converges; invalid settings are InputErrors.
#include <lcprelax/learn/trainer.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace lcprelax::learn {
namespace {

TEST(LearnInfra, ParametersLogTransformAndBounds) {
  ParameterSet p;
  p.add(Parameter{"mu", 0.5, Transform::log, 0.1, 2.0, true});
  p.add(Parameter{"x", -1.0, Transform::identity});
  EXPECT_DOUBLE_EQ(p.free()(0), std::log(0.5));
  const Vector g = p.chain_gradient((Vector(2) << 3.0, 4.0).finished());
  EXPECT_DOUBLE_EQ(g(0), 1.5);
  EXPECT_DOUBLE_EQ(g(1), 4.0);
  p.set_free((Vector(2) << std::log(10.0), 2.0).finished());
  EXPECT_DOUBLE_EQ(p.value("mu"), 2.0);  // clamped to the upper bound
  p.set_learn("x", false);
  EXPECT_EQ(p.chain_gradient(Vector::Ones(2))(1), 0.0);
  EXPECT_THROW(p.add(Parameter{"mu", 1.0}), InputError);
  EXPECT_THROW(p.add(Parameter{"neg", -1.0, Transform::log}), InputError);
  EXPECT_THROW(p.index("nope"), InputError);
}

Vector minimize(OptimizerSettings s, int steps) {
  Optimizer opt(s);
  Vector xi = Vector::Zero(3);
  const Vector c = (Vector(3) << 1.0, -2.0, 0.5).finished();
  for (int k = 0; k < steps; ++k) opt.step(xi, xi - c);
  return xi - c;
}

TEST(LearnInfra, OptimizersClippingSchedule) {
  OptimizerSettings sgd;
  sgd.learning_rate = 0.1;
  EXPECT_LT(minimize(sgd, 500).norm(), 1e-6);
  OptimizerSettings adam;
  adam.kind = OptimizerKind::adam;
  adam.learning_rate = 0.05;
  adam.decay = 0.01;
  EXPECT_LT(minimize(adam, 3000).norm(), 1e-6);
  OptimizerSettings clip = sgd;
  clip.clip_norm = 0.01;
  Optimizer o(clip);
  Vector xi = Vector::Zero(2);
  o.step(xi, (Vector(2) << 30.0, 40.0).finished());
  EXPECT_NEAR(xi.norm(), 0.1 * 0.01, 1e-15);
  OptimizerSettings sched = sgd;
  sched.decay = 0.5;
  Optimizer d(sched);
  for (int k = 0; k < 4; ++k) d.step(xi, Vector::Zero(2));
  EXPECT_DOUBLE_EQ(d.learning_rate(), 0.1 / 3.0);
  EXPECT_THROW(d.step(xi, Vector::Constant(2, std::nan(""))), std::runtime_error);
  sgd.momentum = 1.0;
  EXPECT_THROW(Optimizer bad(sgd), InputError);
}

TEST(LearnInfra, FixedOrderBatchReduction) {
  std::vector<Index> samples;
  for (Index i = 0; i < 1000; ++i) samples.push_back(i);
  auto f = [](Index i, int) {
    SampleResult r;
    r.loss = 1.0 / (1.0 + i) * std::pow(-1.0, i);
    r.gradient = Vector::Constant(2, std::sin(static_cast<double>(i)) * 1e-3 + 1e3 * (i % 7 == 0));
    if (i == 17) throw std::runtime_error("sample 17 fails");
    return r;
  };
  const BatchResult a = evaluate_batch(samples, 2, 1, f), b = evaluate_batch(samples, 2, 2, f);
  EXPECT_EQ(std::memcmp(&a.loss, &b.loss, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(a.gradient.data(), b.gradient.data(), 2 * sizeof(double)), 0);
  EXPECT_EQ(a.failed, 1);
  EXPECT_EQ(a.evaluated, 999);
  EXPECT_NE(a.first_failure.find("sample 17"), std::string::npos);
}

// ℓᵢ(θ) = (θ − cᵢ)², minimum at the mean of cᵢ.
class Quadratic : public Objective {
 public:
  Index num_samples() const override { return 50; }
  SampleResult evaluate(Index i, const ParameterSet& theta, int) override {
    const double c = 1.0 + 0.01 * i, x = theta[0].value;
    SampleResult r;
    r.loss = (x - c) * (x - c);
    r.gradient = Vector::Constant(1, 2.0 * (x - c));
    return r;
  }
};

TEST(LearnInfra, TrainerIsReproducibleAndConverges) {
  auto run = [](int threads) {
    Quadratic q;
    ParameterSet theta({Parameter{"x", 0.0}});
    std::vector<Index> training, validation;
    split_samples(50, 0.2, 3, training, validation);
    TrainSettings t;
    t.epochs = 40;
    t.batch = 8;
    t.threads = threads;
    t.optimizer.learning_rate = 0.05;
    const TrainResult r = train(q, theta, training, validation, t);
    return std::make_pair(theta[0].value, r.history.back().loss);
  };
  const auto a = run(1), b = run(1), c = run(2);
  EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
  EXPECT_EQ(std::memcmp(&a, &c, sizeof a), 0);
  EXPECT_NEAR(a.first, 1.245, 0.05);
  Quadratic q;
  ParameterSet theta({Parameter{"x", 0.0}});
  TrainSettings bad;
  bad.epochs = -1;
  EXPECT_THROW(train(q, theta, {0, 1}, {}, bad), InputError);
  EXPECT_THROW(train(q, theta, {}, {}, TrainSettings{}), InputError);
  EXPECT_THROW(train(q, theta, {99}, {}, TrainSettings{}), InputError);
}

}  // namespace
}  // namespace lcprelax::learn
