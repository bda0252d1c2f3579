#pragma once
// A warm-started primal–dual active-set solver for the convex model's phase QPs (any
// QpProblem: min ½xᵀPx + qᵀx s.t. Ax = b, l ≤ Gx ≤ u, xl ≤ x ≤ xu), used by
// solve_convex_model with ConvexSolver::active_set_newton (contact_step.hpp).
//
// Method, in two stages, each iteration one KKT factorization of an equality-constrained
// QP on a working set of rows and variable bounds,
//     [P + δp I   Cᵀ   ] [x]   [−q ]
//     [C         −δd I ] [ν] = [ d ],   C = [A; G_working; I_working], d their bounds,
// by a CHOLMOD LDLᵀ (sparse/cholmod_ldlt.hpp; quasi-definite for δp, δd > 0; Vanderbei
// 1995), the rows outside the working set kept in the pattern as ν_i = 0 so that one
// symbolic analysis serves every iteration, with iterative refinement against the
// unregularized system (δp = δd = 0):
// 1. crash: up to crash_iterations steps of the primal–dual active-set method of
//    Hintermüller, Ito & Kunisch (2002, "The primal-dual active set strategy as a
//    semismooth Newton method", SIAM J. Optim. 13(3)) from the caller's guess (the previous
//    time step's active set): a row joins where violated, leaves where its multiplier has
//    the wrong sign (lower: ν ≤ 0, upper: ν ≥ 0, the sign convention of
//    Px + q + Aᵀy + Gᵀz + z_bounds = 0). Undamped, this method cycles on the convex
//    model's friction QPs (measured: piles, every step, 12 iterations), so only its first
//    feasible iterate is used;
// 2. the primal feasible active-set method (Nocedal & Wright 2006, Algorithm 16.3) from
//    that iterate, or else from the caller's feasible point with the guessed rows active
//    there: a step toward the working set's minimizer up to the first blocking row (which
//    joins), and at the minimizer all rows with wrong-sign multipliers leave at once (the
//    objective still decreases). It is monotone but adds one blocking row per iteration.
// Stops when the minimizer's multipliers all have the right sign; the KKT residuals of
// the original problem are then checked. A solve that reaches `max_iterations`, a failing
// factorization or residuals above the tolerances is reported as not converged and the
// caller falls back to the interior point. No line search beyond the ratio test.
// Tolerances (absolute, in the units of the rows; QpSettings' convention):
//   primal residual max(‖Ax − b‖∞, dist(Gx, [l, u])∞, dist(x, [xl, xu])∞) ≤ eps_abs
//   dual residual   ‖Px + q + Aᵀy + Gᵀz + z_bounds‖∞ ≤ eps_abs·max(1, ‖q‖∞)
//   complementarity: inactive rows have multiplier 0 exactly; active rows lie on their
//   bound to the primal residual; multiplier signs hold to sign_tol·max(1, ‖ν‖∞).
#include <lcprelax/kkt/qp_problem.hpp>

#include <vector>

namespace lcprelax::detail {

struct ActiveSetSettings {
  double eps_abs = 1e-8;       ///< see the header comment
  double sign_tol = 1e-10;     ///< relative multiplier sign tolerance
  int max_iterations = 12;     ///< KKT factorizations before giving up
  int crash_iterations = 3;    ///< factorizations of the crash (header comment)
  double delta = 1e-9;         ///< δp = δ·max(1, max P_ii), δd = δ / max(1, max P_ii)
  int refinement_steps = 4;    ///< iterative refinement against the unregularized system
};

/// Active-set state of a row or variable bound: −1 at its lower bound, +1 at its upper
/// bound, 0 inactive.
using ActiveState = signed char;

struct ActiveSetResult {
  bool converged = false;        ///< KKT conditions hold to the tolerances (header comment)
  int iterations = 0;            ///< KKT factorizations
  Vector x, y, z, z_bounds;      ///< primal, equality, row and bound multipliers
  std::vector<ActiveState> rows;    ///< final state per row of G
  std::vector<ActiveState> bounds;  ///< final state per variable
  double primal_residual = 0.0, dual_residual = 0.0;
  std::string message;           ///< why, when not converged
};

/// Solves `p` from the initial active set (`rows`: one per row of G, `bounds`: one per
/// variable; a state on an infinite side is ignored). `x_feasible` (or null): a point that
/// satisfies every row and bound to eps_abs, the start when the crash finds none.
/// Throws InputError on wrong sizes.
ActiveSetResult solve_active_set_qp(const QpProblem& p, std::vector<ActiveState> rows,
                                    std::vector<ActiveState> bounds, const ActiveSetSettings& settings = {},
                                    const Vector* x_feasible = nullptr);

}  // namespace lcprelax::detail
