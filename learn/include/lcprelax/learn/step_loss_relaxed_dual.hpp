#pragma once
// The relaxed loss of one island of one contact step in the DUAL form (the impulses z as
// the QP's only unknowns, the Delassus matrix W = J M⁻¹ Jᵀ formed): the former dense relaxed
// loss of `learn polygon` generalized to any island (learn polygon now uses the scene path's
// lifted relaxed loss, step_loss_relaxed.hpp, through polygon_objective.hpp). Parmar, Halm & Posa, "Fundamental Challenges
// in Deep Learning for Stiff Contact Dynamics", IROS 2021; learn/relaxed_lcp.hpp.
//
// Data: the island's ContactSystem s (models/contact_system.hpp), the observed next
// velocity v̄ (3 per island body: m/s, m/s, rad/s) and Δt (s). The LCP is the island's
// sparse Stewart–Trinkle LCP (M_lcp, q) = stewart_trinkle_lcp(s, delassus(s), Δt) in
// z = [λn (nc), β⁺, β⁻, γ (nf each)] with the prediction v⁺ = P z + p = v* + M⁻¹(Jnᵀλn +
// Jtᵀ(β⁺ − β⁻)) (stewart_trinkle_pullback.hpp). The loss is the optimal value
//     ℓ = min_{z̃} a1‖P S z̃ + p − v̄‖² + a2 z̃ᵀR(M_lcp S z̃ + q) + ((ε + δ)/2)‖z̃‖²
//         s.t.  R(M_lcp S z̃ + q) ≥ 0,  z̃ ≥ 0
// solved by RelaxedLcpSolver with the data (R M_lcp S, R q, P S, p, v̄); R = S below
// (the polygon's) unless RelaxedDualScaling::velocity.
// Scaling (velocity units, as the polygon): z = S z̃, S = diag(S_c on λn_c; S_c(f) on β±_f;
// 1 on γ_f), rows scaled by S as well, so z̃ ⊥ S(M S z̃ + q) is the same LCP and the
// complementarity term z̃ᵀS(MSz̃ + q) = zᵀ(Mz + q) is unchanged; only the regularization
// and shift (ε + δ)/2‖z̃‖² see S. Per contact c,
//     S_c = 1 / Σ_{dynamic bodies b of c} minv(3b)      (kg; the translational reduced mass)
// (the bodies are those with columns in Jn's row c; minv(3b) is body b's 1/m, its x entry).
// Why: an impulse λ at contact c changes the bodies' relative translational velocity by
// λ Σ_b 1/m_b = λ/S_c, so λ̃ = λ/S_c is that velocity change (m/s) whatever the masses, and
// ε‖z̃‖² weighs contacts between light and heavy bodies alike without pulling masses to 0.
// For one body on a static shape S_c = m: exactly the former polygon loss's S (on such
// islands the two agreed to 1e-10 relative in ℓ and ∂ℓ/∂θ until that loss was removed).
// S depends on the masses and is differentiated: ∂S_c/∂minv(3b) = −S_c² for b in c.
// Rows (RelaxedDualScaling): `energy` (default, the polygon's) scales the rows by S as
// well, Ms = S M S, so the complementarity term is zᵀ(Mz + q) in N·s·m/s = kg·(m/s)²: against
// a1‖v⁺ − v̄‖² ((m/s)²) its weight is effectively a2·S, i.e. it grows with the bodies' mass
// (a2 S = 0.17 for the polygon's 1.7 kg, 1 for the 10 kg squares of the learning pile).
// `velocity` scales the rows by R = (1 on λn and β± rows, 1/S_c(f) on γ rows), Ms = R M S:
// every row w̃ is a velocity (m/s) and z̃ᵀw̃ is in (m/s)², so a2 weighs it alike whatever
// the masses; the γ–λ̃n coupling becomes a2 μ (not a2 μ S) and the shift δ ≈ (a2 μ)²/H_nn.
// The same LCP either way (R, S > 0); for S = 1 (unit masses) the two coincide. The chain
// rule adds ∂ℓ/∂R_γf·(−1/S_c²) to ∂ℓ/∂S_c in velocity mode.
// Settings (the polygon's defaults): a1 = 1, a2 = 0.1, ε = 1e-6, NonconvexPolicy::shift.
// The Stewart–Trinkle M_lcp is not monotone (z̃ᵀSMSz̃ holds μ S_c γ λ̃n without a γ² term);
// the shift adds δI to the Hessian with the smallest δ = 10ᵏ·max(ε, 1e-8) that makes it PD
// (relaxed_lcp.hpp). In the dual form H_λλ = 2a1 SPᵀPS + a2 sym(RMS) carries W's
// curvature, so δ ≈ (coupling)²/H_nn is small where the normal directions are stiff; where an
// island has more contact rows than independent directions (redundant contacts) H_nn has
// directions with little curvature and δ grows. Measured (tests/learn_step_loss_relaxed_dual
// _test, μ = 0.3–0.5): energy δ = 1e-2 on the 1.7 kg polygon, 1 on 40 kg boxes and on 10 kg
// pile islands (80 and 625 contacts); velocity δ = 1e-3 (box), 1e-2 (two boxes), 0.1 (piles).
// δ does not depend on the data, so the envelope gradient (δ fixed) is exact except where
// a change of the data changes k (a kink of ℓ).
//
// Gradient: RelaxedLcpSolver's envelope-theorem ∂ℓ/∂(Ms, qs, Ps, p) (relaxed_lcp.hpp),
// then Ms = R M S, qs = R∘q, Ps = P S give ∂ℓ/∂M_ij = R_i S_j ∂ℓ/∂Ms_ij, ∂ℓ/∂q = R∘∂ℓ/∂qs,
// ∂ℓ/∂P = ∂ℓ/∂Ps S, ∂ℓ/∂S_j = Σ_i ∂ℓ/∂Ms_ij R_i M_ij + Σ_k ∂ℓ/∂Ps_kj P_kj and ∂ℓ/∂R_i =
// Σ_j ∂ℓ/∂Ms_ij M_ij S_j + q_i ∂ℓ/∂qs_i (R = S in energy mode); stewart_trinkle_pullback
// carries (M, q, P, p) to (Jn, Jt, φ, μ, M⁻¹, v*), and ∂ℓ/∂minv(3b) += −Σ_{c ∋ b} S_c² ∂ℓ/∂S_c
// (∂ℓ/∂S_c summed over λn_c and the β± of c's friction rows).
// Status: solved / solved_inaccurate as the QP's; failed (nonconvex beyond δ = 1e12·ε, or
// the QP failed): loss NaN, gradient zero, message set. v_next is P z + p at the QP's z.
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/learn/relaxed_lcp.hpp>
#include <lcprelax/learn/step_loss.hpp>

#include <memory>
#include <string>

namespace lcprelax::learn {

/// How the LCP's rows are scaled (header comment): `energy` (the polygon's: rows by S,
/// zᵀw in kg·(m/s)²) or `velocity` (γ rows by 1/S, z̃ᵀw̃ in (m/s)²).
enum class RelaxedDualScaling { energy, velocity };
const char* to_string(RelaxedDualScaling s);

struct RelaxedDualStepLossSettings {
  RelaxedDualScaling scaling = RelaxedDualScaling::energy;  ///< energy: the polygon's loss
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
