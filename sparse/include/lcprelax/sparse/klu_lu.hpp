#pragma once
// KLU sparse LU (with BTF and AMD ordering, partial pivoting) for square unsymmetric
// matrices; used by the Lemke basis. factorize() does a full numeric factorization with
// pivoting; refactorize() reuses the last pivot sequence (klu_refactor, cheaper, but may
// be unstable when values change much: check rcond()).
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
  FactorResult factorize(const SparseMatrix& A) override;
  /// Numeric refactorization keeping the previous pivot order (requires factorize() first).
  FactorResult refactorize(const SparseMatrix& A);
  FactorResult solve(Eigen::Ref<DenseMatrix> B) const override;
  FactorResult solve_transposed(Eigen::Ref<DenseMatrix> B) const override;
  long factor_nnz() const override;
  Index rows() const override;
  const char* name() const override { return "klu_lu"; }
  /// Cheap reciprocal condition estimate of the last factorization (klu_rcond).
  double rcond() const;
  /// The columns of A (analyze() first, same pattern) that a factorization which goes on
  /// past zero pivots (KLU's halt_if_singular off) leaves with a pivot |U_kk| ≤
  /// relative_tolerance·max|U_kk|: each depends on the columns before it in KLU's column
  /// order, so replacing them can make A nonsingular (basis repair). Empty when A is
  /// numerically nonsingular. Leaves no usable factorization (factorize() again).
  std::vector<Index> zero_pivot_columns(const SparseMatrix& A, double relative_tolerance);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lcprelax::sparse
