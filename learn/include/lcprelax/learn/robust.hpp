#pragma once
// A robust per-sample loss: each sample's loss ℓᵢ ≥ 0 enters training as ρ(ℓᵢ).
//
// RobustObjective wraps an objective and replaces every sample's loss by Cauchy's
// (Lorentzian) robustifier of scale c > 0, in the units of ℓ:
//   ρ(ℓ) = c·log(1 + ℓ/c),   ρ'(ℓ) = 1/(1 + ℓ/c)
// (Black & Rangarajan, "On the unification of line processes, outlier rejection, and
// robust statistics", IJCV 19, 1996; Triggs, McLauchlan, Hartley & Fitzgibbon, "Bundle
// adjustment — a modern synthesis", 2000, §3.3). ρ is increasing, ρ(0) = 0, ρ(ℓ) ≈ ℓ for
// ℓ ≪ c: a θ at which every sample's loss vanishes stays a global minimizer, and samples
// with ℓ ≲ c are weighted as before. A sample whose loss is far above c (a transition in
// which a wrong geometry changes which features touch, so that the contact normal jumps
// and the loss spikes) pulls with weight ρ'(ℓ) ≈ c/ℓ, so one such sample cannot dominate the
// mean and trap the parameters on the far side of its spike. c = 0 turns the wrapper off
// (ρ(ℓ) = ℓ, bitwise the wrapped objective).
//   gradient:   ρ'(ℓᵢ) ∂ℓᵢ/∂θ
//   residuals:  r̃ᵢ = g(sᵢ) rᵢ with s = ‖r‖², g(s) = √(ρ(s)/s), so ‖r̃ᵢ‖² = ρ(sᵢ) exactly;
//               J̃ᵢ = g Jᵢ + 2g'(s) rᵢ (rᵢᵀ Jᵢ), so that 2J̃ᵀr̃ = ρ'(s)·2Jᵀr (the exact
//               gradient; a least-squares optimizer sees a consistent model).
// g is evaluated by its series 1 − s/(4c) + … for s < 1e-6·c (no cancellation).
#include <lcprelax/learn/trainer.hpp>

namespace lcprelax::learn {

class RobustObjective : public Objective {
 public:
  /// c ≥ 0 and finite (InputError otherwise, naming the scale). `base` must outlive the wrapper.
  RobustObjective(Objective& base, double scale);

  Index num_samples() const override { return base_.num_samples(); }
  void prepare(const ParameterSet& theta, int threads) override { base_.prepare(theta, threads); }
  SampleResult evaluate(Index sample, const ParameterSet& theta, int thread) override;
  void save_state(StateWriter& out) const override { base_.save_state(out); }
  void load_state(StateReader& in) override { base_.load_state(in); }
  std::string residuals_unavailable() const override { return base_.residuals_unavailable(); }
  ResidualResult evaluate_residuals(Index sample, const ParameterSet& theta, int thread) override;

  double scale() const { return scale_; }

 private:
  Objective& base_;
  double scale_;
};

/// ρ(ℓ) = c log(1 + ℓ/c) (ℓ for c = 0) and its derivative: the functions RobustObjective applies.
double cauchy_robust_loss(double loss, double scale);
double cauchy_robust_weight(double loss, double scale);

}  // namespace lcprelax::learn
