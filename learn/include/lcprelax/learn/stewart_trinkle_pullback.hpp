#pragma once
// The island's Stewart–Trinkle LCP as a function of its ContactSystem, its prediction map,
// and the reverse-mode chain rule from ∂ℓ/∂(M_lcp, q, P, p) to ∂ℓ/∂(Jn, Jt, φ, μ, M⁻¹, v*).
//
// LCP (models/contact_step.hpp, stewart_trinkle_lcp; Stewart & Trinkle 1996, Anitescu &
// Potra 1997): unknowns z = [λn (nc), β⁺ (nf), β⁻ (nf), γ (nf)], J = [Jn; Jt] (rows:
// contacts, then friction rows), D = M⁻¹ = diag(minv), W = J D Jᵀ, φ⁺ = max(φ, 0):
//     M_lcp = [ Wnn  Wnt −Wnt  0 ]      q = [ Jn v* + φ⁺/Δt ]
//             [ Wtn  Wtt −Wtt  E ]          [ Jt v*         ]
//             [−Wtn −Wtt  Wtt  E ]          [−Jt v*         ]
//             [ U   −E   −E    0 ]          [ 0             ]
// with E = I (nf × nf) and U_f,c = μ_f where c = friction_rows[f] (else 0). The prediction
// of the next velocity is linear in z:
//     v⁺ = P z + p,   P = D [Jnᵀ  Jtᵀ  −Jtᵀ  0]  (3·bodies × n, sparse),   p = v*.
// Units: z in N·s (λn, β±) and m/s (γ); v⁺ in m/s and rad/s.
//
// Pullback (stewart_trinkle_pullback): given any scalar ℓ's partials dM = ∂ℓ/∂M_lcp,
// dq = ∂ℓ/∂q, dP = ∂ℓ/∂P, dp = ∂ℓ/∂p, with
//   G = ∂ℓ/∂W ((nc+nf)², J-space): G_rc = Σ s_R s_C dM(R, C) over the LCP entries (R, C)
//     that W_rc is copied to, with signs s (normal → +, β⁺ → +, β⁻ → −);
//   ∂ℓ/∂μ_f = dM(γ_f, λn_c(f));  ∂ℓ/∂qn = dq(λn), ∂ℓ/∂qt = dq(β⁺) − dq(β⁻);
//   Q = ∂ℓ/∂(DJᵀ) read in J-space: Q_ik = dP(k, λn_i) for a normal row i, and
//     dP(k, β⁺_f) − dP(k, β⁻_f) for friction row f;
// the cotangent is (dW = dJ D Jᵀ + J D dJᵀ + J dD Jᵀ)
//     ∂ℓ/∂J_ik  = ((G + Gᵀ) J D)_ik + [∂ℓ/∂qn; ∂ℓ/∂qt]_i v*_k + Q_ik D_k     (on J's pattern)
//     ∂ℓ/∂D_k   = (Jᵀ G J)_kk + Σ_i Q_ik J_ik
//     ∂ℓ/∂v*    = dp + Jnᵀ ∂ℓ/∂qn + Jtᵀ ∂ℓ/∂qt
//     ∂ℓ/∂φ_c   = ∂ℓ/∂qn_c / Δt where φ_c > 0, 0 where φ_c ≤ 0 (a kink at φ = 0).
// Entries of dM at the constant positions (the ±1 blocks, zeros, U off the contact of the
// friction row) and of dP on γ's columns carry no data dependence and are ignored; dM and
// dP may have any sparsity pattern (entries off M_lcp's or P's pattern are used where the
// data enter, e.g. G off W's pattern). Cost O(nnz(dM) + nnz(dP)·log + nnz(G)·nnz(J)/rows).
// Used by the dual relaxed loss (step_loss_relaxed_dual.hpp); the hard loss's chain rule
// (step_loss_hard.hpp) is the special case dP = g zᵀ (on P's pattern), dp = g.
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/contact_system_gradient.hpp>
#include <lcprelax/sparse/types.hpp>

namespace lcprelax::learn {

/// v⁺ = P z + p of the island's Stewart–Trinkle LCP (above).
struct StewartTrinklePrediction {
  SparseMatrix P;  ///< 3·bodies × (nc + 3nf): D [Jnᵀ Jtᵀ −Jtᵀ 0], compressed, column-major
  Vector p;        ///< v*
};

/// P and p for island s (sizes as s's; no validation beyond what the products need).
StewartTrinklePrediction stewart_trinkle_prediction(const ContactSystem& s);

/// ∂ℓ/∂(Jn, Jt, φ, μ, M⁻¹, v*) from ∂ℓ/∂(M_lcp, q, P, p) (above). Shapes: dM n×n, dq n,
/// dP (3·bodies)×n, dp 3·bodies, n = nc + 3nf; throws InputError naming the argument when
/// a shape differs or dt is not finite and > 0. The result's Jn, Jt have s's patterns.
ContactSystemCotangent stewart_trinkle_pullback(const ContactSystem& s, double dt, const SparseMatrix& dM,
                                                const Vector& dq, const SparseMatrix& dP, const Vector& dp);

}  // namespace lcprelax::learn
