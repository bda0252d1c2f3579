#pragma once
// The convex loss of one island of one contact step (step_loss.hpp), posed sparse.
//
// Data (models/contact_system.hpp): J = [Jn; Jt] (rows: contacts, then friction rows),
// D = M⁻¹ = diag(minv), gaps φ (m), μ per friction row, free velocity v* and the observed
// next velocity v̄ (3 per island body: m/s, m/s, rad/s), Δt (s). Impulses λ = (λn, λt) in N·s.
//
// Model: the two-phase convex model of models/contact_step.hpp (solve_convex_model) with an
// L2 deviation penalty of weight w ≥ 0 in phase 2's objective (and in phase 1's too with
// phase1_deviation, the seeds' formulation): (w/2)‖v⁺(λ) − v̄‖²_M
// with v⁺ = v* + DJᵀλ adds (w/2)λᵀWλ + wλᵀJ(v* − v̄) (+ const), W = J D Jᵀ. With
// c = (1 + w)v* − w v̄ and bn = Jn v* + max(φ, 0)/Δt (phase 1: w₁ = w with
// phase1_deviation, else 0, in place of w):
//   1. min_{λn ≥ 0} ½(1+w₁)λnᵀWnn λn + λnᵀ(Jn c₁ + max(φ,0)/Δt)   s.t. Wnn λn + bn ≥ 0
//   2. κ = eᵀmax(λn¹, 0);
//      min ½(1+w)λᵀWλ + ρ Σ_i exp(φ_i) Wnn_ii λn_i² + λᵀJc   (softening exp_phi; the
//      other methods of ConvexStepLossSettings::softening replace the ρ term by
//      ½ Σ_i g(φ_i) Wnn_ii λn_i² − λnᵀ v_ref, and phase 1's λn term gets −max(v_ref, 0),
//      models/normal_softening.hpp)
//      s.t. Wn λ + bn ≥ 0,  λn ≥ 0,  eᵀλn ≤ κ(1 + s) + 1e-12 N·s,  |λt_f| ≤ μ_f λn_(row f)
//   with s = 1e-6, else 1e-4, then 1e-2 where phase 2 fails (as models/src/convex_model.cpp).
//   Phase 1's row Wnn λn + bn ≥ 0 is posed only for w > 0 (else κ can leave phase 2
//   infeasible); with w = 0 it is implied by optimality, and posing it would make it weakly
//   active wherever λn > 0. With w = 0 this is exactly solve_convex_model.
//   Loss ℓ = ‖v⁺(λ²) − v̄‖² ((m/s)²), v⁺ = v* + DJᵀλ². Where no contact approaches in
//   either of phase 1's terms (bn ≥ 0 and Jn c + max(φ,0)/Δt ≥ 0) λ = 0 exactly (phase 1's
//   optimum is 0, so κ = 0) and ℓ = ‖v* − v̄‖², answered without a solve.
//
// Formulations (ConvexFormulation, as models/convex_phase_qp.hpp):
//   dual:   x = λ; Hessians (1+w)W (+ the ρ diagonal); non-penetration rows Wn λ ≥ −bn.
//   lifted: x = (Δv, λ) with the equality M Δv − Jᵀλ = 0; ½(1+w)λᵀWλ = ½(1+w)ΔvᵀMΔv and
//           the non-penetration rows are Jn Δv ≥ −bn, so W is never formed: the KKT matrix
//           holds only M and J (the form for islands of thousands of contacts).
//   automatic: lifted from kLiftedMinContacts contacts on. Both give the same ℓ and
//   gradient to the QP tolerance.
//
// Gradient (reverse mode, chained by hand): g = 2(v⁺ − v̄); ∂ℓ/∂λ² = JDg; phase 2's adjoint
// by QpSolver::backward (OptNet: Amos & Kolter 2017, ICML), reusing its final factorization,
// gives ∂ℓ/∂(P, q, A, G, l, u); ∂ℓ/∂κ = (1 + s)·∂ℓ/∂u_κ, and ∂ℓ/∂λn¹_i = ∂ℓ/∂κ where
// λn¹_i > 0; phase 1's adjoint likewise. The QP data's cotangents are then pulled back to
// the island data: W = JDJᵀ gives ∂ℓ/∂J += 2 W̄ₛ J D and ∂ℓ/∂D_k += (Jᵀ W̄ₛ J)_kk (W̄ₛ the
// symmetric part of ∂ℓ/∂W); the softening gives ∂ℓ/∂φ_i += P̄_ii·g′(φ_i)Wnn_ii and
// ∂ℓ/∂Wnn_ii += P̄_ii·g(φ_i) (exp_phi: g = g′ = 2ρ exp(φ_i)), and through v_ref
// ∂ℓ/∂φ_i −= q̄_i ∂v_ref/∂φ, ∂ℓ/∂(Jn v*)_i −= q̄_i ∂v_ref/∂vn (q̄ of each phase's λn
// term); M = diag(1/minv) gives ∂ℓ/∂minv_k = −M̄_kk/minv_k²;
// max(φ, 0)/Δt gives 1/Δt where φ > 0 (0 else: a kink at φ = 0). Where the solution is
// degenerate (a weakly active constraint, a non-unique λ) the derivative is that of the
// interior point's final iterate (qp_solver.hpp); where an adjoint residual exceeds 1e-6
// the result is marked solved_inaccurate and its message says so.
//
// Status: solved when both phases reach the QP tolerance; solved_inaccurate when a phase
// stalled within 1e3·eps or the adjoint residual is large; failed (message names the
// phase) when a phase has no solution: loss is then NaN and the gradient zero.
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/learn/step_loss.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>

