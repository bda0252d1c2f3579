#pragma once
// The 1-D frictional block of Parmar, Halm & Posa, "Fundamental Challenges in Deep
// Learning for Stiff Contact Dynamics" (IROS 2021): a block sliding on the ground, pushed
// horizontally, with Coulomb friction, one velocity-level time step.
//
// Units and conventions (per step; the seeds' data use m = 1 and m·g = 1):
//   v    horizontal velocity before the step, m/s (positive to the right)
//   u    push impulse applied during the step, N·s (positive to the right)
//   m    mass, kg
//   mg   weight impulse of the step, m·g·Δt, N·s (the normal impulse; there is no normal
//        phase: the block never leaves the ground)
//   μ    friction coefficient (dimensionless)
//   λ    friction impulse, N·s, |λ| ≤ μ·mg
//   v⁺ = v + (u + λ)/m;   v* = v + u/m is the velocity the push alone would give.
// Maximum dissipation: λ minimizes the kinetic energy after the step within the friction
// bound, so the exact answer is λ = clamp(−m v*, −μmg, μmg): the block sticks (v⁺ = 0)
// when |v*| ≤ μmg/m and otherwise slides with v⁺ = v* − sign(v*)·μmg/m.
//
// As an LCP (Stewart & Trinkle 1996 in 1-D), z = (λ⁺, λ⁻, γ), λ = λ⁺ − λ⁻, γ the sliding
// speed:
//     0 ≤ λ⁺ ⊥  v⁺ + γ        ≥ 0
//     0 ≤ λ⁻ ⊥ −v⁺ + γ        ≥ 0
//     0 ≤ γ  ⊥  μmg − λ⁺ − λ⁻ ≥ 0,
// i.e. M = [[1/m, −1/m, 1], [−1/m, 1/m, 1], [−1, −1, 0]], q = (v*, −v*, μmg), solved by
// Lemke (lcp/lemke.hpp). As the convex model (contact_step.hpp, without a normal phase):
//     min_λ ½(1 + ρ)λ²/m + λ v*   s.t.  −μmg ≤ λ ≤ μmg,
// solved by the interior-point QP (kkt/qp_solver.hpp); ρ ≥ 0 is the L2 penalty on the
// impulse (dimensionless, scaled by the block's inverse mass like the 2-D convex model's
// diag(Wnn)); ρ = 0 is exactly maximum dissipation and agrees with the LCP.
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/sparse/types.hpp>

#include <string>
#include <vector>

namespace lcprelax {

struct Block1d {
  double mass = 1.0;  ///< m, kg, > 0
  double mg = 1.0;    ///< weight impulse per step, N·s, > 0
  double mu = 0.5;    ///< friction coefficient, ≥ 0
  /// Throws InputError naming the field if not finite or out of range.
  void validate() const;
};

struct Block1dLcp {
  SparseMatrix M;  ///< 3×3, pattern: all entries except (2,2)
  Vector q;        ///< 3
};

/// The LCP of one step (see above). Throws InputError on a bad block or non-finite v, u.
Block1dLcp block1d_lcp(const Block1d& block, double v, double u);

/// The convex model's QP of one step (1 variable, bounds ±μmg, no rows).
QpProblem block1d_convex_qp(const Block1d& block, double v, double u, double rho = 0.0);

/// The exact maximum-dissipation friction impulse λ = clamp(−m v*, −μmg, μmg).
double block1d_exact_impulse(const Block1d& block, double v, double u);
/// v⁺ = v + (u + λ)/m.
double block1d_next_velocity(const Block1d& block, double v, double u, double lambda);

struct Block1dStep {
  ContactStatus status = ContactStatus::unsolved;  ///< solved, solved_inaccurate (QP) or failed
  std::string message;          ///< solver status when it has no solution
  double lambda = 0.0;          ///< friction impulse, N·s
  double v_next = 0.0;          ///< m/s
  Vector z;                     ///< LCP: (λ⁺, λ⁻, γ); convex: (λ)
  std::vector<bool> z_basic;    ///< LCP final basis
  long work = 0;                ///< pivots or interior-point iterations
};

/// One step by Lemke on the LCP.
Block1dStep block1d_step_lcp(const Block1d& block, double v, double u, const LemkeSettings& settings = {});
/// One step by the interior point on the convex model.
Block1dStep block1d_step_convex(const Block1d& block, double v, double u, double rho = 0.0,
                                const QpSettings& settings = {});

}  // namespace lcprelax
