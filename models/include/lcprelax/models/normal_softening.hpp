#pragma once
// Softening of the convex contact model's normal impulses (phase 2 of contact_step.hpp),
// a setting shared by the simulator (SimulatorSettings::convex_softening) and the convex
// learning loss (learn/step_loss_convex.hpp, ConvexStepLossSettings::softening).
//
// Each method adds to phase 2, per contact i with diag(Wnn)_ii = Wnn_i (1/kg), gap φ_i (m)
// and normal velocity vn_i = (Jn v*)_i (m/s):
//     ½ r_i λn_i² − v_ref_i λn_i,     r_i = g(φ_i)·Wnn_i  (1/kg),  v_ref_i (m/s),
// and −max(v_ref_i, 0) λn_i to phase 1 (so that phase 1's impulse budget κ = eᵀλn includes
// the push-out the target velocity asks for; only the positive part, which keeps phase 1's
// answer feasible for phase 2's hard rows; phase 1 keeps no compliance),
// so that where contact i's constraints are inactive phase 2's stationarity reads
//     Jn_i v⁺ = v_ref_i − r_i λn_i          (a soft constraint: Todorov 2014, eq. for
// the regularized dynamics J a = a_ref − R f, in velocity form with λ = Δt f).
// λn in N·s, so r_i λn_i is a velocity. The sign convention is that of conventions.md:
// φ < 0 overlapping, vn < 0 approaching, v_ref > 0 asks to separate.
//
//   exp_phi (default; the model's original term ρ λnᵀ diag(exp φ) diag(Wnn) λn):
//       g = 2ρ·exp(φ),  v_ref = 0.
//       Dimensionless ρ. Softer with a larger gap, never zero; gradient in φ everywhere.
//   linear_penalty (a penalty spring in compliant-constraint form; Servin, Lacoursière &
//   Melin 2006, "Interactive simulation of elastic deformable materials"):
//       g = 2ρ,  v_ref = −min(φ, 0)/Δt.
//       With the constraints inactive, λn = (−φ/Δt − vn⁺)/(2ρ Wnn): a force linear in the
//       overlap, of stiffness m_eff/(2ρΔt²) with m_eff = 1/Wnn, and implicit damping. No
//       gradient in φ from the compliance; the push-out v_ref is kinked at φ = 0.
//   mujoco_impedance (MuJoCo's soft constraints: Todorov 2014, "Convex and analytically-
//   invertible dynamics with contacts and constraints: theory and implementation in
//   MuJoCo", ICRA; solimp/solref as in MuJoCo's documentation, sigmoid power 1):
//       d(φ) = d0 + (d_width − d0)·min(|φ|/width, 1)     impedance in (0, 1)
//       g = (1 − d)/d                                    (R = (1−d)/d·diag(A), A ≈ W)
//       a_ref = −b·vn − k·φ,  b = 2/(d_width·τ),  k = d(φ)/(d_width²·τ²·ζ²)
//       v_ref = vn + Δt·a_ref = (1 − Δt b)·vn − Δt·k(φ)·φ.
//       τ = time_constant (s), ζ = damping_ratio. MuJoCo uses the velocity before the
//       step for vn; the contact system holds v* = v + Δt M⁻¹f, so vn = Jn v* here (it
//       includes the step's external impulse). Kinks at φ = 0 and |φ| = width.
// In every method both phases keep their hard rows (Jn v⁺ + max(φ,0)/Δt ≥ 0; phase 2's
// eᵀλn ≤ κ). A push-out v_ref > 0 makes phase 1 push (Jn v⁺ = v_ref at a lone contact),
// and phase 2's compliance then gives some of it back. Where no contact approaches and
// v_ref ≤ bn = Jn v* + max(φ,0)/Δt, λ = 0 is returned without a solve (contact_step.hpp).
// rho is the simulator's convex_rho (ConvexStepLossSettings::rho); mujoco_impedance does
// not use it.
#include <lcprelax/sparse/types.hpp>

