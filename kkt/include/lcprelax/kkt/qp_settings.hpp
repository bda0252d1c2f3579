#pragma once
// Settings of the interior-point QP solver, with documented defaults.
//
// Termination (all infinity norms, on the UNSCALED problem, as qpbenchmark measures):
//   primal residual  max(‖Ax − b‖, ‖dist(Gx, [l,u])‖, ‖dist(x, [xl,xu])‖) ≤ eps_abs + eps_rel·scale_p
//   dual residual    ‖Px + q + Aᵀy + Gᵀz + z_bounds‖ ≤ eps_abs + eps_rel·scale_d
//   duality gap      |xᵀPx + qᵀx + bᵀy + Σ support terms of z and z_bounds| ≤ eps_abs + eps_rel·scale_g
// where scale_p, scale_d, scale_g are the largest norms of the terms in each expression.
#include <limits>
#include <string>

namespace lcprelax {

/// Which linear system is factorized at each iteration.
enum class KktForm {
  automatic,  ///< the form whose symbolic analysis predicts the smaller nnz(L)
  full,       ///< quasi-definite [P+Σx+ρI, Aᵀ, Gᵀ; A, −δI, 0; G, 0, −W] by CHOLMOD LDLᵀ
  eliminated  ///< SPD P+Σx+ρI + Gᵀ W⁻¹ G by CHOLMOD supernodal LLᵀ (only without equalities)
};

constexpr const char* to_string(KktForm f) {
  switch (f) {
    case KktForm::automatic: return "automatic";
    case KktForm::full: return "full";
    case KktForm::eliminated: return "eliminated";
  }
  return "unknown";
}

/// Fill-reducing ordering of the CHOLMOD KKT factorizations (sparse/cholmod_ldlt.hpp).
enum class KktOrdering {
  automatic,  ///< AMD; where AMD's factor is predicted to cost more than 1e7 flops, also METIS
              ///< and NESDIS nested dissection, keeping the fewest predicted flops (CVXQP1_L:
              ///< 4.4e9 → 9.2e8 flops per factorization, 231 s → 14 s)
  amd         ///< AMD only (the ordering before nested dissection was tried)
};

constexpr const char* to_string(KktOrdering o) {
  switch (o) {
    case KktOrdering::automatic: return "automatic";
    case KktOrdering::amd: return "amd";
  }
  return "unknown";
}

/// Which factorization solves the KKT systems (forward iterations and backward()).
enum class KktBackend {
  automatic,          ///< dense when the full KKT dimension ≤ QpSettings::dense_max_kkt, else
                      ///< cholmod (default; resolved at setup() and update(), reported in
                      ///< QpInfo::kkt_backend)
  cholmod,            ///< CHOLMOD: LDLᵀ of the full form or LLᵀ of the eliminated form
  dense,              ///< dense LDLᵀ with diagonal pivoting (sparse/dense_ldlt.hpp) of the full
                      ///< or the eliminated form, for tiny problems (O(N³) flops, N² memory)
  mumps,              ///< MUMPS LDLᵀ through PETSc, in this process (full form only; needs a
                      ///< PETSc build, sparse/petsc_mumps_ldlt.hpp; not for concurrent threads)
  mumps_distributed   ///< MUMPS LDLᵀ distributed over all MPI ranks: every rank must call
                      ///< setup/solve/backward collectively on the same problem
};

constexpr const char* to_string(KktBackend b) {
  switch (b) {
    case KktBackend::automatic: return "automatic";
    case KktBackend::cholmod: return "cholmod";
    case KktBackend::dense: return "dense";
    case KktBackend::mumps: return "mumps";
    case KktBackend::mumps_distributed: return "mumps_distributed";
  }
  return "unknown";
}

/// Whether the backend runs through PETSc (needs a PETSc build; not thread-safe).
constexpr bool uses_petsc(KktBackend b) { return b == KktBackend::mumps || b == KktBackend::mumps_distributed; }

struct QpSettings {
  double eps_abs = 1e-9;          ///< absolute tolerance on residuals and gap
  double eps_rel = 0.0;           ///< relative tolerance (see header comment)
  double eps_infeasible = 1e-9;   ///< tolerance of infeasibility certificates
  int max_iter = 200;             ///< interior-point iterations
  /// Seconds of one solve(), counted from its start over both runs, polishing and the
  /// infeasibility LPs. A numeric KKT factorization cannot be interrupted: none is started
  /// when its predicted time (the last one measured, or before any the analysis' flop count
  /// at 1e9 flops/s) would end past the limit; the solve then ends with status time_limit.
  double time_limit = std::numeric_limits<double>::infinity();
  double reg_primal = 1e-9;       ///< static primal regularization ρ (scaled problem)
  double reg_dual = 1e-9;         ///< static dual regularization δ (scaled problem)
  double reg_max = 1e-2;          ///< largest regularization tried after failed factorizations
  int max_refinement = 10;        ///< iterative refinement steps against the unregularized KKT
  /// Relative K0 residual of the refined predictor step above which the conservative second
  /// run (the one after a stalled first run, qp_solver.hpp) drops the inequality block's
  /// regularization δ for the rest of that run; the first run drops it only above 1e-8
  /// (kkt/src/qp_ipm_loop.cpp; without δ there the block −1/Dg is still negative definite,
  /// so the matrix stays quasi-definite: Vanderbei 1995). At rows whose s/z falls below δ,
  /// refinement against the unregularized matrix contracts by only δ·Dg/(1 + δ·Dg) per
  /// step; the step's error then stays in the rows' primal residual, which stalls near 1e-9
  /// while μ → 0, and the gap Σ zᵢ·rᵢ with it (LISWET2: relative residuals 1.0…1.4e-9 from
  /// μ ≈ 1e-8 on, gap stuck at 1.3e-5; tests/qp_row_regularization_test.cpp). Measured: with
  /// 1e-9 (or 1e-10) in the first run too, LISWET2 is solved there, but solved contact
  /// problems move out of their tests' tolerances (convex 50-box stack of
  /// tests/models_stiff_cases_test.cpp: residual 6.7e-15 → 1.5e-7), so only the run that
  /// follows a failure uses it.
  double conservative_row_reg_drop = 1e-9;
  /// Primal regularization ρ that replaces reg_primal for the rest of a run once the scaled
  /// dual residual survives two full steps (α > 0.9) in a row, i.e. keeps more than half of
  /// itself where a Newton step would remove it; 0 disables. On a column with
  /// P̃_jj + z/s ≪ ρ (a variable far from its bounds: a large scaled value, its bound
  /// multiplier near 0) refinement against the unregularized matrix contracts by only
  /// ρ/(ρ + P̃_jj + z/s) per step, so a step moves x̃_j by at most about |r_d,j|/ρ; after a
  /// large starting shift the run then stalls with the dual residual at the variable's
  /// reduced cost (QGFRDXPN: scaled r_d 6e-4 for 30 iterations, dual residual 1.7 → 1.9e-6
  /// with the drop). Lowering ρ only on that evidence keeps reg_primal's stabilization
  /// elsewhere: reg_primal = 1e-12 throughout loses LASER, and ρ = reg_primal/max(1, ‖x̃‖∞)
  /// loses LASER and QGROW7. Iterate-driven regularization in the spirit of PIQP (Schwan,
  /// Jiang, Kuhn, Jones, "PIQP: a proximal interior-point quadratic programming solver",
  /// IEEE CDC 2023). tests/qp_primal_regularization_test.cpp. Only while the unscaled dual
  /// residual is above its tolerance: once within it, r_d only jitters at its roundoff
  /// floor, and dropping ρ there lets dual-degenerate LPs' large multipliers drift (gap
  /// stuck at 1e-8). With that guard, on the 288 generated degenerate LPs of
  /// tests/qp_primal_reg_drop_guard_test.cpp: 278 solved against 265 with 0, none lost
  /// (unguarded: 277, 3 lost). tests/qp_polish_test.cpp sets 0 to keep its stalled case.
  /// Off (0) by default: at 1e-13 the convex learning loss's adjoint no longer matches
  /// central differences on a pile island (tests/learn_step_loss_convex_test.cpp, errors up
  /// to 2e-1 relative on friction-row entries), not yet understood; 1e-13 is the value
  /// measured above.
  double primal_reg_drop = 0.0;
  /// Bound-multiplier steps from the dual-residual equation rather than z/s·dx + ξ
  /// (ipm_iterate.hpp); false only to measure what it fixes.
  bool exact_bound_steps = true;
  /// Before each termination test, try the exact multipliers of the variables at a bound
  /// (kkt/src/qp_bound_multipliers.cpp); false only to measure what it fixes.
  bool clean_bound_multipliers = true;
  /// Solution polishing (OSQP's, Stellato et al. 2020, §5.2): when the interior point ends
  /// solved_inaccurate, numerical_error or max_iterations, guess the active set from the
  /// final iterate (slack < multiplier), solve the equality-constrained KKT system on it
  /// (sparse LDLᵀ, refined), correct the guess a few times by multiplier signs and
  /// violated constraints (kkt/src/qp_polish.hpp), and keep the polished point only if all
  /// multipliers have their sign, the worst ratio of its recomputed residuals to their
  /// tolerances is smaller, and it is solved — or, when the interior point was already
  /// solved_inaccurate, every residual is no worse (within 1e-2 of its tolerance). An
  /// accepted point replaces the
  /// interior iterate and the KKT matrix is factorized there once more, so that backward()
  /// differentiates the polished point's active set. Not run after a solved interior point
  /// (solves stay allocation-free) or past time_limit; QpInfo::polish_* report it.
  bool polish = true;
  /// Polishing: give forcing rows (rows all of whose variables sit at an active bound) the
  /// multiplier of smallest magnitude that keeps every sign (their multiplier is not unique
  /// and the interior point's grows along the central path; kkt/src/qp_polish_forcing_rows.cpp).
  bool polish_forcing_rows = true;
  /// Polishing: also try the multipliers of least 2-norm on the polished active set (signs
  /// kept; an active-set least-distance solve, kkt/src/qp_polish_least_norm.cpp). Where the
  /// set of optimal multipliers is unbounded the interior point's grow along the central
  /// path, and the roundoff of the gap's and dual residual's terms grows with them.
  bool polish_least_norm = true;
  /// Gondzio's multiple centrality correctors per iteration (at most; 0 = none) of the
  /// conservative second run, the one that follows a stalled first run (qp_solver.hpp).
  /// Each costs one more solve with the iteration's factor and is kept only if it
  /// lengthens the step (kkt/src/qp_ipm_loop.cpp). Measured: in the second run they solve
  /// QSIERRA (51 of the 64 shared Maros–Meszaros problems instead of 50) and lose one of 288
  /// generated degenerate LPs (tests/qp_degenerate_lp_test.cpp: 265 instead of 266); in
  /// every run they saved 10% of the iterations on the 64 but lost LASER (a gap at its
  /// roundoff floor) and 3 of the 288, so the first run has none.
  int centrality_correctors = 2;
  /// Multiplier-scaled third run (kkt/src/qp_solve.cpp): when the first run and the
  /// conservative second run both end without a solution and the first run's largest
  /// multiplier grew to at least this many times the largest multiplier of its start, one
  /// more run from the cold start with every starting multiplier multiplied by that growth
  /// (0 = never). Mehrotra's start (Mehrotra 1992, §7) makes slacks and multipliers about
  /// equal; on problems whose optimal multipliers are orders of magnitude larger (LISWET:
  /// multipliers ~ n²·|residual| of a convex fit), the slacks reach the boundary while the
  /// multipliers are still small, and every later step is blocked after 1% of its length by
  /// a row whose slack must shrink further (the infeasible central path bends sharply, as in
  /// Wright, "Primal-Dual Interior-Point Methods", SIAM 1997, ch. 6). The failed run has
  /// measured the multipliers' scale: starting there, the iteration converges (LISWET10
  /// solved; tests/qp_multiplier_restart_test.cpp). Only reached by solves that would
  /// otherwise fail, so solved problems and their run times do not change.
  double multiplier_restart_growth = 100.0;
  int ruiz_iterations = 10;       ///< Ruiz equilibration passes (0 disables scaling)
  double step_fraction = 0.995;   ///< fraction to the boundary
  KktForm kkt_form = KktForm::automatic;
  /// CHOLMOD backend only; takes effect at setup().
  KktOrdering kkt_ordering = KktOrdering::automatic;
  /// mumps backends force the full form; takes effect at setup(); solve_qp_batch runs
  /// them on one thread (PETSc is not thread-safe).
  KktBackend kkt_backend = KktBackend::automatic;
  /// automatic: largest full KKT dimension factorized densely, N = n + rows of A + rows of
  /// G with at least one finite side + fixed variables (xl = xu); other bounds add no row.
  /// 0 = always cholmod. 48: between the measured crossovers of sparse and dense problem
  /// data (bench/bench_qp_dense_vs_sparse.cpp; measured crossover, bench/README.md).
  int dense_max_kkt = 48;
  bool verbose = false;           ///< one line per iteration on stderr
  /// When the iteration fails (stalls, diverges, hits max_iter), solve the auxiliary LPs of
  /// qp_infeasibility_lp.cpp that decide primal or dual infeasibility with a certificate.
  bool infeasibility_lps = true;
  /// setup() refuses a P that is not positive semidefinite (InputError naming P: the QP is
  /// nonconvex, and the interior point would end at a saddle or maximum that its residuals
  /// cannot tell from a minimum) by one Cholesky factorization of the scaled P + 1e-9·I;
  /// update() checks P's 2×2 principal minors only (allocation-free). kkt/qp_convexity.hpp.
  /// false only for a caller that has run psd_error() itself (solve_lcp_ipm).
  bool check_convexity = true;

  /// Empty when valid, else a message naming the first bad field.
  std::string validation_error() const;
};

}  // namespace lcprelax
