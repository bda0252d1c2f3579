#pragma once
// The relaxed loss of one island of one contact step in the DUAL form (the impulses z as
// the QP's only unknowns, the Delassus matrix W = J M⁻¹ Jᵀ formed): the polygon's relaxed
// loss (polygon_losses.hpp, "relaxed") generalized to any island, so that a polygon on the
// ground is one instance of the scene path. Parmar, Halm & Posa, "Fundamental Challenges
// in Deep Learning for Stiff Contact Dynamics", IROS 2021; learn/relaxed_lcp.hpp.
//
// Data: the island's ContactSystem s (models/contact_system.hpp), the observed next
// velocity v̄ (3 per island body: m/s, m/s, rad/s) and Δt (s). The LCP is the island's
// sparse Stewart–Trinkle LCP (M_lcp, q) = stewart_trinkle_lcp(s, delassus(s), Δt) in
// z = [λn (nc), β⁺, β⁻, γ (nf each)] with the prediction v⁺ = P z + p = v* + M⁻¹(Jnᵀλn +
// Jtᵀ(β⁺ − β⁻)) (stewart_trinkle_pullback.hpp). The loss is the optimal value
//     ℓ = min_{z̃} a1‖P S z̃ + p − v̄‖² + a2 z̃ᵀS(M_lcp S z̃ + q) + ((ε + δ)/2)‖z̃‖²
//         s.t.  S(M_lcp S z̃ + q) ≥ 0,  z̃ ≥ 0            ((m/s)²·weights)
// solved by RelaxedLcpSolver with the data (S M_lcp S, S q, P S, p, v̄).
// Scaling (velocity units, as the polygon): z = S z̃, S = diag(S_c on λn_c; S_c(f) on β±_f;
// 1 on γ_f), rows scaled by S as well, so z̃ ⊥ S(M S z̃ + q) is the same LCP and the
// complementarity term z̃ᵀS(MSz̃ + q) = zᵀ(Mz + q) is unchanged; only the regularization
// and shift (ε + δ)/2‖z̃‖² see S. Per contact c,
//     S_c = 1 / Σ_{dynamic bodies b of c} minv(3b)      (kg; the translational reduced mass)
// (the bodies are those with columns in Jn's row c; minv(3b) is body b's 1/m, its x entry).
// Why: an impulse λ at contact c changes the bodies' relative translational velocity by
// λ Σ_b 1/m_b = λ/S_c, so λ̃ = λ/S_c is that velocity change (m/s) whatever the masses, and
// ε‖z̃‖² weighs contacts between light and heavy bodies alike without pulling masses to 0.
// For one body on a static shape S_c = m: exactly the polygon's S, and on such an island
// this loss and its gradient equal polygon_relaxed_loss (tests/learn_step_loss_relaxed_dual_test).
// S depends on the masses and is differentiated: ∂S_c/∂minv(3b) = −S_c² for b in c.
// Settings (the polygon's defaults): a1 = 1, a2 = 0.1, ε = 1e-6, NonconvexPolicy::shift.
// The Stewart–Trinkle M_lcp is not monotone (z̃ᵀSMSz̃ holds μ S_c γ λ̃n without a γ² term);
// the shift adds δI to the Hessian with the smallest δ = 10ᵏ·max(ε, 1e-8) that makes it PD
// (relaxed_lcp.hpp). In the dual form H_λλ = 2a1 SPᵀPS + a2 S(M + Mᵀ)S carries W's
// curvature, so δ ≈ (a2 μ S_c)²/H_nn is small where the normal directions are stiff; where an
// island has more contact rows than independent directions (redundant contacts) H_nn has
// directions with only ε and δ grows towards a2 μ S (the numbers are in the test's output).
// δ does not depend on the data, so the envelope gradient (δ fixed) is exact except where
// a change of the data changes k (a kink of ℓ).
//
// Gradient: RelaxedLcpSolver's envelope-theorem ∂ℓ/∂(Ms, qs, Ps, p) (relaxed_lcp.hpp),
// then Ms = S M S, qs = S∘q, Ps = P S give ∂ℓ/∂M_ij = S_i S_j ∂ℓ/∂Ms_ij, ∂ℓ/∂q = S∘∂ℓ/∂qs,
// ∂ℓ/∂P = ∂ℓ/∂Ps S, and ∂ℓ/∂S_i = Σ_(i,j),(j,i) ∂ℓ/∂Ms·Ms / S_i + q_i ∂ℓ/∂qs_i + Σ_k
// ∂ℓ/∂Ps_ki P_ki; stewart_trinkle_pullback carries (M, q, P, p) to (Jn, Jt, φ, μ, M⁻¹, v*)
// and ∂ℓ/∂minv(3b) += −Σ_{c ∋ b} S_c² ∂ℓ/∂S_c (summed over λn_c and the β± of c's rows).
// Status: solved / solved_inaccurate as the QP's; failed (nonconvex beyond δ = 1e12·ε, or
// the QP failed): loss NaN, gradient zero, message set. v_next is P z + p at the QP's z.
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/learn/relaxed_lcp.hpp>
#include <lcprelax/learn/step_loss.hpp>

#include <memory>
#include <string>

namespace lcprelax::learn {

struct RelaxedDualStepLossSettings {
  RelaxedLcpSettings relaxed;  ///< constructor: nonconvex = shift, a2 = 0.1, ε = 1e-6 (the polygon's)
  QpSettings qp;               ///< interior point (automatic backend)
  RelaxedDualStepLossSettings();
  /// Empty if valid, else a message naming the first bad field ("relaxed: ...", "qp: ...";
  /// relaxed.max_dissipation must be none: an island has no maximum-dissipation data).
  std::string validation_error() const;
};

/// A per-thread workspace: keeps the RelaxedLcpSolver (its QP's symbolic analysis is reused
/// while the island's pattern repeats). Not thread-safe.
class RelaxedDualStepLossWorkspace {
 public:
  /// Throws InputError when settings.validation_error() is not empty.
  explicit RelaxedDualStepLossWorkspace(RelaxedDualStepLossSettings settings = {});
  ~RelaxedDualStepLossWorkspace();
  RelaxedDualStepLossWorkspace(RelaxedDualStepLossWorkspace&&) noexcept;
  RelaxedDualStepLossWorkspace& operator=(RelaxedDualStepLossWorkspace&&) noexcept;

  const RelaxedDualStepLossSettings& settings() const;
  /// ℓ, v⁺ and ∂ℓ/∂data for island s, observed next velocity `target` (3 per body), dt
  /// (s). Throws InputError naming the field on invalid data (validate_step_loss_input).
  StepLossResult evaluate(const ContactSystem& s, const Vector& target, double dt);
  /// The last evaluate()'s relaxed-LCP result (z̃ = lambda, shift δ, iterations, timings);
  /// empty before the first evaluation with contacts.
  const RelaxedLcpResult& last() const;
  /// The last evaluate()'s scaling S (one per LCP unknown, above).
  const Vector& scaling() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One-shot: a fresh workspace.
StepLossResult relaxed_dual_step_loss(const ContactSystem& s, const Vector& target, double dt,
                                      const RelaxedDualStepLossSettings& settings = {});

}  // namespace lcprelax::learn
