// The Levenberg–Marquardt optimizer of train() (optimizer.hpp, least_squares.hpp,
// learn/src/levenberg_marquardt.hpp):
// - on Rosenbrock's function as residuals r = (1 − x, 10(y − x²)) from the classic start
//   (−1.2, 1) a full-batch run stops converged at (1, 1) to 1e-8 within 40 epochs, where
//   L-BFGS needs ~46 epochs to reach 1e-6 and Adam does not converge (learn_train_lbfgs_test);
// - on an exponential fit over several samples with a log parameter (ξ = log a) and an
//   identity one it recovers both to 1e-9, with θ bitwise the same for 1 and 2 threads;
// - a run stopped after k epochs and resumed from its checkpoint ends bitwise where an
//   uninterrupted run ends (the damping λ, ν is part of the optimizer state);
// - a wrong Jacobian (sign flipped: every model step goes uphill) finds no decrease: θ stays
//   and the run ends with its own stop reason instead of creeping on;
// - a parameter held fixed does not move;
// - mini-batches, objectives without residuals, more than 400 parameters and
//   Optimizer::step are refused.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace lcprelax::learn {
namespace {

// ℓᵢ = ‖rᵢ‖² and ∂ℓᵢ/∂θ = 2 gradient_sign·Jᵢᵀrᵢ from the residuals.
class SumOfSquares : public Objective {
 public:
  std::string residuals_unavailable() const override { return {}; }
  SampleResult evaluate(Index i, const ParameterSet& theta, int t) override {
    const ResidualResult rr = evaluate_residuals(i, theta, t);
    SampleResult r;
    r.loss = rr.residual.squaredNorm();
    r.gradient = 2.0 * gradient_sign_ * rr.jacobian.transpose() * rr.residual;
    return r;
  }

 protected:
  double gradient_sign_ = 1.0;
};

// Rosenbrock's function as a sum of squares, ℓ = (1 − x)² + 100(y − x²)², every sample equal.
class RosenbrockResiduals : public SumOfSquares {
 public:
  explicit RosenbrockResiduals(double jacobian_sign = 1.0) : sign_(jacobian_sign) { gradient_sign_ = jacobian_sign; }
  Index num_samples() const override { return 3; }
  ResidualResult evaluate_residuals(Index, const ParameterSet& theta, int) override {
    const double x = theta[0].value, y = theta[1].value;
    ResidualResult r;
    r.residual = Vector(2);
    r.residual << 1.0 - x, 10.0 * (y - x * x);
    r.jacobian = DenseMatrix(2, 2);
    r.jacobian << -1.0, 0.0, -20.0 * x, 10.0;
    r.jacobian *= sign_;
    return r;
  }

