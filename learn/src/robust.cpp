// Cauchy robustifier of per-sample losses (robust.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/robust.hpp>

#include <cmath>
#include <string>

namespace lcprelax::learn {

double cauchy_robust_loss(double loss, double scale) {
  if (scale == 0.0) return loss;
  return scale * std::log1p(loss / scale);
}

double cauchy_robust_weight(double loss, double scale) {
  if (scale == 0.0) return 1.0;
  return 1.0 / (1.0 + loss / scale);
}

RobustObjective::RobustObjective(Objective& base, double scale) : base_(base), scale_(scale) {
  if (!(scale >= 0.0) || !std::isfinite(scale))
    throw InputError("robust loss scale must be finite and >= 0 (got " + std::to_string(scale) + ")");
}

SampleResult RobustObjective::evaluate(Index sample, const ParameterSet& theta, int thread) {
  SampleResult r = base_.evaluate(sample, theta, thread);
  if (!r.ok || scale_ == 0.0) return r;
  const double w = cauchy_robust_weight(r.loss, scale_);
  r.loss = cauchy_robust_loss(r.loss, scale_);
  if (r.gradient.size() > 0) r.gradient *= w;
  return r;
}

namespace {

// g(s) = √(ρ(s)/s) and g'(s); series for s ≪ c: ρ/s = 1 − x/2 + x²/3 − …, x = s/c.
void residual_scale(double s, double c, double& g, double& dg) {
  const double x = s / c;
  if (x < 1e-6) {
    g = 1.0 - x / 4.0;
    dg = -1.0 / (4.0 * c);
    return;
  }
  const double rho = c * std::log1p(x);
  const double drho = 1.0 / (1.0 + x);
  g = std::sqrt(rho / s);
  dg = (drho * s - rho) / (2.0 * g * s * s);
}

}  // namespace

ResidualResult RobustObjective::evaluate_residuals(Index sample, const ParameterSet& theta, int thread) {
  ResidualResult r = base_.evaluate_residuals(sample, theta, thread);
  if (!r.ok || scale_ == 0.0) return r;
  const double s = r.residual.squaredNorm();
  double g = 1.0, dg = 0.0;
  residual_scale(s, scale_, g, dg);
  const Eigen::RowVectorXd rtj = r.residual.transpose() * r.jacobian;
  r.jacobian *= g;
  r.jacobian.noalias() += (2.0 * dg) * r.residual * rtj;
  r.residual *= g;
  return r;
}

}  // namespace lcprelax::learn
