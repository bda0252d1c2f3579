#pragma once
// One island's contact impulses for a velocity-level time step, by either contact model
// (DESIGN §1.4). Δt in s, impulses in N·s, velocities in m/s and rad/s.
//
// Both models use the gap term max(φ, 0)/Δt: a contact inside the margin may close its
// gap during the step but never gets a push-out velocity from a penetration (that would
// add kinetic energy); penetration is removed at position level by the simulator's
// post-stabilization (simulator.hpp).
//
// lcp (Stewart & Trinkle 1996; Anitescu & Potra 1997), unknowns z = [λn, β⁺, β⁻, γ]
// (β± per friction row, λt = β⁺ − β⁻, γ the sliding speed):
//     0 ≤ λn ⊥ Jn v⁺ + max(φ,0)/Δt ≥ 0
//     0 ≤ β⁺ ⊥  Jt v⁺ + γ ≥ 0,   0 ≤ β⁻ ⊥ −Jt v⁺ + γ ≥ 0
//     0 ≤ γ  ⊥ μ λn − β⁺ − β⁻ ≥ 0,            v⁺ = v* + M⁻¹(Jnᵀλn + Jtᵀλt),
// an LCP in z with M assembled sparse from W = J M⁻¹ Jᵀ, solved by Lemke.
//
// convex (two phases, DESIGN §1.4), by the interior-point QP:
//   1. min_{λn ≥ 0} ½ λnᵀ Wnn λn + λnᵀ (Jn v* + max(φ,0)/Δt)             (no friction)
//   2. κ = eᵀλn;  min ½ λᵀ W λ + λᵀ J v* + ρ λnᵀ diag(exp(φ)) diag(Wnn) λn
//      s.t. Jn v⁺ + max(φ,0)/Δt ≥ 0, λn ≥ 0, eᵀλn ≤ κ, |λt| ≤ μ λn.
//   Phase 1's solution with λt = 0 is feasible for phase 2, so phase 2 always has one.
//   DESIGN writes the last term as λnᵀ diag(exp(φ)) λn, which is not unit-consistent
//   (λ in N·s, W in 1/kg); it is scaled here by diag(Wnn) with a dimensionless weight ρ
//   (default 1e-3, SimulatorSettings::convex_rho). Measured: with the unscaled term (ρ = 1
//   in 1/kg) a pile of 20 kg polygons gained up to 0.9% of its energy in one step; with
//   the scaled term it dissipates. The term makes λn unique with redundant contacts but
//   also makes contact slightly soft: a block that Coulomb friction holds creeps (measured
//   in tests/dynamics_incline_test.cpp); ρ → 0 recovers maximum dissipation.
//   κ is loosened by 1e-6 relative (convex_model.cpp) so that the interior point has an
//   interior; where no contact approaches (b ≥ 0) the answer λ = 0 is returned directly.
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/models/contact_system.hpp>

#include <string>
#include <vector>

namespace lcprelax {

struct ContactSolution {
  bool ok = false;          ///< the solve reached its status solved
  std::string message;      ///< status text of the failing solve when !ok
  Vector lambda_n;          ///< normal impulse per contact
  Vector lambda_t;          ///< tangential impulse per friction row (along t)
  Vector v_next;            ///< v⁺ per island dof
  double residual = 0.0;    ///< LCP: max|min(z, w)|; QP: max(primal, dual residual) of phase 2
  long work = 0;            ///< Lemke pivots, or interior-point iterations of both phases
  std::vector<bool> z_basic;  ///< LCP final basis (warm start of the next step)
  bool warm_started = false;  ///< LCP: the warm basis solved it in zero pivots
};

struct StewartTrinkleLcp {
  SparseMatrix M;  ///< (nc + 3nf)²
  Vector q;
};

/// The LCP of the lcp model for an island (W = delassus(s)).
StewartTrinkleLcp stewart_trinkle_lcp(const ContactSystem& s, const SparseMatrix& W, double dt);

/// Solves the lcp model; `warm` (size nc + 3nf, or empty) is tried as the first basis.
ContactSolution solve_lcp_model(const ContactSystem& s, double dt, const LemkeSettings& settings,
                                const std::vector<bool>& warm = {});

/// Solves the convex two-phase model.
ContactSolution solve_convex_model(const ContactSystem& s, double dt, const QpSettings& settings,
                                   double rho = 1e-3);

}  // namespace lcprelax
