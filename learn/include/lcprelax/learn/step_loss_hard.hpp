#pragma once
// The hard loss of one island of one contact step (Belbute-Peres et al., "End-to-End
// Differentiable Physics for Learning and Control", NeurIPS 2018), sparse, for any scene:
//     ℓ = ‖v⁺(z) − v̄‖²   ((m/s)², no weighting between linear and angular components),
// z = [λn, β⁺, β⁻, γ] the solution of the island's Stewart–Trinkle LCP (M_lcp, q) of
// models/contact_step.hpp (stewart_trinkle_lcp: W = J M⁻¹ Jᵀ, J = [Jn; Jt], gap term
// max(φ, 0)/Δt), v⁺ = v* + M⁻¹(Jnᵀλn + Jtᵀλt), λt = β⁺ − β⁻, v̄ the observed next velocity.
//
// Solve: the sparse Lemke (lcp/lemke.hpp) with the lcp model's attempts, the simulator's
// (models/lcp_model_attempts.hpp; steps and caps in models/contact_step.hpp): the warm basis
// (if given), a crash path from it, perturbed q + δu (δ = kLcpPerturbation·‖q‖∞, u =
// lcp_perturbation_pattern(s, seed), keyed by ContactSystem::ids) polished on q, exact Lemke,
// M + εI polished on M, and last Lemke with the caller's settings (covering and M + εI
// retries). status: solved (the LCP's own solution), solved_inaccurate (the solution of the
// perturbed LCP q + δu or of M + εI: loss and gradient are those of that LCP with δu and ε
// held fixed), failed (no solution: loss NaN, the gradient zero and not meaningful).
//
// Gradient (reverse mode). With g = 2(v⁺ − v̄), a = M⁻¹g:
//   ∂ℓ/∂z through v⁺: ∂ℓ/∂λn = Jn a, ∂ℓ/∂β± = ±Jt a, ∂ℓ/∂γ = 0;
//   (∂ℓ/∂M_lcp, ∂ℓ/∂q) = LemkeSolver::backward(∂ℓ/∂z) (on the final basis);
//   G = ∂ℓ/∂W (J-space, (nc+nf)²): G_rc = Σ s_R s_C ∂ℓ/∂M_lcp(R, C) over the LCP entries
//     (R, C) that W_rc is copied to with signs s (normal → +, friction → β⁺ +, β⁻ −);
//   ∂ℓ/∂μ_f = ∂ℓ/∂M_lcp(γ_f, λn_c(f));  qn = Jn v* + max(φ,0)/Δt, qt = Jt v* with
//     ∂ℓ/∂qn = ∂ℓ/∂q(λn rows), ∂ℓ/∂qt = ∂ℓ/∂q(β⁺ rows) − ∂ℓ/∂q(β⁻ rows);
//   with D = M⁻¹ = diag(minv), dW = dJ D Jᵀ + J D dJᵀ + J dD Jᵀ:
//     ∂ℓ/∂J   = (G + Gᵀ) J D + [∂ℓ/∂qn; ∂ℓ/∂qt] v*ᵀ + [λn; λt] aᵀ        (on J's pattern)
//     ∂ℓ/∂D_k = (Jᵀ G J)_kk + g_k (Jᵀλ)_k
//     ∂ℓ/∂v*  = g + Jnᵀ ∂ℓ/∂qn + Jtᵀ ∂ℓ/∂qt
//     ∂ℓ/∂φ_c = ∂ℓ/∂qn_c / Δt where φ_c > 0, 0 where φ_c < 0 (a kink at φ = 0);
//   with the per-contact correction (world.hpp ContactLcpBlock) enabled, M_lcp and q hold
//   B and d on every contact's block, so ∂ℓ/∂B = Σ_c ∂ℓ/∂M_lcp[idx_c, idx_c] and
//   ∂ℓ/∂d = Σ_c ∂ℓ/∂q[idx_c] (the entries also enter G, ∂ℓ/∂μ and ∂ℓ/∂q as before).
// Where a wrong prior makes contacts stick the basis does not change with the data and
// the gradient w.r.t. μ is exactly zero (the known weakness of the hard loss). At a
// degenerate LCP solution the gradient is that of the final basis (a one-sided one).
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/learn/step_loss.hpp>

#include <string>
#include <vector>

namespace lcprelax::learn {

struct HardStepLossSettings {
  LemkeSettings lemke;  ///< settings of the last attempt (plain Lemke before it: no retries)
  /// Empty if valid, else a message naming the first bad field ("lemke: ...").
  std::string validation_error() const;
};

/// ℓ and ∂ℓ/∂data for island `s` (validated: throws InputError naming the field on sizes
/// or non-finite values), observed next velocity `target` (3 per island body), time step
/// dt (s, > 0). `warm_basis` (size nc + 3nf, else ignored) is tried first; the final basis
/// is written to `final_basis` when it is not null (warm start of the next evaluation).
/// `skip_exact_cold` and `warm_from_regularized` (the warm basis is that of an answer whose
/// `regularized` was set: step 1c first): run_lcp_model_attempts' options
/// (models/lcp_model_attempts.hpp), as the simulator passes them.
StepLossResult hard_step_loss(const ContactSystem& s, const Vector& target, double dt,
                              const HardStepLossSettings& settings = {}, const std::vector<bool>& warm_basis = {},
                              std::vector<bool>* final_basis = nullptr, bool skip_exact_cold = false,
                              bool warm_from_regularized = false);

/// Throws InputError naming the field unless `s`, `target` (3 per body) and dt (> 0) are
/// consistent and finite (shared by the step losses).
void validate_step_loss_input(const ContactSystem& s, const Vector& target, double dt);

}  // namespace lcprelax::learn
