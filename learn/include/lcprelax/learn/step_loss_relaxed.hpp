#pragma once
// The relaxed loss of one island of one contact step (Parmar, Halm & Posa, "Fundamental
// Challenges in Deep Learning for Stiff Contact Dynamics", IROS 2021; learn/relaxed_lcp.hpp),
// sparse, for any scene, posed LIFTED so that the Delassus matrix W = J M⁻¹ Jᵀ is never
// formed: the KKT matrix holds only M, Jn, Jt (CHOLMOD on islands of hundreds of contacts).
//
// The LCP is the island's Stewart–Trinkle LCP (models/contact_step.hpp) in
// z = [λn (nc), β⁺, β⁻, γ (nf each)], with v⁺ = v* + Δv and M Δv = Jnᵀλn + Jtᵀ(β⁺ − β⁻):
//     w = ( Jn v⁺ + φ⁺/Δt,  Jt v⁺ + γ,  −Jt v⁺ + γ,  μ∘λn(f) − β⁺ − β⁻ ),   φ⁺ = max(φ, 0),
// (with a pair's normal softness, contact_system.hpp: φ⁺ → max(φ, 0) + e∘min(φ, 0) and
// w_n += c∘λn, which adds a2 cᵀλn² to zᵀw, 2 a2 c S² to λ̃n's Hessian diagonal and c S to
// the normal row of G; ∂ℓ/∂c = (a2 S λ̃n + z_n) S λ̃n, ∂ℓ/∂e = (a2 S λ̃n + z_n) min(φ, 0)/Δt,
// ∂ℓ/∂φ = e (a2 S λ̃n + z_n)/Δt where φ < 0; ∂ℓ/∂S gains (2 a2 S λ̃n + z_n) c λ̃n),
// where λn(f) is the normal impulse of friction row f's contact. Its complementarity term,
// with λt = β⁺ − β⁻ (the β±γ products cancel) and Jnᵀλn + Jtᵀλt = M Δv, is
//     zᵀw = (Jnᵀλn + Jtᵀλt)ᵀv⁺ + λnᵀφ⁺/Δt + Σ_f μ_f γ_f λn(f)
//         = ΔvᵀMΔv + (MΔv)ᵀv* + λnᵀφ⁺/Δt + γᵀdiag(μ)λn(f).
// Unknowns in velocity units (as step_loss_relaxed_dual.hpp): λn = S λ̃n, β± = S β̃±
// per contact, S_c = 1/Σ_b minv_b,x the translational reduced mass of contact c's dynamic
// bodies (kg; m for one body on a static shape, so that a one-body island matches the
// polygon's S = m), γ in m/s unscaled, Δv unscaled and not regularized. The QP is
//     ℓ = min a1‖v* + Δv − v̄‖² + a2 zᵀw + (ε/2)‖(λ̃n, β̃⁺, β̃⁻, γ)‖²
//             + Σ_f (b_f/2)(t λ̃n(f)² + γ_f²/t),        b_f = a2 μ_f S_f,
//     s.t.  M Δv − Jnᵀ S λ̃n − Jtᵀ S (β̃⁺ − β̃⁻) = 0,   w ≥ 0 (the γ rows divided by S),
//           λ̃n, β̃±, γ ≥ 0,   Δv free.
// Convexity (local treatment): the bilinear a2 μ_f S_f γ_f λ̃n(f) is indefinite and the
// lifted Hessian has only ε on (λ̃n, γ) (the curvature that makes the polygon's z-space
// Hessian nearly PSD lives in Δv here), so each friction row's (λ̃n, γ) 2×2 block gets the
// shift diag(t b_f, b_f/t): the block becomes εI + b_f [[t, 1], [1, 1/t]] ⪰ εI, i.e. the
// bilinear term is completed to the square (b_f/2)(√t λ̃n + γ/√t)². The shift b_f depends on
// the data and is differentiated (part of the objective). t = shift_balance (default 1);
// the shifts are reported by RelaxedStepLossWorkspace::shifts(). It is larger than the dual
// form's global shift δ ≈ (a2 μ m)²/H_nn (step_loss_relaxed_dual.hpp), so on a one-body
// island with friction the two losses differ (without friction, μ = 0, they are the same QP).
// Hessian: Δv: 2(a1 I + a2 M); λ̃n: ε + t b; β̃±: ε; γ: ε + b/t; (λ̃n, γ): a2 μ S.
//
// The shift biases ℓ (at the true parameters it adds (b_f/2)(t λ̃n² + γ²/t) > 0 per row and
// favours small μ and λn). A proximal CENTRE c = (c_λ (nc), c_γ (nf)) removes the bias:
// the shift becomes (b_f/2)(t (λ̃n(f) − c_λ)² + (γ_f − c_γ,f)²/t), same Hessian, and
// re-centring at the solution is the proximal point method (Rockafellar 1976) on the
// unshifted, nonconvex QP: its fixed points are the unshifted QP's KKT points, where the
// shift term and its gradient vanish, so ℓ → min of a1‖v⁺ − v̄‖² + a2 zᵀw + ε-terms, which
// is (ε/2)‖z̃‖² ≈ 0 at the truth on LCP data. `proximal_iterations` solves per evaluation
// (each an update() of the same pattern), ending early once the solution moves less than
// proximal_tolerance·max(1, ‖(λ̃n, γ)‖∞); callers that evaluate the same sample repeatedly
// (training epochs) pass the previous solution, proximal_point(), as the next centre. The
// gradient is the envelope theorem at the last solve with its centre held fixed. With a
// centre it omits, by default, the shift's own dependence on μ and S (the (b/2)(…)² terms
// below): that is the gradient of the UNSHIFTED problem's Lagrangian at the solution, the
// proximal-point estimate of the unshifted loss's gradient, equal to it at a fixed point;
// the omitted term (∂b/∂θ)/2·‖x − c‖² ≥ 0 would otherwise push μ and masses down while the
// centres lag behind θ. centred_shift_in_gradient = true gives the exact gradient of ℓ_c.
//
// Gradient by the envelope theorem (Milgrom & Segal 2002): with the QpSolver's multipliers
// (qp_problem.hpp: Px + q + Aᵀy + Gᵀz + z_bounds = 0, z < 0 on an active lower side), ℓ
// equals the Lagrangian f + yᵀ(Ax − b) + zᵀ(Gx − l) at the optimum, so ∂ℓ/∂data is its
// partial derivative at fixed (x, y, z) (no extra solve). With λn = Sλ̃n, λt = S(β̃⁺ − β̃⁻),
// z = (z_n, z_p, z_m, z_g) per row block, m = 1/minv:
//     ∂ℓ/∂Jn = z_n v⁺ᵀ − λn yᵀ,   ∂ℓ/∂Jt = (z_p − z_m) v⁺ᵀ − λt yᵀ      (on the patterns)
//     ∂ℓ/∂v* = 2a1(v⁺ − v̄) + a2 m∘Δv + Jnᵀz_n + Jtᵀ(z_p − z_m)
//     ∂ℓ/∂φ_c = (a2 S_c λ̃n_c + z_n,c)/Δt where φ_c > 0, else 0
//     ∂ℓ/∂μ_f = a2 S_f γ_f λ̃n(f) + (a2 S_f/2)(t λ̃n(f)² + γ_f²/t) + z_g,f λ̃n(f)
//               (with a centre and centred_shift_in_gradient: λ̃n − c_λ and γ − c_γ inside
//               the square, here and in ∂ℓ/∂S_c; with a centre otherwise: no square term)
//     ∂ℓ/∂minv_k = −m_k²(a2 Δv_k v⁺_k + y_k Δv_k)  [+ −S_c² ∂ℓ/∂S_c on each contact's bodies' x entry]
//     ∂ℓ/∂S_c = a2 λ̃n_c φ⁺_c/Δt + Σ_f(c) (a2 μ_f γ_f λ̃n_c + (a2 μ_f/2)(t λ̃n_c² + γ_f²/t)
//               − (Jt y)_f (β̃⁺ − β̃⁻)_f) − (Jn y)_c λ̃n_c.
//
// Mass normalization (normalize_by_mass, off by default): zᵀw is an energy (kg·m²/s²) while
// a1's term is a squared velocity, so with a fixed a2 the loss falls when every mass falls
// (all impulses, hence every complementarity violation, scale with a common mass factor):
// a model mismatch (wrong vertices) is then cheapened by lowering all masses. With the setting, a2 is divided by σ = the mean mass of
// the island's dynamic bodies (kg, the x entries of M), a2_σ = a2/σ, so that both terms are
// squared velocities and ℓ is invariant when every mass and inertia of the island is scaled
// by a common factor (the applied pushes in v*, not the loss, then fix the mass scale).
// Every a2 above is then a2_σ, and the mass gradient gains the chain through σ:
//     ∂ℓ/∂minv(3b) += C a2_σ m_b² / Σ_b' m_b',   C = ∂ℓ/∂a2_σ = Σ_k m_k Δv_k(Δv_k + v*_k)
//                     + Σ_c S_c λ̃n_c φ⁺_c/Δt + Σ_f μ_f S_f (γ_f λ̃n(f) + sq_f/2),
// sq_f the square of ∂ℓ/∂μ_f's shift term under the same centre convention.
// relaxed_step_qp() exposes the QP so that tests check these against QpSolver::backward.
// status: solved / solved_inaccurate as the QP's; failed otherwise (loss NaN, gradient zero).
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/kkt/qp_result.hpp>
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/learn/step_loss.hpp>