#include <string>
#include <string_view>

namespace lcprelax {

enum class NormalSoftening { exp_phi, linear_penalty, mujoco_impedance };

constexpr const char* to_string(NormalSoftening m) {
  switch (m) {
    case NormalSoftening::exp_phi: return "exp_phi";
    case NormalSoftening::linear_penalty: return "linear_penalty";
    case NormalSoftening::mujoco_impedance: return "mujoco_impedance";
  }
  return "unknown";
}

/// Inverse of to_string (also "exp", "penalty", "impedance"); throws InputError otherwise.
NormalSoftening parse_normal_softening(std::string_view text);

struct NormalSofteningSettings {
  NormalSoftening method = NormalSoftening::exp_phi;
  // mujoco_impedance only (MuJoCo's defaults: solimp = (0.9, 0.95, 0.001), solref = (0.02, 1)).
  double d0 = 0.9;              ///< impedance at φ = 0, in (0, 1)
  double d_width = 0.95;        ///< impedance at |φ| ≥ width, in (0, 1)
  double width = 1e-3;          ///< m, > 0
  double time_constant = 0.02;  ///< τ, s, > 0 (MuJoCo advises ≥ 2Δt)
  double damping_ratio = 1.0;   ///< ζ, > 0

  /// Empty when valid, else a message naming the first bad field ("d0: must be ...").
  std::string validation_error() const;
};

/// Per-contact terms of one island, with their partial derivatives.
struct NormalSofteningTerms {
  Vector g;           ///< r_i = g_i·Wnn_i
  Vector dg_dphi;     ///< ∂g/∂φ (1/m)
  Vector v_ref;       ///< m/s
  Vector dvref_dphi;  ///< ∂v_ref/∂φ (1/s)
  Vector dvref_dvn;   ///< ∂v_ref/∂vn (dimensionless)
  // A material pair's normal softness (world.hpp FrictionTable; add_pair_softness), empty
  // when no contact has one:
  Vector compliance;  ///< c_i (1/kg), added to r_i on phase 2's λn diagonal
  Vector dvref_derp;  ///< ∂v_ref/∂e_i (m/s): v_ref_i gains −e_i·min(φ_i, 0)/Δt
};

/// The terms for gaps `phi` and normal velocities `vn` = Jn v* (one per contact), with the
/// model's ρ and step Δt (s). Settings are assumed valid.
NormalSofteningTerms normal_softening_terms(const NormalSofteningSettings& settings, double rho, double dt,
                                            const Vector& phi, const Vector& vn);

/// Adds a material pair's normal softness to the terms (the lcp model's normal row
/// Jn v⁺ + (max(φ,0) + e·min(φ,0))/Δt + c·λn, contact_system.hpp): r_i += c_i and
/// v_ref_i += −e_i·min(φ_i, 0)/Δt (a push-out of the fraction e of an overlap), so that where
/// phase 2's constraints are inactive Jn_i v⁺ + e_i min(φ_i, 0)/Δt + c_i λn_i equals the
/// softening's own v_ref_i − g_i Wnn_i λn_i. `compliance` and `erp` one per contact (or
/// empty: 0).
void add_pair_softness(NormalSofteningTerms& terms, const Vector& phi, const Vector& compliance, const Vector& erp,
                       double dt);

/// Phase 1's terms: v_ref replaced by max(v_ref, 0) (derivatives 0 where v_ref < 0; a kink
/// at v_ref = 0); g unchanged (phase 1 does not use it). At v_ref = 0 exactly the derivative
/// in e is kept (the one-sided derivative into e ≥ 0: v_ref is nondecreasing in e, so at
/// the rigid start e = 0 on an overlapping contact max(v_ref, 0) = v_ref for every e ≥ 0),
/// the others are 0.
NormalSofteningTerms phase1_softening_terms(const NormalSofteningTerms& terms);

}  // namespace lcprelax
