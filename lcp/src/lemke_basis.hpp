#pragma once
// Internal: the basis matrix B of Lemke's method and its factorization.
//
// Variables are numbered [0, n) for w_i, [n, 2n) for z_j, 2n for the artificial z₀; the
// column of B for w_i is e_i, for z_j it is −M(:, j), for z₀ it is −d (covering vector),
// from the tableau  w − M z − d z₀ = q.  basic[k] is the variable of basis position k.
//
// Two implementations:
// - DenseLemkeBasis keeps B⁻¹ explicitly (O(n²) memory and work per pivot): small n.
// - SparseLemkeBasis factorizes B₀ (the basis at the last refactorization) with KLU and
//   represents the column replacements since then by a Schur-complement block update
//   (the block-LU update of Eldersveld & Saunders, "A block-LU update for large-scale
//   linear programming", SIAM J. Matrix Anal. Appl. 13, 1992): with P the replaced
//   positions, C their new columns and W = B₀⁻¹C,
//       B⁻¹ = B₀⁻¹ − (W − E_P) S⁻¹ E_Pᵀ B₀⁻¹,   S = E_Pᵀ W   (|P|×|P|, dense LU),
//   so memory is O(nnz(L+U) + n·|P|) and no dense n×n array is formed. B₀ is refactorized
//   when |P| reaches the refactorization interval (at most kMaxSchurUpdates).
//   Lifted (LemkeColumns::lifted(), from LemkeSolver::setup's LcpLiftedForm M = Ĵ D Ĵᵀ + H,
//   D = diag(d) > 0, Ĵ n × m): instead of B₀, whose z columns hold the Delassus part ĴDĴᵀ
//   (dense among the contacts of a body, and so fill and roundoff in every solve: on pile
//   bases ~50% of the entries of B₀⁻¹c come out nonzero, 1% above 1e-10 of the largest),
//   the sparse basis factorizes the (n + m)-square
//       K = [ E_w − (H + σI) E_z   −Ĵ  ]
//           [ −Ĵᵀ E_z              D⁻¹ ]
//   (E_w, E_z: the basis' w and z columns; σ: a regularization shift, 0 unless Lemke's
//   M + εI retry runs), whose Schur complement on the first n rows is B₀ (the momentum
//   rows give y = D Ĵᵀ E_z x). So B₀⁻¹c is the top of K⁻¹[c; 0] and B₀⁻ᵀr the top of
//   K⁻ᵀ[r; 0]: the same numbers up to roundoff, from sparser factors (the augmented
//   system against the normal equations, as in the convex model's lifted QP and in the
//   mixed-LCP form of rigid-body contact: Anitescu & Potra, "Formulating dynamic multi-
//   rigid-body contact problems with friction as solvable linear complementarity
//   problems", Nonlinear Dynamics 14, 1997). Everything outside the factorization (the
//   tableau, x_B, the residuals) still reads M.
//
// Allocation: both bases own their work arrays, sized at construction (n and the
// refactorization interval are fixed then). solve_column, solve, inverse_rows and replace
// allocate nothing; refactor allocates nothing on the dense basis, and on the sparse one
// only inside KLU's analysis and numeric factorization (klu_analyze, klu_factor allocate
// their Symbolic and Numeric objects) and for the storage of the factors' row-wise copy
// (sparse/hypersparse_solve.hpp), which inverse_row_nonzeros fills at the first tie after
// a refactorization; its output vectors allocate only below capacity n. solve_transposed
// (used by backward() only) allocates a temporary, and so does inverse_rows on a lifted
// basis (full tie rows, LemkeSettings::sparse_tie_rows = false: the reference path).
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/sparse/types.hpp>

#include <memory>
#include <vector>

namespace lcprelax {
struct LemkeSharedFactorization;  // lemke.hpp
}

