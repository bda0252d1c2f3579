#pragma once
// Lemke's complementary pivoting method with lexicographic anti-cycling, dense or sparse.
//
// Method (Cottle, Pang & Stone, "The Linear Complementarity Problem", 1992, §4.4): with a
// covering vector d > 0 and artificial z₀, start from the almost-complementary basis
// {w} of  w − Mz − d z₀ = q, bring z₀ in at the most negative q_i/d_i, and then let the
// complement of each leaving variable enter, until z₀ leaves (solved) or an entering
// column has no positive entry (ray termination). Minimum-ratio ties are broken
// lexicographically on the rows of [B⁻¹q, B⁻¹], which prevents cycling on degenerate
// problems. Two factorizations of the basis (LemkeSettings::method):
// - dense: B⁻¹ kept explicitly (O(n²) memory and work per pivot, product-form update,
//   refactorized every refactor_interval pivots and at the end): for small n;
// - sparse: KLU LU of the basis at the last refactorization plus a Schur-complement block
//   update of the columns replaced since (Eldersveld & Saunders 1992), refactorized every
//   refactor_interval replacements, and earlier when an update is ill-conditioned (the
//   Schur complement's condition estimate beyond 1e12) and the updated basic values' residual
//   ‖q − B x_B‖∞ exceeds 1e-10·max(1, ‖M‖∞)·max(1, ‖x_B‖∞) (normalized units), or beyond
//   1e15 at once (LcpInfo::update_checks): memory O(nnz(LU) + n·refactor_interval), no
//   dense n×n array. Rows of B⁻¹ for the tie-breaks are formed only for rows still tied after the
//   ratio test, with their nonzeros only (hypersparse transposed solves with B₀'s factors;
//   LemkeSettings::sparse_tie_rows, lcp/src/lemke_lexicographic.hpp).
// `automatic` uses dense for n ≤ dense_max_n (measured crossover, bench/README.md). Both
// give the same pivot sequence up to roundoff in ties.
//
// Warm start: a basis (which of z_i / w_i is basic) whose basic solution is feasible
// solves in zero pivots. If it factorizes but is infeasible, Lemke runs from it (crash
// start, LemkeSettings::crash_start): the covering vector becomes d = B·1, so that z₀
// enters at the most negative basic value, and the pivots continue as in Lemke's method on
// the LCP transformed by that basis (a good guess, e.g. from an approximate solution, leaves
// a short path); if that path does not end solved, the solve starts cold (from the all-w
// basis, the covering vector of the settings) and the pivots of both count. When the
// warm basis is the one the solver already holds factorized (the final basis of the
// previous solve, M unchanged), it is not factorized again.
//
// Purified start (warm_start_point): an approximate solution z̃ of a degenerate LCP, e.g.
// of a jammed pile whose contacts outnumber the bodies' degrees of freedom (an interior-
// point or Gauss–Seidel answer that loads every contact), suggests a basis {z_j : z̃_j >
// w̃_j} that is singular, and dropping its dependent columns (the repair above) makes the
// basic solution infeasible. Purification instead moves the point along directions that
// keep w = Mz + q: the dependent z_j (superbasic) are driven to zero one at a time, and a
// basic variable that reaches zero first leaves the basis for it, until the z-columns with
// nonzero values are independent (the crossover of interior-point LP codes: Megiddo, "On
// finding primal- and dual-optimal bases", ORSA J. Comput. 3, 1991; Bixby & Saltzman,
// "Recovering an optimal LP basis from an interior point solution", Oper. Res. Lett. 15,
// 1994). Cost: one column solve and basis update per superbasic variable, like a pivot
// (LcpInfo::purification_steps; not counted in pivots). Allocates (a crash start only).
//
// Memory: setup() sizes everything the solver works with (the basis factorization's
// arrays, x_B, the solved entering column, the ratio-test row lists, the tie-break buffers:
// 4n nonzeros of B⁻¹ rows, or with full rows n columns dense, min(n, 64) sparse). A
// repeated solve() of the same size then allocates nothing on the dense basis; on the
// sparse basis only KLU's factorizations from scratch allocate (klu_analyze/klu_factor,
// and the storage of the row-wise copy of the factors for the tie-breaks: at a warm basis
// that is not already factored, every refactor_interval pivots, and for the final basis),
// the pivots between them do not. Exceptions: the tie buffers grow when a tie is larger
// than ever before on this solver, and the retries after a failure copy M.
//
// Backward: at a solution with complementary basis B (columns e_i for basic w_i and −M_:j
// for basic z_j), the basic values are x_B = B⁻¹q, so for ℓ(z):
//     λ = B⁻ᵀ g   (g = ∂ℓ/∂x_B: ∂ℓ/∂z_j on basic z_j, 0 on basic w_i),
//     ∂ℓ/∂q = λ,   ∂ℓ/∂M_ij = λ_i z_j,
// one transposed solve with the final basis, no refactorization. At a degenerate solution
// (z_i = w_i = 0 for some i) the solution map is not differentiable; the result is the
// derivative for the final basis, i.e. one of the one-sided derivatives, and which one
// depends on the pivot path.
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/sparse/klu_lu.hpp>

#include <memory>
#include <vector>