 private:
  double sign_;
};

// yᵢ = a·exp(b tᵢ) at tᵢ = i/4, fitted with rᵢ = a exp(b tᵢ) − yᵢ; a is a log parameter.
constexpr double kA = 2.5, kB = -0.7;
class ExponentialFit : public SumOfSquares {
 public:
  Index num_samples() const override { return 9; }
  ResidualResult evaluate_residuals(Index i, const ParameterSet& theta, int) override {
    const double a = theta[0].value, b = theta[1].value, t = 0.25 * i;
    ResidualResult r;
    r.residual = Vector::Constant(1, a * std::exp(b * t) - kA * std::exp(kB * t));
    r.jacobian = DenseMatrix(1, 2);
    r.jacobian << std::exp(b * t), a * t * std::exp(b * t);
    return r;
  }
};

// A loss that is not a sum of squares: no residuals.
class Plain : public Objective {
 public:
  Index num_samples() const override { return 1; }
  SampleResult evaluate(Index, const ParameterSet& theta, int) override {
    SampleResult r;
    r.loss = std::abs(theta[0].value);
    r.gradient = Vector::Constant(1, theta[0].value >= 0 ? 1.0 : -1.0);
    return r;
  }
};

std::vector<Index> all(Index n) {
  std::vector<Index> s;
  for (Index i = 0; i < n; ++i) s.push_back(i);
  return s;
}

TrainSettings lm_settings(int epochs) {
  TrainSettings ts;
  ts.epochs = epochs;
  ts.optimizer.kind = OptimizerKind::lm;
  ts.rel_loss_tol = 1e-14;
  ts.grad_tol = 1e-10;
  ts.patience = 2;
  return ts;
}

ParameterSet exponential_start() {
  return ParameterSet({Parameter{"a", 1.0, Transform::log}, Parameter{"b", 0.0}});
}

TEST(TrainLm, RosenbrockConvergesToTheMinimum) {
  RosenbrockResiduals f;
  ParameterSet theta({Parameter{"x", -1.2}, Parameter{"y", 1.0}});
  const TrainResult r = train(f, theta, all(3), {}, lm_settings(40));
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_NEAR(theta[0].value, 1.0, 1e-8);
  EXPECT_NEAR(theta[1].value, 1.0, 1e-8);
  std::printf("Rosenbrock: %zu epochs, (%.12g, %.12g)\n", r.history.size(), theta[0].value, theta[1].value);
}

TEST(TrainLm, ExponentialFitIsExactAndTheSameForEveryThreadCount) {
  ExponentialFit f;
  ParameterSet one = exponential_start(), two = exponential_start();
  TrainSettings ts = lm_settings(60);
  ts.threads = 1;
  const TrainResult r1 = train(f, one, all(9), {}, ts);
  ts.threads = 2;
  train(f, two, all(9), {}, ts);
  EXPECT_TRUE(r1.converged) << r1.stop_reason;
  EXPECT_NEAR(one[0].value, kA, 1e-9);
  EXPECT_NEAR(one[1].value, kB, 1e-9);
  EXPECT_EQ(one.values(), two.values());  // bitwise
}

TEST(TrainLm, ResumedRunEndsBitwiseWhereTheUninterruptedOneEnds) {
  ExponentialFit f;
  const std::string path = ::testing::TempDir() + "lcprelax_lm_resume.ckpt";
  ParameterSet straight = exponential_start();
  TrainSettings ts = lm_settings(6);
  ts.patience = 0;
  train(f, straight, all(9), {}, ts);

  ParameterSet resumed = exponential_start();
  ts.checkpoint = path;
  ts.epochs = 3;
  train(f, resumed, all(9), {}, ts);
  ts.epochs = 6;
  ts.resume = path;
  train(f, resumed, all(9), {}, ts);
  EXPECT_EQ(straight.values(), resumed.values());
  std::remove(path.c_str());
}

TEST(TrainLm, WrongJacobianFindsNoDecreaseAndKeepsTheta) {
  RosenbrockResiduals f(-1.0);
  ParameterSet theta({Parameter{"x", -1.2}, Parameter{"y", 1.0}});
  const TrainResult r = train(f, theta, all(3), {}, lm_settings(20));
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.stop_reason.find("lm found no decrease"), std::string::npos) << r.stop_reason;
  EXPECT_EQ(r.history.size(), 1u);
  EXPECT_EQ(theta[0].value, -1.2);
  EXPECT_EQ(theta[1].value, 1.0);
}

TEST(TrainLm, HeldParameterDoesNotMove) {
  ExponentialFit f;
  ParameterSet theta = exponential_start();
  theta.set_learn("b", false);
  theta.set_value("b", kB);
  train(f, theta, all(9), {}, lm_settings(30));
  EXPECT_EQ(theta[1].value, kB);
  EXPECT_NEAR(theta[0].value, kA, 1e-9);
}

TEST(TrainLm, RefusesMiniBatchesPlainLossesAndOptimizerStep) {
  ExponentialFit f;
  ParameterSet theta = exponential_start();
  TrainSettings ts = lm_settings(5);
  ts.batch = 4;
  EXPECT_THROW(train(f, theta, all(9), {}, ts), InputError);
  Plain plain;
  ParameterSet x({Parameter{"x", 1.0}});
  try {
    train(plain, x, all(1), {}, lm_settings(5));
    ADD_FAILURE() << "lm on a loss without residuals was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("least-squares"), std::string::npos) << e.what();
  }
  EXPECT_THROW(plain.evaluate_residuals(0, x, 0), std::logic_error);
  std::vector<Parameter> many;
  for (int i = 0; i < 401; ++i) many.push_back(Parameter{"p" + std::to_string(i), 1.0});
  ParameterSet big(many);
  EXPECT_THROW(train(f, big, all(9), {}, lm_settings(1)), InputError);  // > 400 parameters
  OptimizerSettings os;
  os.kind = OptimizerKind::lm;
  Optimizer opt(os);
  Vector xi = Vector::Zero(1);
  EXPECT_THROW(opt.step(xi, Vector::Ones(1)), std::logic_error);
  EXPECT_EQ(parse_optimizer_kind("lm"), OptimizerKind::lm);
}

}  // namespace
}  // namespace lcprelax::learn
