// The Gaussian prior on the free parameters (learn/prior.hpp):
// - loss, gradient and residuals: ℓ + w‖ξ − ξ_c‖² with ξ = log θ for a log parameter and
//   θ/s for a scaled identity one; the gradient against central differences (1e-7); the
//   residuals satisfy ‖r‖² = ℓ and 2Jᵀr = ∂ℓ/∂θ; a held parameter adds nothing;
// - evaporation: with ℓ(ξ) = e^{−2ξ} (infimum at ξ → ∞, a parameter the data push off to
//   the boundary of the model) Levenberg–Marquardt runs off (ξ > 20 after 40 epochs),
//   while with the prior it stops at the MAP point, the root of −2e^{−2ξ} + 2wξ = 0;
// - a negative or non-finite weight and a θ of another size are refused.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/prior.hpp>

#include "lm_test_problems.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace lcprelax::learn {
namespace {

using namespace lm_test;

// r(ξ) = e^{−ξ} with θ = e^ξ, so r = 1/θ: the loss falls for ever as θ grows.
class Evaporating : public SumOfSquares {
 public:
  Index num_samples() const override { return 1; }
  ResidualResult evaluate_residuals(Index, const ParameterSet& theta, int) override {
    const double t = theta[0].value;
    ResidualResult r;
    r.residual = Vector::Constant(1, 1.0 / t);
    r.jacobian = DenseMatrix::Constant(1, 1, -1.0 / (t * t));
    return r;
  }
};

ParameterSet three_kinds() {
  Parameter scaled{"c", 0.3};
  scaled.scale = 0.5;
  return ParameterSet({Parameter{"a", 1.0, Transform::log}, Parameter{"b", 0.0}, scaled});
}

// ExponentialFit over (a, b) plus an unused third parameter c.
class ExponentialFitPlusOne : public ExponentialFit {
 public:
  ResidualResult evaluate_residuals(Index i, const ParameterSet& theta, int t) override {
    ResidualResult r = ExponentialFit::evaluate_residuals(i, theta, t);
    r.jacobian.conservativeResize(Eigen::NoChange, 3);
    r.jacobian.col(2).setZero();
    return r;
  }
};

TEST(Prior, LossGradientAndResidualsAgree) {
  ExponentialFitPlusOne base;
  const ParameterSet center = three_kinds();
  PriorObjective prior(base, center, 0.7);
  ParameterSet theta = center;
  theta.set_value("a", 1.9);
  theta.set_value("b", -0.3);
  theta.set_value("c", -0.2);
  prior.prepare(theta, 1);
  const SampleResult r = prior.evaluate(4, theta, 0);
  const SampleResult r0 = base.evaluate(4, theta, 0);
  const double da = std::log(1.9) - std::log(1.0), db = -0.3, dc = (-0.2 - 0.3) / 0.5;
  EXPECT_NEAR(r.loss, r0.loss + 0.7 * (da * da + db * db + dc * dc), 1e-14);
  const double h = 1e-6;
  for (Index k = 0; k < 3; ++k) {
    ParameterSet plus = theta, minus = theta;
    plus.set_value(plus[k].name, theta[k].value + h);
    minus.set_value(minus[k].name, theta[k].value - h);
    const double fd = (prior.evaluate(4, plus, 0).loss - prior.evaluate(4, minus, 0).loss) / (2 * h);
    EXPECT_NEAR(r.gradient(k), fd, 1e-7 * std::max(1.0, std::abs(fd))) << theta[k].name;
  }
  const ResidualResult rr = prior.evaluate_residuals(4, theta, 0);
  ASSERT_EQ(rr.residual.size(), 1 + 3);
  EXPECT_NEAR(rr.residual.squaredNorm(), r.loss, 1e-14);
  EXPECT_TRUE((2.0 * rr.jacobian.transpose() * rr.residual - r.gradient).norm() < 1e-13);

  theta.set_learn("c", false);  // held: no prior term, no gradient
  const SampleResult held = prior.evaluate(4, theta, 0);
  EXPECT_NEAR(held.loss, r0.loss + 0.7 * (da * da + db * db), 1e-14);
  EXPECT_EQ(held.gradient(2), r0.gradient(2));
}

TEST(Prior, StopsTheEvaporationOfAParameter) {
  Evaporating base;
  ParameterSet plain({Parameter{"m", 1.0, Transform::log}});
  TrainSettings ts = lm_settings(40);
  ts.patience = 0;
  train(base, plain, all(1), {}, ts);
  EXPECT_GT(std::log(plain[0].value), 20.0);

  const double w = 0.1;
  ParameterSet map({Parameter{"m", 1.0, Transform::log}});
  PriorObjective prior(base, map, w);
  ts.patience = 2;
  train(prior, map, all(1), {}, ts);  // ends converged or at the loss's noise floor
  // MAP: e^{−2ξ} = wξ, solved by Newton's method here.
  double xi = 1.0;
  for (int k = 0; k < 50; ++k) xi -= (std::exp(-2 * xi) - w * xi) / (-2 * std::exp(-2 * xi) - w);
  EXPECT_NEAR(std::log(map[0].value), xi, 1e-7);
}

TEST(Prior, RefusesBadWeightsAndSizes) {
  Evaporating base;
  const ParameterSet one({Parameter{"m", 1.0, Transform::log}});
  EXPECT_THROW(PriorObjective(base, one, -1.0), InputError);
  EXPECT_THROW(PriorObjective(base, one, std::nan("")), InputError);
  PriorObjective prior(base, one, 1.0);
  const ParameterSet two({Parameter{"m", 1.0}, Parameter{"n", 1.0}});
  EXPECT_THROW(prior.prepare(two, 1), InputError);
}

}  // namespace
}  // namespace lcprelax::learn
