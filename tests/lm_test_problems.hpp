#pragma once
// Least-squares test objectives for the Levenberg–Marquardt tests (learn_train_lm_test,
// learn_train_lm_geodesic_test): Rosenbrock's function as residuals and an exponential fit.
#include <lcprelax/learn/trainer.hpp>

#include <cmath>
#include <vector>

namespace lcprelax::learn::lm_test {

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

inline std::vector<Index> all(Index n) {
  std::vector<Index> s;
  for (Index i = 0; i < n; ++i) s.push_back(i);
  return s;
}

inline TrainSettings lm_settings(int epochs) {
  TrainSettings ts;
  ts.epochs = epochs;
  ts.optimizer.kind = OptimizerKind::lm;
  ts.rel_loss_tol = 1e-14;
  ts.grad_tol = 1e-10;
  ts.patience = 2;
  return ts;
}

inline ParameterSet exponential_start() {
  return ParameterSet({Parameter{"a", 1.0, Transform::log}, Parameter{"b", 0.0}});
}

}  // namespace lcprelax::learn::lm_test
