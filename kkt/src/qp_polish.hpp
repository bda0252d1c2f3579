#pragma once
// Solution polishing of the interior point's answer (internal; QpSettings::polish).
//
// Stellato, Banjac, Goulart, Bemporad, Boyd, "OSQP: an operator splitting solver for
// quadratic programs", Math. Prog. Comp. 12, 2020, §5.2; the active-set refinement
// ("crossover") of interior-point codes.
//
// 1. Active set, guessed on the scaled final iterate (standard_form.hpp): a one-sided
//    constraint (a side of a row of G̃ or of a variable bound) is active when its slack is
//    smaller than its multiplier, s < z; where both sides of one row or variable qualify
//    the side with the larger z is taken. Equality rows (Ẽ) are always active.
// 2. Reduced KKT system. Variables at an active bound are fixed there (x̃_B = bound) and
//    eliminated; with C = [Ẽ; G̃_A] restricted to the free columns F and h its active
//    sides (b̃, g̃l or g̃u), the equality-constrained QP
//        [P̃_FF   C_Fᵀ] [x̃_F]   [−q̃_F − P̃_FB x̃_B]
//        [C_F    0   ] [λ  ] = [ h − C_B x̃_B     ]   =: K0 v = r
//    is solved by CHOLMOD LDLᵀ of the quasi-definite K_δ = K0 + diag(δI, −δI) (δ =
//    kPolishDelta, scaled problem) and iterative refinement v ← v + K_δ⁻¹(r − K0 v)
//    started from the interior iterate. Refinement is the proximal point iteration on K0:
//    it converges to a solution of K0 v = r whenever that system is consistent, also when
//    C_F is rank deficient (degenerate vertices with more active rows than free
//    variables) or P̃_FF is singular on the null space of C_F (the solution nearest the
//    interior iterate). The residual r − K0 v is accumulated in long double (mixed-
//    precision refinement: it then reaches the roundoff of v, not that of the residual's
//    terms), and the iterate of smallest ‖r − K0 v‖∞ is kept (on an inconsistent system,
//    i.e. a wrong active set, the residual stops decreasing and v drifts along K0's null
//    space).
// 3. Unscaled candidate: x = Dx∘x̃ with x_j set exactly to its bound at active bounds, row
//    multipliers λ mapped back as y = Ee∘ỹ/c, z = Eg∘ζ/c (0 at inactive rows); bound
//    multipliers of fixed and bound-active variables from stationarity componentwise,
//    z_b,j = −(Px + q + Aᵀy + Gᵀz)_j (0 at free variables). Signs (qp_problem.hpp): z ≤ 0
//    at an active lower side, z ≥ 0 at an active upper side.
// 3b. Forcing rows (QpSettings::polish_forcing_rows): a second candidate of the same point
//    in which every row whose variables all sit at an active bound (or are fixed) gets the
//    multiplier of smallest magnitude that keeps every sign, the bound multipliers taking
//    up the difference (kForcingRowPasses passes; Andersen & Andersen 1995's dual postsolve
//    of forcing constraints); its bound multipliers with a wrong sign below kSignFloorUlps
//    ulps of their stationarity row count as 0. Of the two candidates the better counts;
//    the corrections of step 4 come from the first.
// 3c. Least-norm multipliers (QpSettings::polish_least_norm): a third candidate, the
//    multipliers of the better of 3 and 3b replaced by the element of smallest 2-norm of
//    {w : Px + q + Aᵀy + Gᵀz + z_b = 0 on the active sides, signs kept}
//    (qp_polish_least_norm.cpp); where the interior point's multipliers are unbounded, the
//    roundoff of the gap's and the dual residual's terms falls with them. The reduced
//    system of step 2 is then solved once more from that point (its refinement's floor was
//    set by the large multipliers), the sides with a zero least-norm multiplier left out;
//    up to kLeastNormPasses passes while the candidate improves.
// 4. Corrections (at most kPolishRounds reduced solves): a side whose multiplier has the
//    wrong sign by more than 1e-2·tol_d leaves the active set, an inactive row or bound
//    violated by more than 1e-2·tol_p enters it at the violated side, and the system is
//    solved again; tol_p, tol_d are the termination tolerances eps_abs + eps_rel·scale of
//    the unpolished point. Wrong signs within 1e-2·tol_d are set to 0.
// The best candidate (smallest worst ratio of residual to tolerance, residuals recomputed
// by compute_residuals exactly as the termination test does) among the rounds without a
// wrong sign is returned; the caller (QpSolver::Impl::polish) decides whether to accept it,
// and on acceptance replaces the interior iterate by the polished point (kPolishMu) and
// factorizes the KKT matrix there for backward().
#include "qp_solver_impl.hpp"

#include <vector>

