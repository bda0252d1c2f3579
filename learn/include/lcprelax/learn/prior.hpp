#pragma once
// A Gaussian prior on the free parameters: maximum a posteriori training.
//
// PriorObjective wraps an objective and adds w‖ξ(θ) − ξ_c‖² to every sample's loss, where
// ξ are the free coordinates of parameters.hpp (log θ for μ, masses and inertias; θ/s for
// lengths in units of their class radius, angles) and ξ_c their values when the wrapper is
// built (the initial guess). Since every sample carries it, the mean loss over any set of
// samples carries it exactly once. Held parameters (learn = false) contribute nothing.
//   loss:       ℓᵢ + w Σ_k (ξ_k − ξ_c,k)²                      (dimensionless ξ, w ≥ 0)
//   gradient:   ∂ℓᵢ/∂θ_k + 2w (ξ_k − ξ_c,k) dξ_k/dθ_k          (dξ/dθ = 1/θ or 1/s)
//   residuals:  rᵢ followed by √w (ξ − ξ_c), Jacobian rows √w diag(dξ/dθ)
// so a least-squares optimizer (Levenberg–Marquardt) sees the prior as data: Tikhonov
// regularization of the Gauss–Newton problem. Its use: parameters that the data identify
// only weakly (the common scale of the masses, seen only through the pushes) can run off
// to where the model stops depending on them — "parameter evaporation" (Transtrum, Machta &
// Sethna, "Geometry of nonlinear least squares with applications to sloppy models and
// optimization", Phys. Rev. E 83, 2011, §VII, where a prior is the remedy). The minimizer
// is biased towards ξ_c by O(w / curvature); a second run without the prior, started from
// the first one's result (`--init-from`), removes the bias (docs/cli.md).
#include <lcprelax/learn/trainer.hpp>

namespace lcprelax::learn {

class PriorObjective : public Objective {
 public:
  /// Centre ξ_c = center.free(); w ≥ 0 and finite (InputError otherwise). `base` must
  /// outlive the wrapper.
  PriorObjective(Objective& base, const ParameterSet& center, double weight);

  Index num_samples() const override { return base_.num_samples(); }
  /// Throws InputError when θ and the centre differ in size (train() calls it first).
  void prepare(const ParameterSet& theta, int threads) override;
  SampleResult evaluate(Index sample, const ParameterSet& theta, int thread) override;
  void save_state(StateWriter& out) const override { base_.save_state(out); }
  void load_state(StateReader& in) override { base_.load_state(in); }
  std::string residuals_unavailable() const override { return base_.residuals_unavailable(); }
  ResidualResult evaluate_residuals(Index sample, const ParameterSet& theta, int thread) override;

  double weight() const { return weight_; }

 private:
  // ξ − ξ_c (0 where held) and dξ/dθ (0 where held) at θ.
  void deviation(const ParameterSet& theta, Vector& d, Vector& dxi_dtheta) const;

  Objective& base_;
  Vector center_;
  double weight_;
};

}  // namespace lcprelax::learn
