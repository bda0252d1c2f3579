// One L-BFGS iteration with a weak Wolfe line search (lbfgs_line_search.hpp).
#include "lbfgs_line_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcprelax::learn::detail {
namespace {
constexpr double kArmijo = 1e-4;      // c₁ of the sufficient-decrease condition
constexpr double kMaxFreeStep = 1.0;  // largest change of one free coordinate per trial
constexpr double kWolfe = 0.9;       // c₂ of the weak Wolfe curvature condition
constexpr double kExpand = 2.0;      // growth of α while Armijo holds and Wolfe does not
constexpr int kMaxTrials = 30;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
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
  const double alpha_max = kMaxFreeStep / d_max;
  double alpha = std::min(optimizer.lbfgs_pairs() > 0 ? 1.0 : optimizer.learning_rate() / d_max, alpha_max);
  double lo = 0.0, hi = kInfinity;  // the bracket: Armijo holds at lo (or lo = 0), fails at hi
  double best_loss = loss;          // the lowest Armijo point so far, kept if the search ends
  Vector best_xi, best_g;
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
      if (g1.dot(d) >= kWolfe * slope || alpha >= alpha_max) {  // weak Wolfe (or the longest step)
        optimizer.lbfgs_accept(theta.free() - xi0, g1 - gradient);
        out.accepted = true;
        return out;
      }
      if (r.loss < best_loss) {
        best_loss = r.loss;
        best_xi = theta.free();
        best_g = g1;
      }
      lo = alpha;  // still steeply descending: longer
    } else {
      hi = alpha;  // too long (or not comparable): shorter
    }
    if (hi == kInfinity) {
      alpha = std::min(kExpand * alpha, alpha_max);
    } else if (lo > 0.0) {
      alpha = 0.5 * (lo + hi);  // bisection, robust at kinks (Lewis & Overton 2013)
    } else {
      // Minimizer of the quadratic through (0, loss), slope and (α, C(α)); halve without C(α).
      double next = kShrinkMax * alpha;
      if (comparable) {
        const double curvature = r.loss - loss - slope * alpha;
        if (curvature > 0.0) next = -slope * alpha * alpha / (2.0 * curvature);
      }
      alpha = std::clamp(next, kShrinkMin * alpha, kShrinkMax * alpha);
    }
  }
  if (best_xi.size() > 0) {  // no Wolfe point within the trials: keep the best decrease
    theta.set_free(best_xi);
    optimizer.lbfgs_accept(best_xi - xi0, best_g - gradient);
    out.accepted = true;
    return out;
  }
  theta.set_free(xi0);
  optimizer.lbfgs_forget();
  return out;
}

}  // namespace lcprelax::learn::detail
