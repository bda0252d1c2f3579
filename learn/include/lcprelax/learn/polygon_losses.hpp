#pragma once
// Per-sample losses of the polygon learning problem and ∂ℓ/∂θ (hard, relaxed, convex), from the
// assembly of polygon_assembly.hpp (value + tangent per parameter). The target is the
// sample's NEXT VELOCITY v̄ = v_{k+1} (m/s, m/s, rad/s; no weighting between linear and
// angular components): the simulator's positions are post-stabilized (simulator.hpp), so
// q_{k+1} = q_k + Δt v⁺ holds only up to the projection, while v_{k+1} = v⁺ exactly.
//
// hard and convex are the scene path's step losses (step_loss.hpp) on the sample's island of
// one body (to_contact_system, with every entry of Jn and Jt stored), chained to θ through
// the assembly's tangents: ∂ℓ/∂θ_k = ⟨∂ℓ/∂(Jn, Jt, φ, μ, M⁻¹, v*), ∂(Jn, Jt, φ, μ, M⁻¹, v*)/∂θ_k⟩
// (polygon_solvers.hpp). relaxed keeps its own dense implementation: the dual relaxed step
// loss (step_loss_relaxed_dual.hpp) equals it per sample (on the 315 samples of
// tests/learn_polygon_recovery_test.cpp at the truth and two perturbed models: relative
// 3e-11 in ℓ, 5e-10 in ∂ℓ/∂θ) but has no warm start, and that test's training needs the
// warm starts (cold, this implementation too ends with a 6.5% mass error, above its 5%).
//
// hard = hard_step_loss (step_loss_hard.hpp; Belbute-Peres et al. 2018): ℓ = ‖v⁺(z) − v̄‖²,
//   z the Stewart–Trinkle LCP's solution by Lemke, gradient by LemkeSolver::backward. Zero
//   where a wrong prior makes the contacts stick (λ's basis does not change with θ). Warm
//   start: the previous evaluation's final basis. A solution of the perturbed LCP
//   (solved_inaccurate) counts as solved.
// relaxed (Parmar, Halm & Posa 2021; learn/relaxed_lcp.hpp): ℓ = c, the optimal value of
//   the relaxed QP for the LCP (M, q) of polygon_lcp.hpp with prediction v⁺ = P z + p and
//   target v̄; gradient by the envelope theorem, chained through the LCP's tangents. The
//   unknowns are rescaled to velocity units, z = S z̃ with S = diag(m on λn, β±; 1 on γ),
//   rows scaled by S as well (the same LCP; the complementarity term z̃ᵀS(MSz̃ + q) =
//   zᵀ(Mz + q) is unchanged), so that the relaxed QP's regularization (ε/2)‖z̃‖² does not
//   pull the mass towards 0.
//   The Stewart–Trinkle M is not monotone: zᵀMz contains a2·μ·γ·λn with no γ² term, so the
//   relaxed QP is made convex by NonconvexPolicy::shift (relaxed_lcp.hpp), and the shift
//   δ ≈ (a2 μ m)²/H_nn it needs penalizes the sliding speed γ, i.e. favours sticking.
//   Polygon defaults therefore differ from relaxed_lcp.hpp's: a2 = 0.1 (δ ∝ a2²) and
//   ε = 1e-6. On the recovery problem of tests/learn_polygon_recovery_test.cpp, a2 = 0.1
//   recovers every parameter; a2 = 1 learns μ too large (the shift favours sticking) and
//   a2 = 0.02 leaves μ unidentifiable (the complementarity term is too weak); the numbers
//   are in bench/README.md. Warm start: the previous evaluation's relaxed-LCP result.
// convex = convex_step_loss (step_loss_convex.hpp) in the dual formulation with
//   phase1_regularization = 0: the two-phase model of models/contact_step.hpp
//   (solve_convex_model) with an L2 deviation penalty of weight w ≥ 0 in both phase
//   objectives, (w/2)‖v⁺(λ) − v̄‖²_M, ℓ = ‖v⁺(λ²) − v̄‖², gradient by QpSolver::backward of
//   phase 2, then of phase 1 through κ (Amos & Kolter 2017). With w = 0 the forward is the
//   library's convex model. Phase 1's row Wnn λn + bn ≥ 0 is posed for w > 0 only (implied
//   by optimality when w = 0). Where no contact approaches (bn ≥ 0 and phase 1's linear
//   term ≥ 0) λ = 0 directly. No warm start (the step loss has none). With w = 0 and more
//   contact candidates than the body's 3 dofs can separate (Wnn singular), phase 1's λn and
//   κ are not unique, and posing the row anyway picks another solution: on the recovery
//   test's data at perturbed models the mean loss then differs by 4e-5 relative and single
//   samples' ∂ℓ/∂θ by up to 0.4 (with w = 1, the default, the two agree to 1e-9).
// Every function returns ok = false with the step loss's message when its solve fails.
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/learn/batch.hpp>
#include <lcprelax/learn/polygon_assembly.hpp>
#include <lcprelax/learn/relaxed_lcp.hpp>
#include <lcprelax/lcp/lcp_types.hpp>

