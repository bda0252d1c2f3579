#pragma once
// Dense LDLᵀ with symmetric diagonal pivoting for small symmetric quasi-definite matrices
// K = [H  Bᵀ; B  −D] (H, D positive definite), behind the same Factorization interface as
// CholmodLdlt, for the interior point's tiny KKT systems (a few to a few hundred rows),
// where CHOLMOD's per-call overhead dominates the O(n³/3) flops of a dense factorization.
//
// Method. K = Πᵀ L D̂ Lᵀ Π with L unit lower triangular, D̂ diagonal and Π the product of
// the symmetric transpositions chosen during the elimination: step k swaps row/column k
// with the remaining row/column of largest |diagonal| of the current Schur complement.
// Why this and not the alternatives:
// - Quasi-definite matrices are strongly factorizable: ΠKΠᵀ has an LDLᵀ factorization
//   for EVERY permutation Π, and every Schur complement of a quasi-definite matrix is
//   quasi-definite again (Vanderbei 1995, "Symmetric quasidefinite matrices", SIAM J.
//   Optim. 5(1)). So diagonal pivoting never needs 2×2 pivots (Bunch–Kaufman) and D̂
//   carries the inertia directly (Sylvester): exactly H's size positive pivots.
// - Natural order (no pivoting) is valid too, but eliminates the primal block first,
//   whose pivots can be as small as the regularization ρ (an LP's free variable: 1e-9),
//   with element growth ~1/ρ. Largest-|d| first eliminates such a column only after the
//   rows that couple to it have added G_ij²/w_i to its pivot (Gill, Saunders & Shinnerl
//   1996 analyse the stability of quasi-definite LDLᵀ in terms of such growth).
// - Eigen::LDLT uses the same pivoting but documents only semidefinite input, and its
//   solve() silently pseudo-inverts zero pivots; LU (PartialPivLU) gives no inertia and
//   twice the flops.
// Cost: n³/3 flops, n² doubles of storage (allocated in analyze(), none afterwards:
// factorize() and solve() do not allocate).
//
// Contract (as CholmodLdlt, factorization.hpp): reads the upper triangle of A (entries
// below the diagonal are ignored), factorize() requires the analysed pattern
// (pattern_mismatch otherwise), NaN/Inf values give invalid_input, a pivot that is NaN or
// exactly 0 gives zero_pivot with `pivot` = its column of the input; with
// dynamic_regularization = τ > 0 a pivot with |d| < τ becomes ±τ (its sign kept, 0 → +τ;
// CHOLMOD's dbound rule) and is counted in regularized_pivots(). inertia() gives the signs
// of D̂, so a caller verifies that a quasi-definite matrix factorized as one (wrong-signed
// pivots mean K was not quasi-definite, e.g. a nonconvex P: raise the regularization).
// Meant for n up to a few hundred (kkt: QpSettings::dense_max_kkt); n above
// kMaxDimension is refused with out_of_memory at analyze().
#include <lcprelax/sparse/factorization.hpp>

#include <vector>

namespace lcprelax::sparse {

class DenseLdlt final : public Factorization {
 public:
  /// Largest dimension analyze() accepts (n² doubles: 4096² = 128 MiB).
  static constexpr Index kMaxDimension = 4096;

  /// dynamic_regularization: τ of the header comment (0 disables).
  explicit DenseLdlt(double dynamic_regularization = 0.0);

  FactorResult analyze(const SparseMatrix& A) override;
  FactorResult factorize(const SparseMatrix& A) override;
  FactorResult solve(Eigen::Ref<DenseMatrix> B) const override;
  /// n(n+1)/2 (the dense lower triangle with the diagonal), after analyze().
  long factor_nnz() const override;
  Index rows() const override { return n_; }
  const char* name() const override { return "dense_ldlt"; }

  /// Signs of D̂ in the last successful numeric factorization.
  bool reports_inertia() const override { return true; }
  Inertia inertia() const override { return inertia_; }
  /// Pivots replaced by ±τ in the last numeric factorization.
  Index regularized_pivots() const { return regularized_; }

 private:
  double tau_ = 0.0;
  Index n_ = 0;
  bool analysed_ = false;
  bool factored_ = false;
  std::vector<Index> outer_, inner_;  // the analysed pattern
  DenseMatrix L_;                     // strictly lower: L; diagonal: D̂ (permuted order)
  std::vector<Index> swap_;           // step k exchanged rows/columns k and swap_[k] ≥ k
  std::vector<Index> perm_;           // perm_[k] = input column eliminated at step k
  Inertia inertia_;
  Index regularized_ = 0;
};

}  // namespace lcprelax::sparse
