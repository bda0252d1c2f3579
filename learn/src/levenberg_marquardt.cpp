// One Levenberg–Marquardt iteration (levenberg_marquardt.hpp).
#include "levenberg_marquardt.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>

namespace lcprelax::learn::detail {
namespace {

constexpr double kLmMaxFreeStep = 1.0;  // largest change of one free coordinate per trial
constexpr int kLmMaxTrials = 30;
constexpr double kAcceptRatio = 1e-4;
constexpr double kMinRelativeDecrease = 1e-14;
constexpr double kInitialDamping = 1e-3;
constexpr double kScaleFloor = 1e-12;
constexpr double kGeodesicStep = 0.1;          // h of the second difference (Transtrum & Sethna 2012)
constexpr double kMaxAccelerationRatio = 0.75;  // their α: 2‖a‖/‖v‖ above it rejects the trial

// The mean Gauss–Newton model over the samples: A, b and the mean loss C.
struct NormalEquations {
  DenseMatrix A;
  Vector b;
  double loss = 0.0;
  BatchResult batch;
};

// `base` (indexed by sample) receives each sample's residual when it is not null (the
// geodesic acceleration needs r(ξ₀)).
NormalEquations normal_equations(Objective& objective, const ParameterSet& theta, const std::vector<Index>& samples,
                                 int threads, bool distributed, std::vector<Vector>* base) {
  const Index n = theta.size();
  const Vector chain = theta.chain_gradient(Vector::Ones(n));  // dθ/dξ, 0 where held fixed
  objective.prepare(theta, resolve_threads(threads));
  // Each sample packs J̃ᵀr (n entries) then J̃ᵀJ̃ (n² entries, column-major) into the slot
  // that evaluate_batch reduces in sample order.
  const SampleFunction f = [&](Index i, int t) {
    SampleResult out;
    const ResidualResult rr = objective.evaluate_residuals(i, theta, t);
    if (!rr.ok) {
      out.ok = false;
      out.message = rr.message;
      return out;
    }
    const DenseMatrix J = rr.jacobian * chain.asDiagonal();
    if (base) (*base)[static_cast<std::size_t>(i)] = rr.residual;
    out.loss = rr.residual.squaredNorm();
    out.gradient.resize(n + n * n);
    out.gradient.head(n) = J.transpose() * rr.residual;
    Eigen::Map<DenseMatrix>(out.gradient.data() + n, n, n) = J.transpose() * J;
    return out;
  };
  NormalEquations ne;
  ne.batch = distributed ? evaluate_batch_distributed(samples, n + n * n, threads, f)
                         : evaluate_batch(samples, n + n * n, threads, f);
  if (ne.batch.evaluated == 0) return ne;
  const double inv = 1.0 / ne.batch.evaluated;
  ne.loss = ne.batch.loss * inv;
  ne.b = ne.batch.gradient.head(n) * inv;
  ne.A = Eigen::Map<const DenseMatrix>(ne.batch.gradient.data() + n, n, n) * inv;
  return ne;
}

// The mean of J̃ᵀ r_vv, the residuals' second directional derivative along v pulled back,
// by the finite difference of Transtrum & Sethna (2012, eq. 15) taken with the Jacobian at
// the displaced point ξ₀ + h v (so that no sample's Jacobian at ξ₀ has to be stored):
//   r(ξ₀ + hv) − r(ξ₀) − h J̃(ξ₀ + hv) v = −(h²/2) r_vv + O(h³),
// and J̃(ξ₀ + hv)ᵀ differs from J̃(ξ₀)ᵀ by O(h). Empty when a sample fails there or its
// residual changes length (the trial then goes on without acceleration).
Vector pulled_back_curvature(Objective& objective, ParameterSet& theta, const Vector& xi0, const Vector& v,
                             const std::vector<Index>& samples, int threads, bool distributed,
                             const std::vector<Vector>& base, long expected, LmIteration& it) {
  const Index n = theta.size();
  theta.set_free(xi0 + kGeodesicStep * v);
  objective.prepare(theta, resolve_threads(threads));
  const Vector chain = theta.chain_gradient(Vector::Ones(n));
  const SampleFunction f = [&](Index i, int t) {
    SampleResult out;
    const ResidualResult rr = objective.evaluate_residuals(i, theta, t);
    const Vector& r0 = base[static_cast<std::size_t>(i)];
    if (!rr.ok || rr.residual.size() != r0.size()) {
      out.ok = false;
      out.message = rr.ok ? "the residual changed length" : rr.message;
      return out;
    }
    const DenseMatrix J = rr.jacobian * chain.asDiagonal();
    out.gradient = J.transpose() * (rr.residual - r0 - kGeodesicStep * (J * v));
    return out;
  };
  const BatchResult r = distributed ? evaluate_batch_distributed(samples, n, threads, f)
                                    : evaluate_batch(samples, n, threads, f);
  theta.set_free(xi0);
  ++it.trials;
  it.evaluated += r.evaluated;
  it.failed += r.failed;
  if (r.failed > 0 && it.first_failure.empty()) it.first_failure = r.first_failure;
  if (r.evaluated != expected || !r.gradient.allFinite()) return {};
  return r.gradient * (-2.0 / (kGeodesicStep * kGeodesicStep * static_cast<double>(expected)));
}

}  // namespace

LmIteration lm_iteration(Objective& objective, ParameterSet& theta, const std::vector<Index>& samples, int threads,
                         bool distributed, Optimizer& optimizer) {
  LmIteration it;
  const bool geodesic = optimizer.settings().lm_geodesic_acceleration;
  std::vector<Vector> base;
  if (geodesic && !samples.empty()) base.resize(static_cast<std::size_t>(*std::max_element(samples.begin(), samples.end())) + 1);
  const NormalEquations ne = normal_equations(objective, theta, samples, threads, distributed, geodesic ? &base : nullptr);
  it.evaluated += ne.batch.evaluated;
  it.failed += ne.batch.failed;
  it.first_failure = ne.batch.first_failure;
  if (ne.batch.evaluated == 0 || !std::isfinite(ne.loss) || !ne.A.allFinite() || !ne.b.allFinite()) return it;

  const Index n = theta.size();
  const double max_diag = n > 0 ? ne.A.diagonal().maxCoeff() : 0.0;
  if (!(max_diag > 0.0)) return it;  // no parameter moves any residual
  // Marquardt's scaling; 1 on columns held fixed (A and b are 0 there, so δ is 0 too).
  const Vector D = ne.A.diagonal().cwiseMax(kScaleFloor * max_diag);

  double lambda = kInitialDamping * max_diag, nu = 2.0;
  optimizer.lm_damping(lambda, nu);
  const Vector xi0 = theta.free();
  for (int trial = 0; trial < kLmMaxTrials; ++trial) {
    DenseMatrix K = ne.A;
    K.diagonal() += lambda * D;
    const Eigen::LLT<DenseMatrix> llt(K);
    Vector delta = llt.info() == Eigen::Success ? Vector(llt.solve(-ne.b)) : Vector(Vector::Zero(n));
    const double longest_velocity = delta.lpNorm<Eigen::Infinity>();
    if (longest_velocity > kLmMaxFreeStep) delta *= kLmMaxFreeStep / longest_velocity;
    bool too_curved = false;
    if (geodesic && llt.info() == Eigen::Success && delta.allFinite()) {
      // Geodesic acceleration (Transtrum & Sethna 2012, §III): a = −(A + λD)⁻¹ J̃ᵀ r_vv, the
      // step v + a/2, taken only when 2‖a‖/‖v‖ ≤ kMaxAccelerationRatio in the metric D.
      const Vector rvv = pulled_back_curvature(objective, theta, xi0, delta, samples, threads, distributed, base,
                                               ne.batch.evaluated, it);
      if (rvv.size() == n) {
        const Vector a = llt.solve(-rvv);
        const double ratio = 2.0 * std::sqrt(a.dot(D.cwiseProduct(a)) / delta.dot(D.cwiseProduct(delta)));
        too_curved = !(ratio <= kMaxAccelerationRatio);
        delta += 0.5 * a;
      }
    }
    const double longest = delta.lpNorm<Eigen::Infinity>();
    if (longest > kLmMaxFreeStep) delta *= kLmMaxFreeStep / longest;
    const double predicted = -(2.0 * delta.dot(ne.b) + delta.dot(ne.A * delta));
    bool accept = false;
    double rho = 0.0;
    if (llt.info() == Eigen::Success && delta.allFinite() && predicted > 0.0 && !too_curved) {
      theta.set_free(xi0 + delta);
      const BatchResult r = evaluate_mean(objective, theta, samples, threads, distributed);
      ++it.trials;
      it.evaluated += r.evaluated;
      it.failed += r.failed;
      if (r.failed > 0 && it.first_failure.empty()) it.first_failure = r.first_failure;
      if (r.evaluated == ne.batch.evaluated && std::isfinite(r.loss)) {
        const double decrease = ne.loss - r.loss;
        rho = decrease / predicted;
        accept = rho > kAcceptRatio && decrease > kMinRelativeDecrease * std::abs(ne.loss);
      }
    }
    if (accept) {
      lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      nu = 2.0;
      lambda = std::max(lambda, 1e-300);
      optimizer.lm_set_damping(lambda, nu, true);
      it.accepted = true;
      return it;
    }
    theta.set_free(xi0);
    lambda *= nu;
    nu *= 2.0;
    if (!std::isfinite(lambda) || !std::isfinite(nu)) break;
  }
  // No decrease at any damping tried: θ stays; the damping restarts from its initial value.
  optimizer.lm_set_damping(kInitialDamping * max_diag, 2.0, false);
  return it;
}

}  // namespace lcprelax::learn::detail