namespace lcprelax {

/// A sparse LU factorization that LemkeSolvers hand on from one solve to the next, one
/// solver at a time (LemkeSolver::share_factorization): when a basis to factorize has the
/// pattern of the one factorized before in it, KLU's symbolic analysis (BTF and COLAMD
/// orderings, which depend on the pattern only) is reused, and so is the pivot order of
/// the numeric factorization held (klu_refactor, no pivot search), unless the result's
/// condition estimate falls below 0.1 times that of the factorization that chose the
/// pivots (then a pivoted factorization runs). For a caller that solves a sequence of LCPs
/// from the previous basis (a simulated pile at rest: the warm basis and the pattern of M
/// repeat from step to step, and the values move little): where partial pivoting would
/// choose the same pivots, the factors and every result are the same as without sharing,
/// bit for bit (tests/lcp_shared_factorization_test.cpp); where it would choose others,
/// they differ by roundoff, and the solve's residual check decides as always.
struct LemkeSharedFactorization {
  sparse::KluLu klu;
  long analyses = 0;        ///< symbolic analyses done in it
  long factorizations = 0;  ///< numeric factorizations (each after an analysis or reusing one)
  long reused_pivots = 0;   ///< of these, refactorizations with the held pivot order
};
std::shared_ptr<LemkeSharedFactorization> make_lemke_shared_factorization();

class LemkeSolver {
 public:
  explicit LemkeSolver(LemkeSettings settings = {});
  ~LemkeSolver();
  LemkeSolver(LemkeSolver&&) noexcept;
  LemkeSolver& operator=(LemkeSolver&&) noexcept;

  /// Validates (square M, sizes, finite values, covering > 0; throws InputError).
  void setup(const SparseMatrix& M, const Vector& q);
  /// As above, with M's lifted form M = J diag(d) Jᵀ + H (lcp_types.hpp LcpLiftedForm),
  /// used by the sparse basis' factorizations (LemkeSettings::lifted_basis); throws
  /// InputError on sizes that do not match, non-finite entries, d ≤ 0, or a form that
  /// does not equal M (two probe vectors, relative 1e-8). A later setup(M, q) drops it.
  void setup(const SparseMatrix& M, const Vector& q, const LcpLiftedForm& lifted);
  /// M given by its lifted form only, M = J diag(d) Jᵀ + H (n = q.size()); same checks of
  /// the form. M itself is formed (Eigen sparse products, same values as a Delassus M to
  /// roundoff) only when the solve needs its columns: a pivot that brings in a z, a crash
  /// start or purification, the retries, backward(). A warm basis that solves the LCP is
  /// factorized in the lifted form and checked with w = J (d ∘ Jᵀz) + Hz + q, so a
  /// simulator step at rest never forms M. The tolerances (pivot tolerance, the retries' ε)
  /// scale with the bound ‖|J| (d ∘ |J|ᵀ1) + |H| 1‖∞ ≥ ‖M‖∞ instead of ‖M‖∞ itself. With
  /// the dense method or LemkeSettings::lifted_basis off, M is formed here. A backward()
  /// that forms M changes the solver: do not call it from two threads at once on a solver
  /// set up this way (result() and solved LCPs' z, w stay as they are).
  void setup(const LcpLiftedForm& lifted, const Vector& q);
  /// New q (same n), keeping M.
  void update_q(const Vector& q);
  /// Basis to try first in the next solve() (size n; true = z_i basic).
  void warm_start(const std::vector<bool>& z_basic);
  /// Approximate solution z (size n, user units, finite; negative entries count as 0) to
  /// start the next solve() from: it is purified into a vertex basis (below), which is
  /// then used as a warm_start basis (crash start when LemkeSettings::crash_start is on).
  /// Where purification does not end in a complementary basis, `fallback` (size n; empty:
  /// {z_j : z_j > w_j}, the basis the point suggests) is used instead. Replaces a
  /// warm_start basis given before; requires setup() (throws std::logic_error, and
  /// InputError on a wrong size or a non-finite entry).
  void warm_start_point(const Vector& z, const std::vector<bool>& fallback = {});
  const LcpResult& solve();
  /// Gradient of ℓ(z) given ∂ℓ/∂z; requires status solved (else std::logic_error).
  LcpGradient backward(const Vector& dl_dz) const;
  const LcpResult& result() const;
  /// Instrumentation: hook(true) before and hook(false) after every factorization of the
  /// basis from scratch (allocation-counting tests exclude KLU's factorizations with it);
  /// nullptr (the default) for none.
  void set_refactorization_hook(void (*hook)(bool starting));
  /// When not null, every pivot appends its entering and its leaving variable (numbering
  /// of lemke_basis.hpp: w_i = i, z_j = n + j, z₀ = 2n) to *trace, the first `max_pivots`
  /// pivots only when max_pivots ≥ 0 (no allocation when the caller reserved 2·max_pivots
  /// entries; the lcp model reads the start of a failed crash path so); nullptr (the
  /// default) for none. The trace is appended to, never cleared, by solve().
  void set_pivot_trace(std::vector<Index>* trace, long max_pivots = -1);
  /// Factorize this solver's bases (sparse method only; the dense one ignores it) in
  /// `shared` from the next setup() on; nullptr: a factorization of its own (the default).
  /// The solver keeps `shared` alive, and it must not be used by another solver until this
  /// one is destroyed or set up again without it: it holds this solver's factors
  /// (backward() and result() of a solved LCP use them).
  void share_factorization(std::shared_ptr<LemkeSharedFactorization> shared);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lcprelax
