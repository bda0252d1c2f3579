// The Levenberg–Marquardt optimizer of train() (optimizer.hpp, least_squares.hpp,
// learn/src/levenberg_marquardt.hpp):
// - on Rosenbrock's function as residuals r = (1 − x, 10(y − x²)) from the classic start
//   (−1.2, 1) a full-batch run stops converged at (1, 1) to 1e-8 within 40 epochs, where
//   L-BFGS needs ~46 epochs to reach 1e-6 and Adam does not converge (learn_train_lbfgs_test);
// - on an exponential fit over several samples with a log parameter (ξ = log a) and an
//   identity one it recovers both to 1e-9, with θ bitwise the same for 1 and 2 threads,
//   with and without the geodesic acceleration (the chain rule at the displaced point);
// - a run stopped after k epochs and resumed from its checkpoint ends bitwise where an
//   uninterrupted run ends (the damping λ, ν is part of the optimizer state);
// - a wrong Jacobian (sign flipped: every model step goes uphill) finds no decrease: θ stays
//   and the run ends with its own stop reason instead of creeping on;
// - a parameter held fixed does not move;
// - mini-batches, objectives without residuals, more than 400 parameters and
//   Optimizer::step are refused.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/trainer.hpp>

#include "lm_test_problems.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace lcprelax::learn {
namespace {

using namespace lm_test;

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
  for (const bool geodesic : {false, true}) {  // with and without the geodesic acceleration
    SCOPED_TRACE(geodesic ? "geodesic acceleration" : "plain");
    ExponentialFit f;
    ParameterSet one = exponential_start(), two = exponential_start();
    TrainSettings ts = lm_settings(60);
    ts.optimizer.lm_geodesic_acceleration = geodesic;
    ts.threads = 1;
    const TrainResult r1 = train(f, one, all(9), {}, ts);
    ts.threads = 2;
    train(f, two, all(9), {}, ts);
    EXPECT_TRUE(r1.converged) << r1.stop_reason;
    EXPECT_NEAR(one[0].value, kA, 1e-9);
    EXPECT_NEAR(one[1].value, kB, 1e-9);
    EXPECT_EQ(one.values(), two.values());  // bitwise
  }
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