#include <string>

namespace lcprelax::learn {

struct ConvexStepLossSettings {
  QpSettings qp;                 ///< both phases (QpSettings' defaults)
  double rho = 1e-3;             ///< ρ of the softening term (contact_step.hpp), ≥ 0
  /// The normal softening (models/normal_softening.hpp); exp_phi is the ρ term above.
  NormalSofteningSettings softening;
  double deviation = 1.0;        ///< w of the deviation penalty, ≥ 0
  /// Whether phase 1 carries the deviation penalty too (the default, the seeds' and the
  /// polygon's formulation). With it,
  /// κ = eᵀλn¹ moves towards the observed v̄ although phase 1 has no friction, so on data of
  /// the convex model itself ℓ ≠ 0 at the true parameters (measured on a 30-body pile: mean
  /// 0.049 (m/s)² with w = 1, r = 0; 1.3e-12 with w = 0). With false, phase 1 is the
  /// simulator's (w = 0) and only phase 2 is pulled towards v̄: at the truth its optimum is v̄
  /// itself, so the penalty vanishes there (with phase1_regularization = 0; measured 5.7e-13,
  /// 7e-8 with r = 1e-6, 0.056 with r = 1e-3). Not the default: on the settled-pile
  /// gradient checks its adjoint agrees with central differences to 4.5e-5 only (phase 1
  /// without the penalty's curvature is nearly singular), against 1e-6 with it.
  bool phase1_deviation = true;
  ConvexFormulation formulation = ConvexFormulation::automatic;
  /// r ≥ 0: phase 1 gets (r/2) Σ Wnn_ii λn_i² (the phase-2 softening's form without exp(φ)).
  /// Where an island has more active contacts than degrees of freedom (any settled 2-D pile),
  /// Wnn is singular, phase 1's λn and with it κ = eᵀλn are not unique, and the adjoint
  /// through the interior point's particular solution differs from central differences by
  /// ~1e-3 (measured on a 96-contact, 20-body pile step, tests/learn_scene_gradient_test).
  /// r makes phase 1 strictly convex and its solution unique: with r = 1e-3 (= ρ) the
  /// gradient agrees with central differences to 1e-5. r = 0 is the simulator's model
  /// exactly (solve_convex_model); r > 0 moves v⁺ by O(r) of the normal impulses.
  double phase1_regularization = 1e-3;
  /// Phase 2 puts no normal impulse on an open contact (φ > 0) that phase 1's answer leaves
  /// open (SimulatorSettings::convex_release_open_contacts, models/convex_phase_qp.hpp). Which
  /// contacts are released is decided from the forward solve and held fixed in the gradient
  /// (a bound λn_i ≤ 0 of phase 2, constant in the data), like an active set.
  bool release_open_contacts = false;

  /// Empty when valid, else a message naming the first bad field ("rho: must be ...").
  std::string validation_error() const;
};

/// Seconds spent in the last call (phases of convex_step_loss).
struct ConvexStepLossTimes {
  double assembly = 0.0, solve = 0.0, backward = 0.0;
};

/// The convex loss of island `s` for the observed next velocity `target` (s.num_dofs()
/// entries) and time step `dt` (s, > 0), with its gradient ∂ℓ/∂(Jn, Jt, φ, μ, M⁻¹, v*).
/// Throws InputError naming the field for invalid settings, inconsistent sizes of `s`,
/// non-finite data, minv ≤ 0, or a bad `target` or `dt`. `times` (optional) receives the
/// seconds of this call.
StepLossResult convex_step_loss(const ContactSystem& s, const Vector& target, double dt,
                                const ConvexStepLossSettings& settings, ConvexStepLossTimes* times = nullptr);

/// The same solve with ∂v⁺/∂(island data) row by row (step_loss.hpp, StepJacobianResult):
/// one backward pass per dof through both phases' final factorizations (the loss's gradient
/// is the row combination with weights 2(v⁺ − v̄)). For Gauss–Newton training, where the
/// prediction's Jacobian, not only the loss's gradient, is needed. Same errors and statuses
/// as convex_step_loss (solved_inaccurate where any row's adjoint residual exceeds 1e-6).
StepJacobianResult convex_step_jacobian(const ContactSystem& s, const Vector& target, double dt,
                                        const ConvexStepLossSettings& settings);

}  // namespace lcprelax::learn
