// The L-BFGS optimizer of train() (optimizer.hpp, trainer.hpp, learn/src/lbfgs_line_search.hpp):
// - its two-loop direction equals −H g of the explicit BFGS inverse-Hessian recursion
//   H ← (I − ρ s yᵀ) H (I − ρ y sᵀ) + ρ s sᵀ from H₀ = (sᵀy/yᵀy) I of the newest pair
//   (Nocedal & Wright 2006, eqs. 7.16–7.20), on random pairs;
// - pairs with sᵀy ≤ 0 are not stored, and at most `memory` pairs are kept;
// - on Rosenbrock's valley (condition number ~2500 at its minimum) a full-batch run stops
//   converged at (1, 1) to 1e-6 within 100 epochs, where Adam with the same cap and learning
//   rate has not converged;
// - on a kinked loss |x − c| the line search fails at the kink and ends the run with its
//   own stop reason (no endless creeping at the noise floor);
// - on Lewis and Overton's nonsmooth Rosenbrock function 8|x² − y| + (1 − x)², whose
//   minimum (1, 1) lies on the kink x² = y, the weak Wolfe line search lets BFGS follow the
//   kink to 1e-4 (a backtracking Armijo search stops at the kink, far from the minimum);
// - mini-batches and Optimizer::step are refused.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace lcprelax::learn {
namespace {

// ℓᵢ(x, y) = (a − x)² + b (y − x²)² for every sample (a = 1, b = 100): the mean is the same.
class Rosenbrock : public Objective {
 public:
  Index num_samples() const override { return 4; }
  SampleResult evaluate(Index, const ParameterSet& theta, int) override {
    const double x = theta[0].value, y = theta[1].value;
    SampleResult r;
    r.loss = (1.0 - x) * (1.0 - x) + 100.0 * (y - x * x) * (y - x * x);
    r.gradient.resize(2);
    r.gradient(0) = -2.0 * (1.0 - x) - 400.0 * x * (y - x * x);
    r.gradient(1) = 200.0 * (y - x * x);
    return r;
  }
};

// ℓ(x) = |x − c|: a minimum at a kink, where no line search along −g can decrease (c not
// on the grid of the first steepest-descent steps, which would land on it exactly).
constexpr double kKink = 0.3 + 0.01 / 7.0;
class Kink : public Objective {
 public:
  Index num_samples() const override { return 1; }
  SampleResult evaluate(Index, const ParameterSet& theta, int) override {
    const double d = theta[0].value - kKink;
    SampleResult r;
    r.loss = std::abs(d);
    r.gradient = Vector::Constant(1, d >= 0 ? 1.0 : -1.0);  // a subgradient, never 0
    return r;
  }
};

// Lewis & Overton, "Nonsmooth optimization via quasi-Newton methods", Math. Programming
// 141 (2013), §6: ℓ(x, y) = 8|x² − y| + (1 − x)², minimum 0 at (1, 1), on the kink.
class NonsmoothRosenbrock : public Objective {
 public:
  Index num_samples() const override { return 1; }
  SampleResult evaluate(Index, const ParameterSet& theta, int) override {
    const double x = theta[0].value, y = theta[1].value, k = x * x - y;
    const double sign = k >= 0 ? 1.0 : -1.0;
    SampleResult r;
    r.loss = 8.0 * std::abs(k) + (1.0 - x) * (1.0 - x);
    r.gradient.resize(2);
    r.gradient(0) = 16.0 * sign * x - 2.0 * (1.0 - x);
    r.gradient(1) = -8.0 * sign;
    return r;
  }
};

std::vector<Index> samples(Index n) {
  std::vector<Index> s;
  for (Index i = 0; i < n; ++i) s.push_back(i);
  return s;
}

TEST(TrainLbfgs, TwoLoopDirectionEqualsTheExplicitBfgsRecursion) {
  const Index n = 5;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);  // an SPD "Hessian" so that sᵀy > 0
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j) A(i, j) = normal(rng);
  A = A * A.transpose() + Eigen::MatrixXd::Identity(n, n);
  OptimizerSettings os;
  os.kind = OptimizerKind::lbfgs;
  os.memory = 3;
  Optimizer opt(os);
  std::vector<Vector> S, Y;
  for (int k = 0; k < 5; ++k) {
    Vector s(n);
    for (Index i = 0; i < n; ++i) s(i) = normal(rng);
    const Vector y = A * s;
    ASSERT_TRUE(opt.lbfgs_accept(s, y));
    S.push_back(s);
    Y.push_back(y);
  }
  EXPECT_EQ(opt.lbfgs_pairs(), 3);  // memory 3: the two oldest dropped
  const std::size_t first = S.size() - 3;
  const Vector& sn = S.back();
  const Vector& yn = Y.back();
  Eigen::MatrixXd H = sn.dot(yn) / yn.squaredNorm() * Eigen::MatrixXd::Identity(n, n);
  for (std::size_t k = first; k < S.size(); ++k) {
    const double rho = 1.0 / Y[k].dot(S[k]);
    const Eigen::MatrixXd V = Eigen::MatrixXd::Identity(n, n) - rho * Y[k] * S[k].transpose();
    H = V.transpose() * H * V + rho * S[k] * S[k].transpose();
  }
  Vector g(n);
  for (Index i = 0; i < n; ++i) g(i) = normal(rng);
  const Vector expected = -H * g;
  const Vector d = opt.lbfgs_direction(g);
  EXPECT_LE((d - expected).norm(), 1e-10 * expected.norm()) << d.transpose() << "\n" << expected.transpose();
}

