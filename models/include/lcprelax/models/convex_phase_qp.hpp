#pragma once
// The two interior-point QPs of the convex contact model (contact_step.hpp), the one
// assembly used by the simulator (models/src/convex_model.cpp) and by the convex learning
// loss (learn/step_loss_convex.hpp), in one of two equivalent formulations
// (ConvexFormulation):
//
// dual: the unknowns are the impulses only, x = (λn, λt), and the Hessian is the Delassus
//   matrix W = J M⁻¹ Jᵀ. Smallest problem, but W couples every pair of contacts that share
//   a body (a clique per body), and phase 2's non-penetration rows repeat W's normal rows.
//
// lifted: the velocity change w = Δv = M⁻¹ Jᵀ λ is an unknown too, x = (w, λn, λt), tied
//   to the impulses by the equality M w − Jnᵀ λn − Jtᵀ λt = 0. Then ½ λᵀ W λ = ½ wᵀ M w
//   and the non-penetration rows W(0:nc, :) λ + b ≥ 0 become Jn w + b ≥ 0, so the KKT
//   matrix holds only M (diagonal) and the Jacobians (6 entries per contact row in 2-D):
//   its graph is the body–contact incidence graph, and a fill-reducing order eliminates
//   contacts before bodies. This is the classical primal–dual form of the contact problem
//   (e.g. Anitescu & Potra 1997; Stewart & Trinkle 1996 keep v and λ as unknowns alike).
//   Lifted is faster from a few tens of contacts on (the measured crossover that sets
//   kLiftedMinContacts is in bench/README.md).
//
// Both have the same optimum in λn, λt and v⁺ (v⁺ is unique; λ is unique where the ρ term
// and W make it so): the equality only names J M⁻¹ Jᵀ λ. Phase 2's row `nc` is eᵀλn ≤ κ
// in both; the caller sets its upper bound u(nc).
//
// ConvexPhaseTerms holds what the learning loss changes (its defaults are the simulator's
// QPs, built bitwise as without them): the quadratic term scaled by s = 1 + w (the L2
// deviation penalty's curvature), other linear terms (J c in place of J v*), phase 1's
// regularization ½ r Σ Wnn_ii λn_i², and phase 1's non-penetration rows.
//
// Rows of phase 2 (m = nc + 1 + 2 nf): 0..nc non-penetration (Wn λ or Jn w) ≥ −bn; nc:
// eᵀλn ≤ κ; per friction row f: λt_f − μ_f λn ≤ 0 (row nc + 1 + 2f) and λt_f + μ_f λn ≥ 0
// (row nc + 2 + 2f). Units: impulses N·s, velocities m/s (rad/s), bn m/s.
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/normal_softening.hpp>

namespace lcprelax::detail {

/// A phase QP and where the impulses sit in its unknowns: x(lambda_offset + i) is λn_i for
/// i < nc and λt_(i − nc) for nc ≤ i < nc + nf (phase 1 has λn only).
struct ConvexPhaseQp {
  QpProblem problem;
  Index lambda_offset = 0;
};

/// The formulation `requested` resolves to for island `s` (automatic: lifted iff the
/// island has at least kLiftedMinContacts contacts).
ConvexFormulation resolve_convex_formulation(ConvexFormulation requested, const ContactSystem& s);

/// What both phases of one island need.
struct ConvexModelData {
  /// `bn` = Jn v* + max(φ, 0)/Δt, computed by the caller (it tests bn ≥ 0 first).
  ConvexModelData(const ContactSystem& system, const Vector& bn, ConvexFormulation form);
  const ContactSystem& s;
  ConvexFormulation form;  ///< dual or lifted (resolved)
  Vector bn;               ///< Jn v* + max(φ, 0)/Δt (m/s)
  Vector w_nn;             ///< diag(Wnn) = diag(Jn M⁻¹ Jnᵀ) (1/kg)
  SparseMatrix W;          ///< J M⁻¹ Jᵀ, rows and columns (contacts, friction rows); dual only
  bool lifted() const { return form == ConvexFormulation::lifted; }
};

/// Departures from the simulator's phase QPs (the defaults leave them unchanged).
struct ConvexPhaseTerms {
  double hessian_scale = 1.0;   ///< s: ½ s λᵀWλ (dual) or ½ s wᵀMw (lifted), s > 0
  const Vector* qn = nullptr;   ///< λn's linear term before −v_ref (default: phase 1 bn, phase 2 Jn v*)
  const Vector* qt = nullptr;   ///< λt's linear term (phase 2; default Jt v*)
  double regularization = 0.0;  ///< phase 1: r ≥ 0 of ½ r Σ Wnn_ii λn_i²
  bool contact_rows = false;    ///< phase 1: pose Wnn λn + bn ≥ 0 (or Jn w + bn ≥ 0) as rows 0..nc
};

/// Phase 1: min_{λn ≥ 0} ½ s λnᵀ Wnn λn + ½ r Σ Wnn_ii λn_i² + λnᵀ (qn − v_ref), v_ref the
/// softening's target velocity (0 for exp_phi), qn = bn by default.
ConvexPhaseQp convex_phase1_qp(const ConvexModelData& d, const NormalSofteningTerms& softening,
                               const ConvexPhaseTerms& terms = {});

/// A contact counts as open for release_open_contacts when phase 1 leaves its gap at the
/// end of the step wider than this (m): SimulatorSettings' default penetration slop, the
/// depth within which contacts count as resting. Without a threshold the decision at a
/// contact that phase 1 leaves exactly touching and unloaded (gap velocity and λ1 both ≈ 0,
/// common in stacks) follows the solver's roundoff, and the step jumps with it: on two
/// stacked boxes the convex loss jumped by 0.014 under a 1e-6 m change of one φ.
inline constexpr double kOpenContactMinGap = 1e-4;

/// Phase 2 puts no normal impulse on an open contact that phase 1 leaves open
/// (SimulatorSettings::convex_release_open_contacts): contact i with φ_i > 0 whose normal
/// velocity under phase 1's frictionless impulses λ1 leaves its gap open by more than
/// kOpenContactMinGap at the end of the step `dt` (s), bn_i + (Wnn λ1)_i > Wnn_ii λ1_i +
/// kOpenContactMinGap/dt (the velocity slack exceeds λ1_i's own velocity contribution by
/// that margin; phase 1's complementarity makes one of the two ≈ 0), gets the bound
/// λn_i ≤ 0 (xu = 0; λt_i then vanishes by its cone rows). Without it phase 2 may spend
/// phase 1's budget κ on such contacts and hold bodies at a gap up to the contact margin
/// (measured in docs/formulations.md). Returns how many contacts were released.
/// `phase2` is phase 2's QP with λn from column `lambda_offset` (ConvexPhaseQp's).
Index release_open_contacts(const ConvexModelData& d, const Vector& lambda1, QpProblem& phase2, Index lambda_offset,
                            double dt);

/// Relative loosenings of phase 2's bound eᵀλn ≤ κ(1 + slack) + 1e-12 N·s, tried in order
/// (convex_model.cpp explains why; the Newton path uses the first).
inline constexpr double kKappaSlacks[] = {1e-6, 1e-4, 1e-2};

/// Phase 2 (contact_step.hpp) with u(nc) = +∞ for eᵀλn ≤ κ (the caller sets it), with the
/// normal softening's terms (normal_softening.hpp): ½ Σ g_i Wnn_i λn_i² − λnᵀ v_ref.
ConvexPhaseQp convex_phase2_qp(const ConvexModelData& d, const NormalSofteningTerms& softening,
                               const ConvexPhaseTerms& terms = {});

}  // namespace lcprelax::detail
