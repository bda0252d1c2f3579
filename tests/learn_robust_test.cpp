// The Cauchy robust per-sample loss (learn/robust.hpp):
// - loss ρ(ℓ) = c log(1 + ℓ/c), gradient ρ'(ℓ)∂ℓ/∂θ against central differences; the
//   residuals satisfy ‖r̃‖² = ρ(ℓ) and 2J̃ᵀr̃ = the robust gradient, far from the minimum (ℓ ≫ c)
//   and next to it (the series branch, ℓ < 1e-6 c); c = 0 leaves the objective bitwise;
// - one sample with a loss spike between the start and the truth (a transition whose contact
//   features switch) traps plain gradient descent on its far side, while the robust loss
//   reaches the truth, where every sample's loss vanishes;
// - a negative or non-finite scale is refused.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/robust.hpp>

#include "lm_test_problems.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace lcprelax::learn {
namespace {

using namespace lm_test;

ParameterSet rosenbrock_at(double x, double y) { return ParameterSet({Parameter{"x", x}, Parameter{"y", y}}); }

void expect_consistent(RobustObjective& robust, Objective& base, const ParameterSet& theta, double c) {
  robust.prepare(theta, 1);
  const SampleResult r = robust.evaluate(0, theta, 0);
  const SampleResult r0 = base.evaluate(0, theta, 0);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.loss, c * std::log1p(r0.loss / c), 1e-14 * std::max(1.0, r.loss));
  const double h = 1e-6;
  for (Index k = 0; k < theta.size(); ++k) {
    ParameterSet plus = theta, minus = theta;
    plus.set_value(theta[k].name, theta[k].value + h);
    minus.set_value(theta[k].name, theta[k].value - h);
    const double fd = (robust.evaluate(0, plus, 0).loss - robust.evaluate(0, minus, 0).loss) / (2 * h);
    EXPECT_NEAR(r.gradient(k), fd, 1e-7 * std::max(1.0, std::abs(fd))) << theta[k].name;
  }
  const ResidualResult rr = robust.evaluate_residuals(0, theta, 0);
  ASSERT_TRUE(rr.ok);
  EXPECT_NEAR(rr.residual.squaredNorm(), r.loss, 1e-13 * std::max(1e-300, r.loss) + 1e-300);
  const Vector g = 2.0 * rr.jacobian.transpose() * rr.residual;
  EXPECT_LE((g - r.gradient).norm(), 1e-12 * std::max(1e-12, r.gradient.norm())) << g.transpose();
}

TEST(RobustLoss, LossGradientAndResidualsAgree) {
  RosenbrockResiduals base;
  const double c = 0.5;
  RobustObjective robust(base, c);
  expect_consistent(robust, base, rosenbrock_at(-0.7, 1.3), c);     // ℓ ≈ 70 ≫ c
  expect_consistent(robust, base, rosenbrock_at(0.9, 0.74), c);     // ℓ = 0.5 = c
  expect_consistent(robust, base, rosenbrock_at(1.0 + 1e-5, 1.0), c);  // ℓ ≈ 4e-8 < 1e-6·c: series branch

  RobustObjective off(base, 0.0);
  const ParameterSet theta = rosenbrock_at(-0.7, 1.3);
  const SampleResult a = off.evaluate(1, theta, 0), b = base.evaluate(1, theta, 0);
  EXPECT_EQ(a.loss, b.loss);
  EXPECT_EQ(a.gradient, b.gradient);
  EXPECT_EQ(off.evaluate_residuals(1, theta, 0).jacobian, base.evaluate_residuals(1, theta, 0).jacobian);
}

// Nine samples ℓ = (θ − 1)² and one with a spike of height S at θ = 0.6 that vanishes at the
// truth θ = 1: ℓ₉ = S ((θ − 1)/0.4)² / (1 + ((θ − 0.6)/0.05)²).
class SpikedFit : public Objective {
 public:
  Index num_samples() const override { return 10; }
  void prepare(const ParameterSet&, int) override {}
  SampleResult evaluate(Index i, const ParameterSet& theta, int) override {
    const double t = theta[0].value;
    SampleResult r;
    r.gradient = Vector(1);
    if (i < 9) {
      r.loss = (t - 1) * (t - 1);
      r.gradient(0) = 2 * (t - 1);
      return r;
    }
    const double u = (t - 0.6) / 0.05, a = (t - 1) * (t - 1) / 0.16, da = 2 * (t - 1) / 0.16;
    const double q = 1 + u * u;
    r.loss = kSpike * a / q;
    r.gradient(0) = kSpike * (da / q - a * (2 * u / 0.05) / (q * q));
    return r;
  }
  static constexpr double kSpike = 50.0;
};

double descend(Objective& objective) {
  ParameterSet theta({Parameter{"t", 0.5}});
  TrainSettings ts;
  ts.epochs = 3000;
  ts.patience = 0;
  ts.optimizer.kind = OptimizerKind::sgd;
  ts.optimizer.momentum = 0.0;
  ts.optimizer.learning_rate = 0.05;
  train(objective, theta, all(10), {}, ts);
  return theta[0].value;
}

TEST(RobustLoss, OneSpikedSampleNoLongerTrapsTheFit) {
  SpikedFit base;
  EXPECT_LT(descend(base), 0.5);  // plain mean: held on the far side of the spike
  RobustObjective robust(base, 0.05);
  EXPECT_NEAR(descend(robust), 1.0, 1e-6);
}

TEST(RobustLoss, RefusesBadScales) {
  SpikedFit base;
  EXPECT_THROW(RobustObjective(base, -1.0), InputError);
  EXPECT_THROW(RobustObjective(base, std::nan("")), InputError);
  EXPECT_THROW(RobustObjective(base, INFINITY), InputError);
}

}  // namespace
}  // namespace lcprelax::learn