TEST(TrainLbfgs, PairsWithoutPositiveCurvatureAreNotStored) {
  OptimizerSettings os;
  os.kind = OptimizerKind::lbfgs;
  Optimizer opt(os);
  const Vector s = Vector::Constant(2, 1.0);
  EXPECT_FALSE(opt.lbfgs_accept(s, -s));
  EXPECT_FALSE(opt.lbfgs_accept(s, Vector::Zero(2)));
  EXPECT_EQ(opt.lbfgs_pairs(), 0);
  EXPECT_EQ(opt.steps(), 2);  // counted as steps all the same
  EXPECT_TRUE(opt.lbfgs_accept(s, 2.0 * s));
  EXPECT_EQ(opt.lbfgs_pairs(), 1);
  // H₀ = (sᵀy/yᵀy) I = I/2 with one pair along s: −H g for g ∥ s is −g/2.
  const Vector d = opt.lbfgs_direction(s);
  EXPECT_NEAR(d(0), -0.5, 1e-15);
  EXPECT_NEAR(d(1), -0.5, 1e-15);
}

TrainSettings full_batch(OptimizerKind kind) {
  TrainSettings t;
  t.epochs = 100;
  t.threads = 1;
  t.optimizer.kind = kind;
  t.optimizer.learning_rate = 0.05;
  t.rel_loss_tol = 1e-12;
  t.grad_tol = 1e-8;
  t.patience = 1;
  return t;
}

TEST(TrainLbfgs, SolvesRosenbrockWhereAdamDoesNot) {
  Rosenbrock f;
  ParameterSet a({Parameter{"x", -1.2}, Parameter{"y", 1.0}});
  const TrainResult r = train(f, a, samples(4), {}, full_batch(OptimizerKind::lbfgs));
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_NEAR(a[0].value, 1.0, 1e-6);
  EXPECT_NEAR(a[1].value, 1.0, 1e-6);
  std::printf("lbfgs: %zu epochs, %s, (x, y) = (%.10f, %.10f)\n", r.history.size(), r.stop_reason.c_str(), a[0].value,
              a[1].value);
  ParameterSet b({Parameter{"x", -1.2}, Parameter{"y", 1.0}});
  const TrainResult adam = train(f, b, samples(4), {}, full_batch(OptimizerKind::adam));
  EXPECT_FALSE(adam.converged);
  EXPECT_GT(std::abs(b[0].value - 1.0), 1e-3);
  std::printf("adam:  %zu epochs, %s, (x, y) = (%.6f, %.6f)\n", adam.history.size(), adam.stop_reason.c_str(),
              b[0].value, b[1].value);
}

TEST(TrainLbfgs, AKinkEndsTheRunWithItsOwnReason) {
  Kink f;
  ParameterSet theta({Parameter{"x", 1.0}});
  TrainSettings t = full_batch(OptimizerKind::lbfgs);
  t.epochs = 1000;
  const TrainResult r = train(f, theta, samples(1), {}, t);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.stop_reason.rfind("lbfgs line search found no decrease", 0), 0u) << r.stop_reason;
  EXPECT_LT(static_cast<int>(r.history.size()), 200);
  EXPECT_NEAR(theta[0].value, kKink, 1e-6);
}

TEST(TrainLbfgs, FollowsAKinkToTheMinimumOnNonsmoothRosenbrock) {
  NonsmoothRosenbrock f;
  ParameterSet theta({Parameter{"x", -0.9}, Parameter{"y", 1.5}});
  TrainSettings t = full_batch(OptimizerKind::lbfgs);
  t.epochs = 500;
  const TrainResult r = train(f, theta, samples(1), {}, t);
  std::printf("nonsmooth Rosenbrock: %zu epochs, %s, (x, y) = (%.8f, %.8f)\n", r.history.size(),
              r.stop_reason.c_str(), theta[0].value, theta[1].value);
  EXPECT_NEAR(theta[0].value, 1.0, 1e-4);
  EXPECT_NEAR(theta[1].value, 1.0, 1e-4);
}

TEST(TrainLbfgs, RefusesMiniBatchesAndPlainSteps) {
  Rosenbrock f;
  ParameterSet theta({Parameter{"x", 0.0}, Parameter{"y", 0.0}});
  TrainSettings t = full_batch(OptimizerKind::lbfgs);
  t.batch = 2;
  EXPECT_THROW(train(f, theta, samples(4), {}, t), InputError);
  t.batch = 4;  // the whole set: allowed
  EXPECT_NO_THROW(train(f, theta, samples(4), {}, t));
  OptimizerSettings os;
  os.kind = OptimizerKind::lbfgs;
  Optimizer opt(os);
  Vector xi = Vector::Zero(2);
  EXPECT_THROW(opt.step(xi, Vector::Ones(2)), std::logic_error);
  os.memory = 0;
  EXPECT_THROW(Optimizer{os}, InputError);
  EXPECT_EQ(parse_optimizer_kind("lbfgs"), OptimizerKind::lbfgs);
  EXPECT_THROW(parse_optimizer_kind("bfgs"), InputError);
}

}  // namespace
}  // namespace lcprelax::learn
