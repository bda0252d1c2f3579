#pragma once
// Small dense QP solver for batches of tiny problems (learning layers: a relaxed LCP of a
// few contacts, a block's 9-variable QP), with the same problem, result and gradient types
// and the same statuses and tolerances as QpSolver (qp_solver.hpp, qp_settings.hpp).
//
// Methods, in this order (DenseQpMethod::active_set_first; interior_point skips the first):
// 1. Where P is positive definite: the dual active-set method of Goldfarb & Idnani ("A
//    numerically stable dual method for solving strictly convex quadratic programs", Math.
//    Programming 27, 1983; kkt/src/dense_qp_active_set.cpp): exact up to roundoff in a few
//    O(n²) active-set changes, with P's Cholesky factor kept while P's values repeat
//    (a batch with one P). Its point is accepted only if it passes the termination test.
// 2. Mehrotra's primal-dual predictor-corrector (Mehrotra 1992; Wright 1997, ch. 11) on the
//    one-sided form
//     minimize ½xᵀPx + qᵀx   s.t.  A'x = b',  Cx − s = d,  s ≥ 0   (multipliers y', λ ≥ 0)
// where A' holds A's rows plus G's equality rows (l_i = u_i) and fixed variables, and C the
// finite sides of the other rows and bounds (lower side: +g_i, d = l_i; upper side: −g_i,
// d = −u_i). Each Newton system is reduced to the normal matrix K = P + Cᵀ diag(λ/s) C
// (+ ρI, ρ = 1e-12·max(1, max |P_jj|) raised tenfold while the Cholesky factorization
// fails) and, with equality rows, its Schur complement A'K⁻¹A'ᵀ (+ δI, δ as ρ), both by
// dense Cholesky. No equilibration: it is meant for problems whose data are O(1).
// 3. A problem neither solves (not within 60 interior-point iterations, failed
// factorizations, infeasible) is handed to QpSolver with the same settings (QpInfo::message
// says so), so the status and the solution are QpSolver's then, including infeasibility
// certificates. QpInfo::message names the method that solved.
//
// Termination: the unscaled residuals of qp_settings.hpp (primal, dual, gap; infinity
// norms; eps_abs + eps_rel·scale), computed from the returned x, y, z, z_bounds in the
// conventions of qp_problem.hpp. Only `solved` comes out of the dense iteration.
//
// Backward (OptNet, Amos & Kolter 2017): the adjoint of the KKT conditions
//     Px + q − A'ᵀy' − Cᵀλ = 0,  A'x = b',  λ∘(Cx − d) = 0
// at the final iterate, written with c̃ = Λc as the quasi-definite system
// [P A'ᵀ Cᵀ; A' 0 0; C 0 −W] (W = S Λ⁻¹), whose sides with W ≥ 1 are eliminated into
// P + Cᵀ W⁻¹ C and whose sides with W < 1 (the active ones, W → 0) stay as rows of a Schur
// complement, so that nothing of size 1/W enters a factor; solve() factorizes it at the
// final iterate (backward() adds no factorization) and backward() refines against the
// unregularized system (≤ 3 steps, until its relative residual is ≤ 1e-12). Weakly active
// constraints (slack and multiplier both ≤ eps_abs: the derivative does not exist) get,
// after the interior point, its final interpolation W = s/λ, as in QpSolver; after the
// active-set method (W = 0 on the strictly active set, ∞ off it) the central-path limit
// W_k = c_kᵀZ(ZᵀPZ)⁻¹Zᵀc_k (Z: null space of the strictly active rows), which gives the
// mean of the two one-sided derivatives, what central differences approach (exactly for
// one such constraint; for several, each as if alone). The result uses
// QpGradient's conventions (dP on P's upper pattern, equality rows' derivative on the side
// the multiplier says is active, zero for infinite bounds); adjoint_residual is the
// relative residual of the unregularized adjoint system.
//
// Memory: setup() sizes the work arrays, so the iterations of solve() do not allocate; the
// final factorization and backward(…, out) use buffers kept between calls (a few small
// vectors are resized when the active set's size changes). Use: lcprelax.QpBatch / QpLayer
// pick it for small problems (engine "auto").
#include <lcprelax/kkt/qp_gradient.hpp>
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/kkt/qp_result.hpp>
#include <lcprelax/kkt/qp_settings.hpp>

#include <memory>

namespace lcprelax {

/// How DenseQpSolver solves: first the exact dual active-set method (strictly convex
/// problems; the interior point where it fails), or the interior point alone.
enum class DenseQpMethod { active_set_first, interior_point };

class DenseQpSolver {
 public:
  /// Largest n + (rows of A) + 2·(rows of G) + 2n (every side of every row and bound
  /// finite) this solver is meant for: the dense work grows like n², factorizations like n³.
  /// Measured (random strictly convex QPs, batch 1,024, solve + backward, 1 thread): 7–10×
  /// faster than QpSolver from 3n + 2m = 25 to 125 (bench/run_qp_layer_random.py).
  static constexpr Index kMaxDimension = 128;

  explicit DenseQpSolver(QpSettings settings = {}, DenseQpMethod method = DenseQpMethod::active_set_first);
  ~DenseQpSolver();
  DenseQpSolver(DenseQpSolver&&) noexcept;
  DenseQpSolver& operator=(DenseQpSolver&&) noexcept;
  DenseQpSolver(const DenseQpSolver&) = delete;
  DenseQpSolver& operator=(const DenseQpSolver&) = delete;

  /// Whether `problem`'s sizes are small enough for the dense solver (kMaxDimension;
  /// decided by the sizes alone, so the same for every problem of one pattern).
  static bool suits(const QpProblem& problem);

  /// Validates (throws InputError, like QpSolver) and copies the problem into dense storage.
  void setup(const QpProblem& problem);
  /// New values with the same sizes and sparsity pattern (throws InputError otherwise).
  void update(const QpProblem& problem);
  const QpResult& solve();
  /// Adjoint pass at the last solution (status solved or solved_inaccurate, else throws
  /// std::logic_error); dl_dy, dl_dz may be empty (zero).
  QpGradient backward(const Vector& dl_dx, const Vector& dl_dy = Vector(), const Vector& dl_dz = Vector());
  /// The same into `out`, reusing its storage when it already holds this problem's patterns.
  void backward(const Vector& dl_dx, const Vector& dl_dy, const Vector& dl_dz, QpGradient& out);
  const QpResult& result() const;
  /// Whether the last solve() was handed to QpSolver.
  bool used_fallback() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lcprelax
