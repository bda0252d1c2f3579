#pragma once
// Per-sample losses of the polygon learning problem and ∂ℓ/∂θ (hard, relaxed, convex), from the
// assembly of polygon_assembly.hpp (value + tangent per parameter). The target is the
// sample's NEXT VELOCITY v̄ = v_{k+1} (m/s, m/s, rad/s; no weighting between linear and
// angular components): the simulator's positions are post-stabilized (simulator.hpp), so
// q_{k+1} = q_k + Δt v⁺ holds only up to the projection, while v_{k+1} = v⁺ exactly.
//
// hard (Belbute-Peres et al. 2018): ℓ = ‖v⁺(z) − v̄‖², z the Stewart–Trinkle LCP's solution
//   by Lemke (polygon_lcp.hpp); ∂ℓ/∂θ_k = ⟨∂ℓ/∂M, dM_k⟩ + ⟨∂ℓ/∂q, dq_k⟩ + gᵀ(dP_k z + dp_k)
//   with g = 2(v⁺ − v̄) and (∂ℓ/∂M, ∂ℓ/∂q) = LemkeSolver::backward(Pᵀg). Zero where a
//   wrong prior makes the contacts stick (λ's basis does not change with θ).
// relaxed (Parmar, Halm & Posa 2021; learn/relaxed_lcp.hpp): ℓ = c, the optimal value of
//   the relaxed QP for the LCP (M, q) with prediction v⁺ = P z + p and target v̄; gradient
//   by the envelope theorem, chained through the same tangents. The unknowns are rescaled
//   to velocity units, z = S z̃ with S = diag(m on λn, β±; 1 on γ), rows scaled by S as well
//   (the same LCP; the complementarity term z̃ᵀS(MSz̃ + q) = zᵀ(Mz + q) is unchanged), so
//   that the relaxed QP's regularization (ε/2)‖z̃‖² does not pull the mass towards 0.
//   The Stewart–Trinkle M is not monotone: zᵀMz contains a2·μ·γ·λn with no γ² term, so the
//   relaxed QP is made convex by NonconvexPolicy::shift (relaxed_lcp.hpp), and the shift
//   δ ≈ (a2 μ m)²/H_nn it needs penalizes the sliding speed γ, i.e. favours sticking.
//   Polygon defaults therefore differ from relaxed_lcp.hpp's: a2 = 0.1 (δ ∝ a2²) and
//   ε = 1e-6. On the recovery problem of tests/learn_polygon_recovery_test.cpp, a2 = 0.1
//   recovers every parameter; a2 = 1 learns μ too large (the shift favours sticking) and
//   a2 = 0.02 leaves μ unidentifiable (the complementarity term is too weak); the numbers
//   are in bench/README.md.
// convex (the two-phase model of models/contact_step.hpp solve_convex_model), with
//   an L2 deviation penalty of weight w ≥ 0 in both subproblem objectives: the prediction's
//   deviation from the target in the mass norm, (w/2)‖v⁺(λ) − v̄‖²_M, which with
//   v⁺ = v* + M⁻¹Jᵀλ adds (w/2)λᵀWλ + wλᵀJ(v* − v̄) (+ const):
//     1. min_{λn ≥ 0} ½λnᵀ(1+w)Wnn λn + λnᵀ(bn + wJn(v* − v̄)),  bn = Jn v* + max(φ,0)/Δt,
//        s.t. Wnn λn + bn ≥ 0 (implied by optimality when w = 0; with w > 0 it must be
//        explicit, else κ can be too small for phase 2 to be feasible)
//     2. κ = eᵀmax(λn¹, 0);  min ½λᵀ[(1+w)W + 2ρ diag(exp(φ)) diag(Wnn)]λ + λᵀ(Jv* + wJ(v* − v̄))
//        s.t. Wn λ + bn ≥ 0, λn ≥ 0, eᵀλn ≤ κ(1 + s) + 1e-12, |λt| ≤ μλn
//   (s = 1e-6, else 1e-4, 1e-2 as convex_model.cpp), ℓ = ‖v⁺(λ²) − v̄‖², gradient by
//   QpSolver::backward of phase 2, then of phase 1 through κ (∂ℓ/∂λn¹ = (1+s)∂ℓ/∂u_κ on
//   positive entries; Amos & Kolter 2017). With w = 0 the forward is the library's convex
//   model. Where no contact approaches (both phase-1 linear terms ≥ 0) λ = 0 directly.
// Every function returns ok = false with a message when its solve fails.
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
  bool warm_start = true;            ///< per-sample warm starts from the previous evaluation
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

/// What a sample keeps between evaluations (warm starts).
struct PolygonWarmStart {
  std::vector<bool> lemke_basis;     ///< hard
  RelaxedLcpResult relaxed;          ///< relaxed (valid when relaxed_valid)
  bool relaxed_valid = false;
  Vector x1, y1, z1, zb1, x2, y2, z2, zb2;  ///< convex phases
};

/// Seconds spent in each part (accumulated).
struct PolygonLossTimes {
  double assembly = 0.0, solve = 0.0, backward = 0.0;
  long samples = 0;
};

/// Solvers kept between the samples one thread evaluates (polygon_solvers.hpp, internal):
/// Lemke (hard) and the two phases' QpSolvers (convex), whose symbolic analyses are reused
/// (QpSolver::update) while the sparsity pattern repeats.
struct PolygonSolvers;

/// Per-sample losses for the assembled data `a` (value and tangents) and target v̄.
/// `warm` is read and updated when settings.warm_start. `solvers` (hard, convex): a
/// thread's workspace made with settings (PolygonObjective's), or null for solvers local
/// to the call; either gives the same result bit for bit.
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
