// Gaussian prior on the free parameters (prior.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/prior.hpp>

#include <cmath>
#include <string>

namespace lcprelax::learn {

PriorObjective::PriorObjective(Objective& base, const ParameterSet& center, double weight)
    : base_(base), center_(center.free()), weight_(weight) {
  if (!(weight >= 0.0) || !std::isfinite(weight))
    throw InputError("prior weight must be finite and >= 0 (got " + std::to_string(weight) + ")");
}

void PriorObjective::prepare(const ParameterSet& theta, int threads) {
  if (theta.size() != center_.size())
    throw InputError("prior: " + std::to_string(theta.size()) + " parameters, its centre has " +
                     std::to_string(center_.size()));
  base_.prepare(theta, threads);
}

void PriorObjective::deviation(const ParameterSet& theta, Vector& d, Vector& dxi_dtheta) const {
  const Vector dtheta_dxi = theta.chain_gradient(Vector::Ones(theta.size()));  // 0 where held
  d = theta.free() - center_;
  dxi_dtheta = Vector::Zero(theta.size());
  for (Index k = 0; k < theta.size(); ++k) {
    if (dtheta_dxi(k) == 0.0) {
      d(k) = 0.0;
    } else {
      dxi_dtheta(k) = 1.0 / dtheta_dxi(k);
    }
  }
}

SampleResult PriorObjective::evaluate(Index sample, const ParameterSet& theta, int thread) {
  SampleResult r = base_.evaluate(sample, theta, thread);
  if (!r.ok || weight_ == 0.0) return r;
  Vector d, dxi_dtheta;
  deviation(theta, d, dxi_dtheta);
  r.loss += weight_ * d.squaredNorm();
  if (r.gradient.size() == theta.size()) r.gradient += 2.0 * weight_ * d.cwiseProduct(dxi_dtheta);
  return r;
}

ResidualResult PriorObjective::evaluate_residuals(Index sample, const ParameterSet& theta, int thread) {
  ResidualResult r = base_.evaluate_residuals(sample, theta, thread);
  if (!r.ok) return r;
  Vector d, dxi_dtheta;
  deviation(theta, d, dxi_dtheta);
  const Index m = r.residual.size(), n = theta.size();
  const double s = std::sqrt(weight_);
  Vector residual(m + n);
  residual << r.residual, s * d;
  DenseMatrix jacobian = DenseMatrix::Zero(m + n, n);
  jacobian.topRows(m) = r.jacobian;
  jacobian.bottomRows(n).diagonal() = s * dxi_dtheta;
  r.residual = std::move(residual);
  r.jacobian = std::move(jacobian);
  return r;
}

}  // namespace lcprelax::learn