#include <memory>
#include <string>

namespace lcprelax::learn {

struct RelaxedStepLossSettings {
  double a1 = 1.0;              ///< weight of ‖v⁺ − v̄‖², > 0
  double a2 = 0.1;              ///< weight of zᵀw (the polygon's), ≥ 0
  double regularization = 1e-6; ///< ε (velocity units), > 0 (the polygon's)
  double shift_balance = 1.0;   ///< t of the per-contact shift diag(t b, b/t), > 0
  int proximal_iterations = 1;  ///< solves per evaluation, each re-centred (≥ 1; 1: one solve)
  double proximal_tolerance = 1e-9;  ///< relative move of (λ̃n, γ) that ends the iterations early
  bool centred_shift_in_gradient = false;  ///< with a centre: exact ∂ℓ_c (true) or the unshifted estimate
  bool normalize_by_mass = false;  ///< a2 divided by the island's mean dynamic-body mass (header comment)
  QpSettings qp;                ///< interior point (automatic backend: CHOLMOD above dense_max_kkt)
  /// Empty if valid, else a message naming the first bad field.
  std::string validation_error() const;
};

/// The lifted QP for island s (variables [Δv (3·bodies), λ̃n (nc), β̃⁺, β̃⁻, γ (nf each)];
/// rows of G: [w_n (nc), w_β⁺, w_β⁻, w_γ/S (nf each)]; A: the nd momentum rows), the shift
/// centred at `center` ([λ̃n (nc); γ (nf)]) or at 0 when null. Validates (throws InputError).
QpProblem relaxed_step_qp(const ContactSystem& s, const Vector& target, double dt,
                          const RelaxedStepLossSettings& settings, const Vector* center = nullptr);

/// A per-thread workspace: keeps the QpSolver and reuses its symbolic analysis
/// (QpSolver::update) while the island's sparsity pattern repeats (same bodies, contacts
/// and Jacobian patterns); on another pattern it sets up again. Both paths give the same
/// result to roundoff. Not thread-safe.
class RelaxedStepLossWorkspace {
 public:
  /// Throws InputError when settings.validation_error() is not empty.
  explicit RelaxedStepLossWorkspace(RelaxedStepLossSettings settings = {});
  ~RelaxedStepLossWorkspace();
  RelaxedStepLossWorkspace(RelaxedStepLossWorkspace&&) noexcept;
  RelaxedStepLossWorkspace& operator=(RelaxedStepLossWorkspace&&) noexcept;

