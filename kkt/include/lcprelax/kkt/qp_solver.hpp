#pragma once
// Sparse primal-dual interior-point QP solver (Mehrotra predictor-corrector) with an
// adjoint backward pass that reuses the final forward factorization.
//
// Method. The problem (qp_problem.hpp) is equilibrated (Ruiz), its two-sided rows and
// bounds are split into one-sided inequalities Cx + s = h, s ≥ 0 with multipliers z ≥ 0,
// and each iteration solves the regularized quasi-definite Newton system
//     [P + Σ_b + ρI   Aᵀ    Cᵀ ] [dx]   [r_x]
//     [A              −δI   0  ] [dy] = [r_y]
//     [C              0    −W  ] [dz]   [r_z]        W = S Z⁻¹ (+δ), Σ_b from bounds
// by CHOLMOD LDLᵀ (KktForm::full) or, without equality rows and where its factor is
// sparser, the SPD Schur complement P + Σ_b + ρI + Cᵀ W⁻¹ C by supernodal LLᵀ
// (KktForm::eliminated). Fill-reducing ordering (QpSettings::kkt_ordering): AMD, and where
// AMD's factor is predicted to cost more than 1e7 flops also METIS and CHOLMOD's nested
// dissection, keeping the ordering with the fewest predicted flops (CVXQP1_L: 4.4e9 → 9.2e8
// flops per factorization). Iterative refinement is done against the unregularized
// system (ρ = δ = 0). A failed factorization raises ρ and δ tenfold (up to reg_max)
// and retries. Mehrotra, "On the implementation of a primal-dual interior point
// method", SIAM J. Optim. 2(4), 1992; Wright, "Primal-Dual Interior-Point Methods", 1997.
//
// A run that stalls (numerical_error, e.g. "no progress in the residuals": Mehrotra's
// corrector can cycle on degenerate problems) is repeated once from the start with a plain
// centred path-following step (σ ≥ 0.1, no second-order correction, Gondzio's correctors,
// the inequality block's δ dropped at QpSettings::conservative_row_reg_drop); its result is kept
// when it is solved (QpInfo::message says so, iterations count both runs). If it fails too
// and the first run's largest multiplier grew at least QpSettings::multiplier_restart_growth
// times over its start, a third run starts from the cold start with its multipliers
// multiplied by that growth (kkt/src/qp_solve.cpp); otherwise, or if that run fails too,
// the first run's outcome is reported.
//
// Polishing (QpSettings::polish, Stellato et al., "OSQP", Math. Prog. Comp. 2020, §5.2): a
// run that ends solved_inaccurate, numerical_error or max_iterations guesses the active set
// from its last iterate (slack < multiplier), solves the equality-constrained KKT system on
// it (CHOLMOD LDLᵀ, iterative refinement), corrects wrongly signed or violated constraints
// (≤ 4 solves), and keeps the polished point only when its recomputed unscaled residuals
// are better and meet eps (kkt/src/qp_polish.hpp); backward() then differentiates the
// polished point's active set. QpInfo::polish_* report it.
//
// Infeasibility is detected by certificates on the iterates (see qp_result.hpp), not by
// running out of iterations.
//
// Lifecycle: setup(problem) → solve() → [update(values, same pattern) → solve()]* →
// backward(dl_dx). update() refuses another sparsity pattern (throws InputError).
//
// Memory: setup() allocates the scaled problem, the KKT pattern and all work vectors. After
// the first solve() (which creates the factorization's own workspaces), solve(),
// update() with the same row classification, and warm_start() perform no heap allocation
// with the dense backend (both forms) and CHOLMOD's LDLᵀ of the full form
// (tests/qp_allocation_test.cpp); CHOLMOD's supernodal LLᵀ of the eliminated form
// allocates inside each numeric factorization (the rest of the loop does not). Exceptions: a
// result message longer than any before, a failed run (numerical_error: the conservative
// second run copies the first result), infeasibility LPs, and update() when a row changes
// between equality, one- and two-sided (a new structure: as setup()).
//
// Backward (OptNet, Amos & Kolter 2017, "OptNet: Differentiable Optimization as a Layer
// in Neural Networks", ICML): at the solution, differentiating the KKT conditions
//     Px + q + Aᵀy + Cᵀz = 0,  Ax = b,  diag(z)(Cx − h) = 0
// gives a linear system whose transpose, after scaling the last block row by Z⁻¹, is the
// final symmetric KKT matrix [P Aᵀ Cᵀ; A 0 0; C 0 −W] of the forward solve. backward()
// solves it once with the final factorization (zero new numeric factorizations; refined
// against the unregularized matrix; the one exception is a solve that ended before its
// first factorization, a warm start already optimal: backward() then re-solves cold and
// uses that factorization, see qp_backward.cpp) for d = (d_x, d_y, d̃_z), and returns
//     ∂ℓ/∂q = d_x,  ∂ℓ/∂b = −d_y,  ∂ℓ/∂h = −d̃_z,
//     ∂ℓ/∂P = ½(d_x xᵀ + x d_xᵀ),  ∂ℓ/∂A = d_y xᵀ + y d_xᵀ,  ∂ℓ/∂C = d̃_z xᵀ + z d_xᵀ,
// mapped back to P, A, G, l, u, xl, xu (qp_gradient.hpp). Strictly inactive constraints
// get zero gradient. At weakly active constraints (z_i = 0 and s_i = 0, where the solution
// map is not differentiable) the result is that of the final interior iterate: W_i = s_i/z_i
// there interpolates between the active and the inactive one-sided derivative.
#include <lcprelax/kkt/qp_gradient.hpp>
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/kkt/qp_result.hpp>
#include <lcprelax/kkt/qp_settings.hpp>