#include <string>
#include <vector>

namespace lcprelax::learn {

enum class PolygonMethod { hard, relaxed, convex };
const char* to_string(PolygonMethod m);
/// "hard", "relaxed" or "convex"; throws InputError("--method: ...") otherwise.
PolygonMethod parse_polygon_method(const std::string& s);

struct PolygonLossSettings {
  PolygonMethod method = PolygonMethod::relaxed;
  LemkeSettings lemke;               ///< hard
  RelaxedLcpSettings relaxed;        ///< relaxed (constructor: nonconvex = shift, a2 = 0.1, ε = 1e-6)
  QpSettings qp;                     ///< relaxed and convex
  double convex_rho = 1e-3;          ///< ρ of the convex model (contact_step.hpp)
  double convex_deviation = 1.0;     ///< w of the deviation penalty, ≥ 0
  bool warm_start = true;            ///< hard, relaxed: per-sample warm starts from the previous evaluation
  /// Extra contact candidates (m, ≥ 0; polygon_active_vertices' extra_margin): vertices
  /// within the speculative margin + candidate_margin of the ground enter the sample's
  /// problem. With 0 (the simulator's active set), vertices displaced by a perturbed
  /// geometry (25%: ±0.05 m per coordinate on the CLI's polygon) miss contacts that the
  /// data show, and mass and inertia absorb the missing impulses. At the truth the extra
  /// candidates leave the hard loss at roundoff and raise the relaxed one slightly. The
  /// numbers are in bench/README.md.
  double candidate_margin = 0.05;
  PolygonLossSettings();
  std::string validation_error() const;  ///< empty if valid
};

/// What a sample keeps between evaluations.
struct PolygonWarmStart {
  std::vector<bool> lemke_basis;     ///< hard: the last final basis (tried first)
  RelaxedLcpResult relaxed;          ///< relaxed (valid when relaxed_valid)
  bool relaxed_valid = false;
};

/// Seconds spent in each part (accumulated).
struct PolygonLossTimes {
  double assembly = 0.0, solve = 0.0, backward = 0.0;
  long samples = 0;
};

/// A thread's workspace for the hard and convex losses (polygon_solvers.hpp, internal).
/// The step losses keep no solver between calls, so it holds nothing; it stays in the
/// signatures so that callers need not change.
struct PolygonSolvers;

/// Per-sample losses for the assembled data `a` (value and tangents) and target v̄.
/// `warm` is read and updated when settings.warm_start (hard: the Lemke basis; relaxed: the
/// relaxed-LCP result). `solvers` (hard, convex): unused (null or PolygonObjective's).
SampleResult polygon_hard_loss(const PolygonAssembly& a, const Vec3& target, double dt,
                               const PolygonLossSettings& settings, PolygonWarmStart& warm, PolygonLossTimes& times,
                               PolygonSolvers* solvers = nullptr);
SampleResult polygon_relaxed_loss(const PolygonAssembly& a, const Vec3& target, double dt,
                                  const PolygonLossSettings& settings, RelaxedLcpSolver& solver,
                                  PolygonWarmStart& warm, PolygonLossTimes& times);
SampleResult polygon_convex_loss(const PolygonAssembly& a, const Vec3& target, double dt,
                                 const PolygonLossSettings& settings, PolygonWarmStart& warm, PolygonLossTimes& times,
                                 PolygonSolvers* solvers = nullptr);

}  // namespace lcprelax::learn