namespace lcprelax::detail {

/// Largest Schur complement of the sparse basis: an update is refused (forcing a
/// refactorization) when |P| reaches min(refactor_interval, kMaxSchurUpdates). S and its
/// LU live in fixed-capacity storage of this size, so replacing a column never allocates.
inline constexpr int kMaxSchurUpdates = 64;

/// Columns of the Lemke tableau for M (CSC) and covering vector d, and (when lifted()) of
/// the lifted basis matrix K above.
struct LemkeColumns {
  const SparseMatrix* M = nullptr;
  const Vector* d = nullptr;
  Index n = 0;
  // Lifted form (all null: none): Ĵ (n × m, CSC), Ĵᵀ (m × n, CSC), H (n × n, CSC), the
  // diagonal d of D (size m, > 0) and the shift σ (read at every refactorization).
  const SparseMatrix* J = nullptr;
  const SparseMatrix* JT = nullptr;
  const SparseMatrix* H = nullptr;
  const Vector* dof_inverse_mass = nullptr;
  const double* shift = nullptr;
  bool lifted() const { return J != nullptr; }
  /// Rows of the basis factorization: n + m when lifted, else n.
  Index factor_size() const { return lifted() ? n + J->cols() : n; }
  /// Dense column of variable var into out (size n).
  void dense(Index var, Eigen::Ref<Vector> out) const;
  /// y += alpha · (column of var).
  void add_to(Index var, double alpha, Vector& y) const;
  /// Writes the nonzeros of the column of var (explicit zeros of M skipped) to
  /// rows[0..c) and values[0..c), in increasing row order; returns c (at most nnz of
  /// M's column, 1 for w_i, n for z₀).
  Index write_column(Index var, int* rows, double* values) const;
  /// K's column for variable var (lifted only): as write_column for w_i and z₀; for z_j the
  /// entries of −(H + σI)(:, j), then those of −Ĵ(j, :) at rows n + k; increasing rows.
  Index write_lifted_column(Index var, int* rows, double* values) const;
  /// K's column n + k (lifted only): −Ĵ(:, k), then 1/d_k at row n + k.
  Index write_dof_column(Index k, int* rows, double* values) const;
  /// Entries bounding K's nonzeros for any basis (lifted only).
  Index lifted_nonzeros_bound() const { return H->nonZeros() + 2 * J->nonZeros() + 3 * n + J->cols(); }
};

class LemkeBasis {
 public:
  virtual ~LemkeBasis() = default;
  /// Factorizes B for the variables basic[0..n); false if B is (numerically) singular.
  virtual bool refactor(const std::vector<Index>& basic) = 0;
  /// a ← B⁻¹ (column of var), a of size n; remembers what replace() needs for this column.
  virtual void solve_column(Index var, Vector& a) = 0;
  /// x ← B⁻¹ x (x of size n).
  virtual void solve(Vector& x) = 0;
  /// x ← B⁻ᵀ x.
  virtual void solve_transposed(Vector& x) const = 0;
  /// Rows `rows` of B⁻¹, transposed: out.col(k) = (row rows[k] of B⁻¹)ᵀ; out is n × rows.size().
  virtual void inverse_rows(const std::vector<Index>& rows, Eigen::Ref<DenseMatrix> out) = 0;
  /// Row r of B⁻¹ with its nonzeros only: column indices (in no particular order) into
  /// `index`, values into `value` (both cleared first). The dense basis reads its B⁻¹; the
  /// sparse one solves Bᵀy = e_r hypersparsely (work proportional to the nonzeros touched,
  /// sparse/hypersparse_solve.hpp). Entries may be numerically zero.
  virtual void inverse_row_nonzeros(Index r, std::vector<int>& index, std::vector<double>& value) = 0;
  /// Replaces the column at position r by the column last passed to solve_column, whose
  /// solved form is a (a(r) ≠ 0). Returns false when a refactorization is due or the
  /// update is numerically unsafe; the caller then calls refactor().
  virtual bool replace(Index r, const Vector& a) = 0;
  /// True after a replace() that returned true for an update whose accuracy is in doubt
  /// (the sparse basis: its Schur complement's condition estimate beyond 1e12): the caller
  /// measures the residual of the updated basic values and refactorizes when it is too large.
  virtual bool update_needs_check() const { return false; }
  /// Bytes held by the factorization (for reports).
  virtual long memory_bytes() const = 0;
};

std::unique_ptr<LemkeBasis> make_dense_lemke_basis(const LemkeColumns& columns, int refactor_interval);
/// sparse_columns: entering columns by hypersparse solves (LemkeSettings::sparse_columns).
/// shared: the factorization to factorize in (its symbolic analysis reused while the
/// pattern repeats; lemke.hpp LemkeSharedFactorization), or nullptr for one of its own.
/// lu_pivot_tolerance: KLU's partial-pivoting threshold (LemkeSettings::lu_pivot_tolerance),
/// set before every factorization (a shared factorization may have served other settings);
/// lu_ordering: KLU's column ordering for the analyses (LemkeSettings::lu_ordering), set
/// before each analysis (an analysis reused while the pattern repeats keeps its own).
std::unique_ptr<LemkeBasis> make_sparse_lemke_basis(const LemkeColumns& columns, int refactor_interval,
                                                    bool sparse_columns, LemkeSharedFactorization* shared,
                                                    double lu_pivot_tolerance, LuOrdering lu_ordering);

}  // namespace lcprelax::detail
