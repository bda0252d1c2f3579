#pragma once
// Linear complementarity problem, solver statuses, settings and results.
//
//     find z, w  with  w = M z + q,   0 ≤ z ⊥ w ≥ 0      (M n×n, q n)
//
// Residual reported on every solve (Info::complementarity): max_i |min(z_i, w_i)| with w
// recomputed as Mz + q from the returned z, i.e. 0 exactly at a solution; it is the
// natural-map residual in the ∞-norm.
#include <lcprelax/sparse/types.hpp>

#include <limits>
#include <string>
#include <vector>

namespace lcprelax {

/// The outcome of a solve. Misuse (wrong sizes, NaN data, invalid settings) is not a status:
/// it throws InputError.
enum class LcpStatus {
  unsolved,         ///< solve() was not called
  solved,           ///< complementary basis found, residual within tolerance
  ray_termination,  ///< Lemke's ray: no solution found (infeasible, or M outside the classes Lemke covers)
  pivot_limit,      ///< stopped at LemkeSettings::max_pivots
  numerical_error   ///< singular basis or residual above tolerance after refactorization
};

constexpr const char* to_string(LcpStatus s) {
  switch (s) {
    case LcpStatus::unsolved: return "unsolved";
    case LcpStatus::solved: return "solved";
    case LcpStatus::ray_termination: return "ray_termination";
    case LcpStatus::pivot_limit: return "pivot_limit";
    case LcpStatus::numerical_error: return "numerical_error";
  }
  return "unknown";
}

/// Whether a result with this status carries a usable solution (z, w complementary within
/// the residual tolerance).
constexpr bool has_solution(LcpStatus s) { return s == LcpStatus::solved; }

/// How Lemke's basis is factorized (lemke.hpp): dense explicit inverse (O(n²) memory,
/// fast for small n) or sparse KLU LU with block updates (O(nnz) memory).
enum class LemkeMethod { automatic, dense, sparse };

constexpr const char* to_string(LemkeMethod m) {
  switch (m) {
    case LemkeMethod::automatic: return "automatic";
    case LemkeMethod::dense: return "dense";
    case LemkeMethod::sparse: return "sparse";
  }
  return "unknown";
}

/// Column ordering of a sparse LU factorization (LemkeSettings::lu_ordering).
enum class LuOrdering { amd, colamd };

constexpr const char* to_string(LuOrdering o) { return o == LuOrdering::colamd ? "colamd" : "amd"; }

struct LemkeSettings {
  /// automatic: dense when n ≤ dense_max_n, else sparse.
  LemkeMethod method = LemkeMethod::automatic;
  /// Largest n solved densely by `automatic` (measured crossover, bench/README.md).
  int dense_max_n = 32;
  /// Pivot limit; 0 means 50·(n + 1), plus 2ⁿ for n < 20 (enough for Murty's examples),
  /// capped at 10⁷. Contact LCPs take a few pivots per unknown.
  long max_pivots = 0;
  /// Zero tolerance of the pivot entries and of the lexicographic ties; 0 means
  /// 10·n·ε·max(1, ‖M‖∞) (scaled as in Drake's MobyLCP). The pivoting runs on q/‖q‖∞ (the
  /// solution scales with q), so ties are scale-free and tiny q (resting contact) works.
  double pivot_tolerance = 0.0;
  /// Accepted complementarity residual max|min(z, w)|; 0 means 1e-9·‖q‖∞ (relative to q,
  /// as the Siconos error ‖z − max(0, z − w)‖₂/‖q‖₂ is).
  double residual_tolerance = 0.0;
  /// Refactorize the basis from scratch every this many pivots (drift control; for the
  /// sparse method also the largest Schur-complement update, memory n·interval doubles).
  int refactor_interval = 50;
  /// Partial-pivoting threshold u ∈ (0, 1] of the sparse method's LU of the basis
  /// (sparse::KluLu::set_pivot_tolerance: |L_ij| ≤ 1/u). 1 (true partial pivoting) rather
  /// than KLU's sparsity-favouring 0.001: on degenerate pile LCPs the threshold pivots let
  /// a fresh factorization of a basis that the updates still solved accurately lose it
  /// (x_B drifting by O(‖q‖) at one refactorization), and the path then ends on a ray or a
  /// false solution. Measured on 500-body piles with the LCP model (bench/results/
  /// lemke_lu_pivoting.txt, 3 seeds): 11,027 pivots and 3.5 s per step with 1 against 16,472
  /// and 5.2 s with 0.001, about the same time per pivot; exported piles of 100–300 bodies
  /// take the same paths, the Siconos files keep their statuses. The dense method always
  /// pivots fully (ignored there).
  double lu_pivot_tolerance = 1.0;
  /// Fill-reducing column ordering of the sparse method's LU of the basis
  /// (sparse::KluLu::set_ordering). colamd (default): COLAMD on the basis' columns, which
  /// orders for the Cholesky factor of BᵀB, a bound on L and U under any row interchanges
  /// (George & Ng 1987; Davis, Gilbert, Larimore & Ng 2004), as the true partial pivoting
  /// above makes them; amd: KLU's own default, AMD on B + Bᵀ, which assumes diagonal pivots.
  /// Measured on the lifted bases of a settled 1,000-body pile solved on M + εI (the LCP
  /// model's regularized answers, bench/results/lemke_lu_ordering.txt): COLAMD's L + U about
  /// 307,000 entries against AMD's 588,000, a fresh factorization 7.5 ms against 19 ms
  /// (analysis 4.2 against 2.8 ms), one reusing the pivots 3.4 against 10 ms; on the bases
  /// of M there about the same (99,000 and 97,000 entries, 1 ms). On the six 500-body LCP
  /// pile windows (bench/results/pile_scaling_lcp_windows.txt) COLAMD took less time per
  /// step on five (seed 3: 1.9 s against 6.5 s, whose regularized paths on M + εI had cost
  /// 0.47–0.73 ms per pivot with AMD), 10% more on seed 4, 0.87–1.07× the CPU time per
  /// pivot on all but seed 3; failed islands 0 and the same inexact ones or fewer. A 500-body
  /// drop (120 steps) took 0.74 against 0.72 s per step, with the same 6 inexact answers.
  /// Ignored by the dense method.
  LuOrdering lu_ordering = LuOrdering::colamd;
  /// Lexicographic tie-breaks on the rows of B⁻¹ formed with their nonzeros only (true:
  /// hypersparse transposed solves on the sparse basis, only the columns where a tied row
  /// is nonzero visited) or as full rows (false: the reference, one dense transposed solve
  /// per tied row). Same decisions up to the roundoff of the solves (lcp/src/lemke_lexicographic.hpp).
  bool sparse_tie_rows = true;
  /// Entering columns B⁻¹a of the sparse method solved from a's nonzeros (true: hypersparse
  /// solves with the factors of B₀, only the factors' entries that the solution reaches
  /// visited, sparse/hypersparse_column_solve.hpp; once the solved columns are denser than
  /// 10%, a dense solve with the same factors that skips the columns of zero entries, which
  /// repeats klu_solve bit for bit) or by KLU's dense triangular solve (false: the
  /// reference). Same pivots up to the roundoff of the hypersparse solves.
  bool sparse_columns = true;
  /// Factorize the sparse method's bases in the lifted form when setup() was given one
  /// (LcpLiftedForm: K of lcp/src/lemke_basis.hpp, the momentum equations kept as rows
  /// instead of the Delassus products): the same solves up to roundoff from sparser factors.
  /// false: the basis B₀ of M's columns (the reference). Ignored without a lifted form and
  /// by the dense method. Measured on 500-body LCP piles (bench/results/lemke_lifted_basis.txt):
  /// factors ~40% smaller, entering columns 4–8% nonzero instead of ~50% (mostly roundoff),
  /// 1.22–1.38× less time per pivot.
  bool lifted_basis = true;
  /// Retries after a ray termination or numerical failure (not after the pivot limit):
  /// first `covering_retries` solves with perturbed covering vectors (d_i·(1 + (i mod 7)/7),
  /// then d_i·(1 + 10⁻³i), alternating), then `regularization_retries` solves on M + εI with
  /// ε = regularization·max(1, ‖M‖∞)·100ᵏ. A retry's z is accepted only if it solves the
  /// original LCP to residual_tolerance, so a genuinely unsolvable LCP still ends in its
  /// first failure status. Meant for degenerate contact LCPs (redundant and wedged
  /// contacts), where roundoff sends the pivot path to a secondary ray; backward() then
  /// differentiates with the accepted retry's basis. Set both to 0 for plain Lemke.
  int covering_retries = 2;
  int regularization_retries = 2;
  double regularization = 1e-10;
  /// Covering vector d > 0 of the artificial variable (empty: all ones).
  Vector covering;
  /// When a warm-start basis (LemkeSolver::warm_start) is singular, repair it, and when it
  /// factorizes but its basic solution is infeasible, run Lemke from it (a crash start,
  /// lemke.hpp) before the cold start from the all-w basis. For a basis close to the
  /// solution's (fc2d_pgs.hpp: granular 667 contacts, 568 pivots against 1,405 cold). Off by
  /// default: from the previous time step's basis (the simulator's warm start) the crash
  /// paths are long and often fail when run unbounded (200-body LCP pile: 35,603 pivots per
  /// step against 19,545 cold, bench/run_pile_scaling); the LCP contact model therefore runs
  /// it capped at n/2 pivots without the cold fallback (crash_cold_fallback = false,
  /// models/contact_step.hpp), where it pays on about one step in three; from a PGS basis of the pile's island LCP too (crash
  /// paths end on a ray or a singular basis within 1–34 pivots, then the cold start runs).
  /// The Siconos fc2d problems are where it pays (`lcprelax fc2d --crash pgs`; granular
  /// 2,020 contacts: 1,900 pivots against 5,274 cold), and the LCP contact model's polish
  /// of a perturbed solution (models/contact_step.hpp: 0–30 pivots from its basis).
  bool crash_start = false;
  /// After a failed crash path (or a warm basis that does not factorize), run the cold
  /// start in the same solve (true), or stop with the crash path's status (false: the
  /// caller has its own cold attempt; max_pivots then bounds the crash path alone).
  bool crash_cold_fallback = true;
  /// Covering vector of a crash path: d = B·1 for the warm basis B (true: z₀ enters at the
  /// most negative basic value), or the settings' covering vector (false): for a basis that
  /// solves the perturbed LCP q + δd, the path is then the homotopy from q + θd (θ ≤ δ)
  /// back to q. A negative basic value that d does not raise ((B⁻¹d)_i ≤ 0) makes the start
  /// inadmissible: the crash path stops with numerical_error.
  bool crash_covering_from_basis = true;
  /// Rounds of block principal pivoting on a crash basis before Lemke runs from it: the
  /// basic variables that are negative are exchanged for their complements while the count
  /// of negative ones falls (lemke_crash.cpp). 0: off. Granular fc2d from a 50-sweep PGS
  /// basis: 667 contacts 33 pivots against 568 without, 2,020 contacts 1,383 against 1,900
  /// (tests/lcp_crash_flip_test.cpp). The LCP contact model's crash paths run without it
  /// (models/src/lcp_model.cpp: not measured there).
  int crash_flip_rounds = 5;

