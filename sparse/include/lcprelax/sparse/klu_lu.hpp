#pragma once
// KLU sparse LU (with BTF and AMD or COLAMD ordering, partial pivoting) for square unsymmetric
// matrices; used by the Lemke basis. factorize() does a full numeric factorization with
// pivoting; refactorize() reuses the last pivot sequence (klu_refactor, cheaper, but may
// be unstable when values change much: check rcond()). analyze() puts the column
// singletons (columns with one entry, each on a row of its own) first as 1×1 blocks and
// runs KLU's analysis (BTF, AMD/COLAMD) on the other rows and columns only: the same diagonal
// blocks as KLU's analysis of the whole matrix, at the cost of the rest (a Lemke basis is
// mostly slack columns e_i); KLU's own analysis of the whole matrix when there are none.
#include <lcprelax/sparse/factorization.hpp>

#include <memory>
#include <vector>

namespace lcprelax::sparse {

class KluLu final : public Factorization {
 public:
  KluLu();
  ~KluLu() override;
  KluLu(const KluLu&) = delete;
  KluLu& operator=(const KluLu&) = delete;
  KluLu(KluLu&&) noexcept;
  KluLu& operator=(KluLu&&) noexcept;

  FactorResult analyze(const SparseMatrix& A) override;
  /// Column singletons that the last analyze() put first (0: KLU analysed the whole matrix).
  Index leading_singletons() const;
  /// Whether analyze() puts the column singletons first (default true; false: KLU's own
  /// analysis of the whole matrix). Applies to the next analyze().
  void set_singletons_first(bool on);
  bool singletons_first() const;
  /// Whether the last analyze() was of A's pattern (A compressed), so that factorize(A)
  /// can reuse its symbolic analysis (BTF and AMD/COLAMD orderings depend on the pattern only).
  bool analyzed_for(const SparseMatrix& A) const;
  FactorResult factorize(const SparseMatrix& A) override;
  /// Numeric refactorization keeping the previous pivot order (requires factorize() first).
  FactorResult refactorize(const SparseMatrix& A);
  FactorResult solve(Eigen::Ref<DenseMatrix> B) const override;
  FactorResult solve_transposed(Eigen::Ref<DenseMatrix> B) const override;
  long factor_nnz() const override;
  Index rows() const override;
  const char* name() const override { return "klu_lu"; }
  /// Numeric factorization of A (same pattern as analyze()): klu_refactor with the pivot
  /// order of the last factorize() when one is held and the result's rcond() is at least
  /// min_rcond_ratio times that factorization's (the values moved little, so the old
  /// pivots still suit them), else factorize(). A repeated pattern with nearby values — a
  /// Lemke basis that stays from one time step to the next — then costs a refactorization
  /// without the pivot search. reused_pivots() says which one ran.
  FactorResult factorize_reusing_pivots(const SparseMatrix& A, double min_rcond_ratio);
  /// Whether the last successful numeric factorization was a refactorization.
  bool reused_pivots() const;
  /// Cheap reciprocal condition estimate of the last factorization (klu_rcond).
  double rcond() const;
  /// Threshold u of the partial pivoting in factorize() (KLU's Common.tol): a pivot is
  /// taken from the preferred (diagonal) position when its magnitude is at least u times
  /// the largest in its column, so that every |L_ij| ≤ 1/u. KLU's default 0.001 favours
  /// sparsity and allows a growth of up to 1000 per elimination step; 1 is true partial
  /// pivoting (|L_ij| ≤ 1). Applies to the next factorize(); throws std::invalid_argument
  /// unless 0 < u ≤ 1.
  void set_pivot_tolerance(double u);
  double pivot_tolerance() const;
  /// Fill-reducing column ordering of each diagonal block in analyze() (KLU's
  /// Common.ordering). amd (KLU's default): AMD on the pattern of A + Aᵀ, which assumes
  /// the pivots fall on the diagonal, as they do on circuit-like matrices with a strong
  /// diagonal. colamd: COLAMD on A's columns (Davis, Gilbert, Larimore & Ng, "A column
  /// approximate minimum degree ordering algorithm", ACM TOMS 30, 2004), whose ordering
  /// bounds the fill of LU with any row interchanges, for matrices on which partial
  /// pivoting leaves the diagonal. Applies to the next analyze(); an analysis already
  /// held (analyzed_for) keeps the ordering it was made with.
  enum class Ordering { amd, colamd };
  void set_ordering(Ordering ordering);
  Ordering ordering() const;
  /// The columns of A (analyze() first, same pattern) that a factorization which goes on
  /// past zero pivots (KLU's halt_if_singular off) leaves with a pivot |U_kk| ≤
  /// relative_tolerance·max|U_kk|: each depends on the columns before it in KLU's column
  /// order, so replacing them can make A nonsingular (basis repair). Empty when A is
  /// numerically nonsingular. Leaves no usable factorization (factorize() again).
  std::vector<Index> zero_pivot_columns(const SparseMatrix& A, double relative_tolerance);

  /// The factors of the last factorization (klu_extract), in KLU's convention
  ///     N = L·U + F,   N_kl = A(P[k], Q[l]) / Rs[k]
  /// (row k of N is row P[k] of A divided by Rs[k]: klu_extract returns the scale factors
  /// in the permuted order, as a test of hypersparse_solve checks; column l of N is column
  /// Q[l] of A); L unit lower triangular (diagonal stored), U upper triangular, both block
  /// diagonal over the BTF blocks; F the entries above the diagonal blocks. All CSC over
  /// the permuted indices; R[b]..R[b + 1] − 1 are the positions of diagonal block b (R has
  /// nblocks + 1 entries). Allocates only beyond out's capacity. False when not factorized.
  struct Factors {
    Index n = 0;
    std::vector<int> Lp, Li, Up, Ui, Fp, Fi, P, Q, R;
    std::vector<double> Lx, Ux, Fx, Rs;
  };
  bool extract(Factors& out) const;
  /// Entries of L, U and F of the last factorization (0 when not factorized).
  void factor_counts(Index& lnz, Index& unz, Index& offdiagonal) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lcprelax::sparse