#include <memory>

namespace lcprelax {

class QpSolver {
 public:
  explicit QpSolver(QpSettings settings = {});
  ~QpSolver();
  QpSolver(QpSolver&&) noexcept;
  QpSolver& operator=(QpSolver&&) noexcept;
  QpSolver(const QpSolver&) = delete;
  QpSolver& operator=(const QpSolver&) = delete;

  /// Validates (throws InputError), scales, builds the KKT pattern and index maps, and
  /// performs the symbolic analysis.
  void setup(const QpProblem& problem);
  /// New values with the same sparsity pattern: reuses ordering and analysis, rewrites the
  /// scaled problem in place and redoes the Ruiz equilibration on it (the values equal
  /// those of a fresh setup()). result() becomes unsolved (its vectors keep their storage
  /// and old values until the next solve()). Throws InputError if the pattern or sizes
  /// differ or the data are invalid.
  void update(const QpProblem& problem);
  /// True if setup() was done and `problem` has its sizes and sparsity pattern (the
  /// pattern test of update(), without an exception when it fails).
  bool can_update(const QpProblem& problem) const;
  /// Starts the next solve() from this point (sizes n, me, mi, n); a poor guess is
  /// pushed into the interior, so any finite values are safe.
  void warm_start(const Vector& x, const Vector& y, const Vector& z, const Vector& z_bounds);
  /// Runs the interior point; the returned reference stays valid until the next call.
  const QpResult& solve();
  /// Adjoint pass at the last solution (requires status solved or solved_inaccurate,
  /// else throws std::logic_error). dl_dy and dl_dz may be empty vectors (meaning zero).
  QpGradient backward(const Vector& dl_dx, const Vector& dl_dy = Vector(), const Vector& dl_dz = Vector());

  const QpResult& result() const;
  /// Numeric KKT factorizations since setup() (backward() adds none, except after a
  /// 0-iteration warm-started solve, which it re-solves cold: see the header comment).
  int numeric_factorizations() const;
  const QpSettings& settings() const;
  /// Changes settings (validated, throws InputError) without redoing setup().
  void set_settings(const QpSettings& settings);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lcprelax