namespace lcprelax::detail {

constexpr double kPolishDelta = 1e-7;      ///< regularization δ of K_δ (scaled problem)
constexpr int kPolishRounds = 4;           ///< reduced solves (guess + corrections)
constexpr int kPolishRefinement = 25;      ///< refinement steps per reduced solve
constexpr double kPolishSignFraction = 1e-2;  ///< wrong-sign / violation threshold (× tolerance)
/// Bound multipliers whose wrong sign is below this many ulps of their stationarity row's
/// Σ|terms| count as 0, not as wrong (qp_polish.cpp, after the forcing-row step).
constexpr double kSignFloorUlps = 16.0;
/// Passes of the forcing-row step over all rows (rows share variables: a later row's shift
/// can free an earlier one's); stops early when a pass shifts nothing.
constexpr int kForcingRowPasses = 10;
/// Complementarity s·z of the iterate that replaces the interior one after an accepted
/// polish (scaled problem): active sides get s = μ/z with z = max(|ζ|, √μ), inactive ones
/// z = μ/s with s = max(slack, √μ); the KKT matrix is factorized there once, so that
/// backward() differentiates the polished point's active set with the forward machinery:
/// W = s/z = μ/z² on active sides (1e-14 at z = 1) and s²/μ on inactive ones (1e14 at
/// s = 1); a weakly active side (z = s = √μ) gets W = 1, between the two.
constexpr double kPolishMu = 1e-14;
/// Least-norm multipliers (step 3c): regularization δ/max|M|² of the quasi-definite system,
/// refinement steps per solve and active-set rounds (pinned sign components).
constexpr double kLeastNormDelta = 1e-12;
constexpr int kLeastNormRefinement = 30;
constexpr int kLeastNormRounds = 8;
/// A least-norm solve counts when its stationarity error ‖Px + q + Mw‖∞ is at most this
/// many times that of the multipliers it replaces (or the polish's sign threshold).
constexpr double kLeastNormStationarity = 10.0;
/// Passes of step 3c (least-norm multipliers, then the reduced system again from them).
constexpr int kLeastNormPasses = 3;

struct PolishOutcome {
  int rounds = 0;          ///< reduced systems factorized
  bool found = false;      ///< a candidate without wrong-sign multipliers exists
  Residuals residuals;     ///< its unscaled residuals (compute_residuals)
};

/// Polishes on the active set guessed from `it` (the final iterate of a run on f, p).
/// `before` are the residuals of the unpolished result (they set tol_p and tol_d). On
/// found, `candidate` holds the best polished point (x, y, z, z_bounds; info untouched).
/// Allocates (a new reduced pattern per round); uses w's unscaled products as scratch.
/// Step 3b: a row (of A, an equality row of G, or an active side of G, `rows`: 0 inactive,
/// ±1 active side) all of whose variables sit at an active bound (`bounds`: ±1) or are fixed is
/// a forcing constraint: shifting its multiplier ω by Δ moves only the bound multipliers of
/// those variables, z_b,j = t_j − a_j·Δ with t_j = −(Px + q + Aᵀy + Gᵀz)_j, so stationarity
/// holds for every Δ. ω is set to its value of smallest |ω| that keeps ω's sign (active side)
/// and every z_b,j's sign (≤ 0 at a lower bound, ≥ 0 at an upper one; free at a fixed
/// variable) no worse than at Δ = 0, in up to kForcingRowPasses passes over the rows. The
/// interior point's multiplier of such a row is not unique and grows along the central path
/// (the analytic centre of an unbounded set), and its term ω·bound then dominates the gap
/// (QBORE3D: rows l = u = −1.78e-15, ω ~ 1e6). The dual postsolve of forcing constraints:
/// Andersen & Andersen, "Presolving in linear programming", Math. Prog. 71, 1995, §3;
/// Gondzio, INFORMS J. Comput. 9, 1997. `target` holds t on entry and the shifted t on
/// return; cand.y, cand.z are updated. Returns the number of shifts. Allocates.
int shrink_forcing_row_multipliers(const StandardForm& f, const QpProblem& p, const std::vector<signed char>& rows,
                                   const std::vector<signed char>& bounds, QpResult& cand, Vector& target);

/// Step 3c: replaces cand's multipliers (y, z, z_bounds) on the active set (`rows`, `bounds`
/// as above; equality rows and fixed variables always active, free sign) by the sign-keeping
/// ones of least 2-norm (method in qp_polish_least_norm.cpp), given cand.x. A solve counts
/// when its stationarity error is at most max(tol_d, kLeastNormStationarity × that of cand's
/// multipliers). Returns false, leaving
/// cand untouched, when no solve succeeds or the largest multiplier does not shrink. Allocates.
bool least_norm_multipliers(const StandardForm& f, const QpProblem& p, const std::vector<signed char>& rows,
                            const std::vector<signed char>& bounds, double tol_d, QpResult& cand);

PolishOutcome polish_solution(const StandardForm& f, const QpProblem& p, const Iterate& it, const QpSettings& s,
                              const Residuals& before, QpResult& candidate, Workspace& w);

}  // namespace lcprelax::detail
