// One L-BFGS iteration with a backtracking Armijo line search (lbfgs_line_search.hpp).
#include "lbfgs_line_search.hpp"

#include <algorithm>
#include <cmath>

namespace lcprelax::learn::detail {
namespace {
constexpr double kArmijo = 1e-4;      // c₁ of the sufficient-decrease condition
constexpr double kMaxFreeStep = 1.0;  // largest change of one free coordinate per trial
constexpr int kMaxTrials = 30;
constexpr double kRoundoff = 1e-14;   // relative decrease taken as loss jitter, not progress
constexpr double kShrinkMin = 0.1, kShrinkMax = 0.5;  // safeguard of the interpolated α
}  // namespace

LbfgsIteration lbfgs_iteration(Objective& objective, ParameterSet& theta, const std::vector<Index>& samples,
                               int threads, bool distributed, Optimizer& optimizer, double loss, long evaluated,
                               const Vector& gradient) {
  LbfgsIteration out;
  const Vector xi0 = theta.free();
  Vector d = optimizer.lbfgs_direction(gradient);
  double slope = gradient.dot(d);
  out.steepest = optimizer.lbfgs_pairs() == 0;
  if (!(slope < 0.0)) {
    out.steepest = true;
    optimizer.lbfgs_forget();
    d = -gradient;
    slope = -gradient.squaredNorm();
  }
  const double d_max = d.size() ? d.lpNorm<Eigen::Infinity>() : 0.0;
  if (!(slope < 0.0) || !(d_max > 0.0) || !std::isfinite(slope)) return out;  // zero gradient: nothing to do
  double alpha = optimizer.lbfgs_pairs() > 0 ? 1.0 : optimizer.learning_rate() / d_max;
  alpha = std::min(alpha, kMaxFreeStep / d_max);
  for (int trial = 0; trial < kMaxTrials; ++trial) {
    theta.set_free(xi0 + alpha * d);
    const BatchResult r = evaluate_mean(objective, theta, samples, threads, distributed);
    ++out.trials;
    out.evaluated += r.evaluated;
    out.failed += r.failed;
    if (r.failed > 0 && out.first_failure.empty()) out.first_failure = r.first_failure;
    const bool comparable = r.evaluated == evaluated && std::isfinite(r.loss) && r.gradient.allFinite();
    // Armijo, and a decrease above the loss's roundoff (warm-started solves make the loss
    // jitter by a few ulps between evaluations at one θ; a "decrease" within that jitter
    // would let a stalled search creep on forever).
    if (comparable && r.loss <= loss + kArmijo * alpha * slope && loss - r.loss > kRoundoff * std::abs(loss)) {
      const Vector g1 = theta.chain_gradient(r.gradient);
      optimizer.lbfgs_accept(theta.free() - xi0, g1 - gradient);
      out.accepted = true;
      return out;
    }
    // Minimizer of the quadratic through (0, loss), slope and (α, C(α)); halve without C(α).
    double next = kShrinkMax * alpha;
    if (comparable) {
      const double curvature = r.loss - loss - slope * alpha;
      if (curvature > 0.0) next = -slope * alpha * alpha / (2.0 * curvature);
    }
    alpha = std::clamp(next, kShrinkMin * alpha, kShrinkMax * alpha);
  }
  theta.set_free(xi0);
  optimizer.lbfgs_forget();
  return out;
}

}  // namespace lcprelax::learn::detail
