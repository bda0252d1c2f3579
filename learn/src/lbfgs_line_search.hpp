#pragma once
// One L-BFGS iteration of train() (trainer.hpp, optimizer.hpp): the quasi-Newton direction
// d = −H g at ξ₀ and a line search for a step α that satisfies the weak Wolfe conditions
//   C(ξ₀ + αd) ≤ C(ξ₀) + c₁ α gᵀd,   c₁ = 1e-4       (sufficient decrease, Armijo)
//   ∇C(ξ₀ + αd)ᵀd ≥ c₂ gᵀd,          c₂ = 0.9        (curvature)
// on the mean loss C over the training samples. The losses are only piecewise smooth (contact
// modes change at kinks); the weak Wolfe search by bracketing and bisection is what lets
// BFGS follow a kink to a minimum on it (Lewis & Overton, "Nonsmooth optimization via
// quasi-Newton methods", Math. Programming 141, 2013), where a backtracking Armijo search
// takes ever shorter steps across it and stalls. The curvature condition also guarantees
// sᵀy > 0, so the pair is stored. Trial steps:
// - the first trial is α = 1 (the BFGS step), or without stored pairs the step that moves the
//   largest free coordinate by the learning rate α_k (optimizer.hpp);
// - while Armijo holds and the curvature condition does not, α doubles; once a trial fails
//   Armijo, α bisects the bracket; before any trial has held Armijo it shrinks by the
//   safeguarded quadratic interpolation of Nocedal & Wright (2006, §3.5: the minimizer of the
//   quadratic through C(ξ₀), its slope and C(ξ₀ + αd), kept within [0.1α, 0.5α]);
// - no trial moves a free coordinate by more than kMaxFreeStep = 1 (a factor e on log
//   parameters such as μ or a mass, one class radius on a vertex); a trial at that longest
//   step that holds Armijo is accepted;
// - a trial counts only when every sample that evaluated at ξ₀ evaluates there too (the
//   mean is then over the same samples), and its loss is finite;
// - Armijo counts only with a decrease of more than 1e-14 relative (the jitter of
//   warm-started solves), so a search at the noise floor fails and ends the run.
// At most kMaxTrials = 30 trials. A Wolfe point leaves θ there and stores the pair (s, y) of
// the step and the gradient change (Optimizer::lbfgs_accept, which skips pairs without
// positive curvature); when the trials end without one, the Armijo point of lowest loss is
// taken the same way; without any, θ stays at ξ₀ and the stored pairs are dropped, so the
// next iteration starts from steepest descent. A direction that is not a descent direction
// (gᵀd ≥ 0, possible only through roundoff) is replaced by −g the same way.
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
