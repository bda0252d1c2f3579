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
//   when |P| reaches the refactorization interval.
#include <lcprelax/sparse/types.hpp>

#include <memory>
#include <vector>

namespace lcprelax::detail {

/// Columns of the Lemke tableau for M (CSC) and covering vector d.
struct LemkeColumns {
  const SparseMatrix* M = nullptr;
  const Vector* d = nullptr;
  Index n = 0;
  /// Dense column of variable var into out (size n).
  void dense(Index var, Eigen::Ref<Vector> out) const;
  /// y += alpha · (column of var).
  void add_to(Index var, double alpha, Vector& y) const;
  /// Appends the column of variable var as triplets in column `col` of B.
  void append(Index var, Index col, std::vector<Triplet>& out) const;
};

class LemkeBasis {
 public:
  virtual ~LemkeBasis() = default;
  /// Factorizes B for the variables basic[0..n); false if B is (numerically) singular.
  virtual bool refactor(const std::vector<Index>& basic) = 0;
  /// a ← B⁻¹ (column of var); remembers what replace() needs for this column.
  virtual void solve_column(Index var, Vector& a) = 0;
  /// x ← B⁻¹ x.
  virtual void solve(Vector& x) const = 0;
  /// x ← B⁻ᵀ x.
  virtual void solve_transposed(Vector& x) const = 0;
  /// Rows `rows` of B⁻¹, transposed: out.col(k) = (row rows[k] of B⁻¹)ᵀ.
  virtual void inverse_rows(const std::vector<Index>& rows, DenseMatrix& out) const = 0;
  /// Replaces the column at position r by the column last passed to solve_column, whose
  /// solved form is a (a(r) ≠ 0). Returns false when a refactorization is due or the
  /// update is numerically unsafe; the caller then calls refactor().
  virtual bool replace(Index r, const Vector& a) = 0;
  /// Bytes held by the factorization (for reports).
  virtual long memory_bytes() const = 0;
};

std::unique_ptr<LemkeBasis> make_dense_lemke_basis(const LemkeColumns& columns, int refactor_interval);
std::unique_ptr<LemkeBasis> make_sparse_lemke_basis(const LemkeColumns& columns, int refactor_interval);

}  // namespace lcprelax::detail
