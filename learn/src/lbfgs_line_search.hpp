#pragma once
// One L-BFGS iteration of train() (trainer.hpp, optimizer.hpp): the quasi-Newton direction
// d = −H g at ξ₀ and a backtracking line search for the Armijo condition
//   C(ξ₀ + αd) ≤ C(ξ₀) + c₁ α gᵀd,   c₁ = 1e-4
// on the mean loss C over the training samples (Nocedal & Wright, "Numerical Optimization",
// 2nd ed. 2006, Algorithm 3.1 with the safeguarded quadratic interpolation of §3.5: the next
// trial α is the minimizer of the quadratic through C(ξ₀), its slope and C(ξ₀ + αd), kept
// within [0.1α, 0.5α]). Trial steps:
// - the first trial is α = 1 (the BFGS step), or without stored pairs the step that moves the
//   largest free coordinate by the learning rate α_k (optimizer.hpp);
// - no trial moves a free coordinate by more than kMaxFreeStep = 1 (a factor e on log
//   parameters such as μ or a mass, one class radius on a vertex): the losses are only
//   piecewise smooth, and a long step across many contact-mode changes is wasted work;
// - a trial counts only when every sample that evaluated at ξ₀ evaluates there too (the
//   mean is then over the same samples), and its loss is finite;
// - it is accepted only if it also lowers the loss by more than 1e-14 relative (the
//   jitter of warm-started solves), so a search at the noise floor fails and ends the run.
// At most kMaxTrials = 30 trials. An accepted trial leaves θ there and stores the pair
// (s, y) of the step and the gradient change (Optimizer::lbfgs_accept); when no trial is
// accepted θ stays at ξ₀ and the stored pairs are dropped, so the next iteration starts
// from steepest descent. A direction that is not a descent direction (gᵀd ≥ 0, possible
// only through roundoff) is replaced by −g the same way.
#include <lcprelax/learn/optimizer.hpp>
#include <lcprelax/learn/parameters.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <vector>

namespace lcprelax::learn::detail {

struct LbfgsIteration {
  bool accepted = false;   ///< θ moved
  bool steepest = false;   ///< the direction was −g (no stored pairs, or a non-descent d replaced)
  int trials = 0;          ///< loss + gradient evaluations of the training set made
  long evaluated = 0;      ///< sample evaluations over all trials
  int failed = 0;          ///< failed sample evaluations over all trials
  std::string first_failure;
};

/// One iteration from θ, whose mean loss over `samples` is `loss` with `evaluated` samples
/// evaluated and gradient `gradient` (w.r.t. the free parameters ξ).
LbfgsIteration lbfgs_iteration(Objective& objective, ParameterSet& theta, const std::vector<Index>& samples,
                               int threads, bool distributed, Optimizer& optimizer, double loss, long evaluated,
                               const Vector& gradient);

}  // namespace lcprelax::learn::detail