  const RelaxedStepLossSettings& settings() const;
  /// ℓ, v⁺ and ∂ℓ/∂data (envelope theorem) for island s, observed next velocity `target`
  /// (3 per body), dt (s), the first solve's shift centred at `center` ([λ̃n; γ], nc + nf
  /// entries) or at 0 when null. Throws InputError on invalid data or a centre of the wrong size.
  /// `iterations` > 0 overrides settings().proximal_iterations for this call.
  StepLossResult evaluate(const ContactSystem& s, const Vector& target, double dt,
                          const Vector* center = nullptr, int iterations = 0);
  /// [λ̃n; γ] of the last evaluate()'s last solve (zeros without contact): the next centre.
  const Vector& proximal_point() const;
  int proximal_solves() const;  ///< QP solves done by all evaluate() calls
  /// The last evaluate()'s QP result (x, y, z) and per-friction-row shifts b_f.
  const QpResult& qp_result() const;
  const Vector& shifts() const;
  int setups() const;   ///< symbolic analyses done (QpSolver::setup)
  int updates() const;  ///< evaluations that reused one (QpSolver::update)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One-shot: a fresh workspace.
StepLossResult relaxed_step_loss(const ContactSystem& s, const Vector& target, double dt,
                                 const RelaxedStepLossSettings& settings = {}, const Vector* center = nullptr);

}  // namespace lcprelax::learn