  /// Empty when valid, else a message naming the first bad field.
  std::string validation_error() const;
};

/// The structure of a contact LCP's matrix, M = J·diag(d)·Jᵀ + H (LemkeSolver::setup's
/// optional argument): J (n × m) maps the m generalized velocities to the LCP's rows (a row
/// of zeros where a row has no velocity, e.g. a friction slack), d > 0 the inverse masses
/// (the diagonal of M⁻¹), H (n × n) the rest (compliance, friction coefficients, the
/// ±1 couplings of the friction slacks). Units are M's. The sparse Lemke basis then
/// factorizes the momentum equations with the basis instead of the Delassus products
/// (LemkeSettings::lifted_basis). setup() checks the identity on two probe vectors
/// and throws InputError when it does not hold to 1e-8 relative.
struct LcpLiftedForm {
  SparseMatrix J;
  Vector d;
  SparseMatrix H;
};

struct LcpInfo {
  LcpStatus status = LcpStatus::unsolved;
  std::string message = "solve() was not called";
  long pivots = 0;
  double complementarity = std::numeric_limits<double>::quiet_NaN();  ///< max|min(z, w)|
  double seconds = 0.0;
  bool warm_started = false;  ///< the warm-start basis was complementary and feasible
  bool crash_started = false;  ///< Lemke ran from the (infeasible) warm-start basis
  long crash_pivots = 0;       ///< pivots of that crash path (included in pivots)
  long tie_breaks = 0;      ///< pivots whose ratio test compared rows of B⁻¹ (lexicographic ties)
  int repair_rounds = 0;    ///< rounds of basis repair of a singular crash basis (lemke_crash.cpp)
  LemkeMethod method = LemkeMethod::automatic;  ///< dense or sparse: the one used
  long refactorizations = 0;  ///< basis factorizations from scratch
  long ray_rechecks = 0;  ///< rays found with an updated factorization, rechecked after a fresh one
  /// Pivots whose basis update was ill-conditioned (sparse method: Schur complement's rcond
  /// estimate in (1e-15, 1e-12]) and whose updated basic values were checked by their
  /// residual instead of refactorizing at once; of these, `update_refactorizations` failed
  /// the check (residual above 1e-10·max(1, ‖M‖∞)·max(1, ‖x_B‖∞), normalized units).
  long update_checks = 0;
  long update_refactorizations = 0;
  /// Steps of the purification of a warm-start point (LemkeSolver::warm_start_point,
  /// lemke_purify.cpp): superbasic z_j driven to 0 or into the basis; not counted in pivots.
  long purification_steps = 0;
  double regularization = 0.0;  ///< ε of the accepted retry on M + εI, 0 if none
  /// The solver holds M as a matrix: given to setup(M, q, ...), or formed from the lifted
  /// form when a solve after setup(lifted, q) needed its columns (false: it never did).
  bool matrix_formed = true;
};

struct LcpResult {
  Vector z;
  Vector w;
  /// Final basis: basis[i] = true if z_i is basic (else w_i); usable as a warm start.
  std::vector<bool> z_basic;
  LcpInfo info;
};

/// ∂ℓ/∂M (on M's sparsity pattern) and ∂ℓ/∂q.
struct LcpGradient {
  SparseMatrix dM;
  Vector dq;
};

}  // namespace lcprelax
