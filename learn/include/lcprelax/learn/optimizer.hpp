#pragma once
// Optimizers for the free parameters ξ (parameters.hpp).
//
//   sgd  (with momentum, the seeds' choice):  m ← β m + g,   ξ ← ξ − α_k m
//   adam (Kingma & Ba 2015):  m ← β1 m + (1−β1) g,  s ← β2 s + (1−β2) g²,
//                             ξ ← ξ − α_k m̂ / (√ŝ + ε),  m̂ = m/(1−β1ᵏ), ŝ = s/(1−β2ᵏ)
//   lbfgs (limited-memory BFGS, Nocedal & Wright, "Numerical Optimization", 2nd ed. 2006,
//         §7.2): direction d = −H g by the two-loop recursion (their Algorithm 7.4) over the
//         last `memory` accepted pairs sᵢ = ξᵢ₊₁ − ξᵢ, yᵢ = gᵢ₊₁ − gᵢ, with H₀ = (sᵀy/yᵀy)·I of
//         the newest pair (their eq. 7.20); a pair with sᵀy ≤ 1e-10·‖s‖‖y‖ is not stored, so
//         H stays positive definite on nonconvex or kinked losses. The step length along d
//         needs loss values, so lbfgs does not use step(): the trainer runs a backtracking
//         Armijo line search over the whole training set (trainer.hpp, lbfgs_line_search.hpp).
//         Deterministic, hence for full batches only.
//   lm   (Levenberg–Marquardt: Levenberg 1944, Marquardt 1963; damping update of Nielsen
//         1999, as in Madsen, Nielsen & Tingleff, "Methods for non-linear least squares
//         problems", 2004, §3.2): for least-squares losses only; the step solves
//         (A + λ diag(A))δ = −b on the Gauss–Newton model of least_squares.hpp. Its trial
//         evaluations are run by the trainer (learn/src/levenberg_marquardt.hpp); the
//         optimizer keeps the damping λ and its growth factor ν (state: m = (λ, ν)).
// Learning-rate schedule α_k = α / (1 + decay·k), k = steps taken so far (lbfgs: the
// first trial step of a line search without stored pairs moves the largest free
// coordinate by α_k).
// Gradient clipping: g is scaled by clip_norm/‖g‖₂ where ‖g‖₂ > clip_norm.
// A non-finite gradient throws std::runtime_error instead of poisoning ξ.
// state()/restore() expose the moments (lbfgs: the stored pairs, S in m and Y in s, each
// the pairs' vectors one after another, oldest first) and the step count for checkpoints (checkpoint.hpp):
// an optimizer restored from another's state continues bit for bit as that one would.
#include <lcprelax/sparse/types.hpp>

#include <limits>
#include <string>

namespace lcprelax::learn {

enum class OptimizerKind { sgd, adam, lbfgs, lm };
const char* to_string(OptimizerKind k);
/// "sgd", "adam", "lbfgs" or "lm"; throws InputError otherwise.
OptimizerKind parse_optimizer_kind(const std::string& s);

struct OptimizerSettings {
  OptimizerKind kind = OptimizerKind::sgd;
  double learning_rate = 1e-2;  ///< α > 0
  double momentum = 0.9;        ///< β ∈ [0, 1), sgd
  double beta1 = 0.9;           ///< adam, ∈ [0, 1)
  double beta2 = 0.999;         ///< adam, ∈ [0, 1)
  double epsilon = 1e-8;        ///< adam, > 0
  double decay = 0.0;           ///< schedule α/(1 + decay·k), ≥ 0
  double clip_norm = std::numeric_limits<double>::infinity();  ///< > 0 (sgd, adam)
  int memory = 10;              ///< lbfgs: (s, y) pairs kept, ≥ 1
  /// lm: add the geodesic acceleration to each trial step (Transtrum & Sethna 2012; one
  /// more residual and Jacobian evaluation of the training set per trial,
  /// learn/src/levenberg_marquardt.hpp).
  bool lm_geodesic_acceleration = false;
  /// Empty if valid, else a message naming the first bad field.
  std::string validation_error() const;
};

/// Everything an Optimizer carries between steps: the first moment m (sgd: the momentum
/// buffer), the second moment s (adam; zeros for sgd) and the number of steps taken. m and
/// s are empty before the first step.
struct OptimizerState {
  Vector m, s;
  long steps = 0;
};

class Optimizer {
 public:
  /// Throws InputError on invalid settings.
  explicit Optimizer(const OptimizerSettings& settings = {});
  /// One update of ξ by the gradient ∂ℓ/∂ξ (sizes must match; state is sized on first use).
  /// sgd and adam only (lbfgs throws std::logic_error: its steps need a line search).
  void step(Vector& xi, const Vector& gradient);
  /// lbfgs: −H g by the two-loop recursion over the stored pairs (−g without pairs).
  Vector lbfgs_direction(const Vector& gradient) const;
  /// lbfgs: counts an accepted step and stores the pair (s, y) unless sᵀy ≤ 1e-10‖s‖‖y‖
  /// (then returns false); the oldest pair goes once `memory` are stored.
  bool lbfgs_accept(const Vector& s, const Vector& y);
  /// lbfgs: forgets the stored pairs (after a failed line search).
  void lbfgs_forget();
  /// lbfgs: pairs stored.
  int lbfgs_pairs() const;
  /// lm: the stored damping λ and growth factor ν; false before the first iteration.
  bool lm_damping(double& lambda, double& nu) const;
  /// lm: stores λ > 0 and ν ≥ 2; an accepted step is counted.
  void lm_set_damping(double lambda, double nu, bool accepted);
  void reset();
  OptimizerState state() const { return {m_, s_, steps_}; }
  /// Continues from `state` (of an optimizer with the same settings); throws InputError if
  /// m and s differ in size, steps < 0, or a moment is not finite.
  void restore(const OptimizerState& state);
  long steps() const { return steps_; }
  double learning_rate() const;  ///< α_k for the next step
  const OptimizerSettings& settings() const { return settings_; }

 private:
  OptimizerSettings settings_;
  Vector m_, s_;
  long steps_ = 0;
  /// lbfgs: length of one stored vector (set by the first pair, or after restore() by the
  /// first gradient; 0 while unknown).
  mutable Index pair_size_ = 0;
};

}  // namespace lcprelax::learn
