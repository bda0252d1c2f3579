#pragma once
// CHOLMOD simplicial LDLᵀ without pivoting for symmetric quasi-definite matrices
// K = [H  Bᵀ; B  −D] (H, D positive definite), which admit LDLᵀ under any symmetric
// permutation (Vanderbei 1995, "Symmetric quasidefinite matrices", SIAM J. Optim. 5(1)).
// The fill-reducing ordering (AMD) is chosen once in analyze() and kept.
//
// Pivots: a pivot with |d| < dynamic_regularization is replaced by ±dynamic_regularization
// (its sign kept; CHOLMOD's Common->dbound), otherwise an exactly zero or NaN pivot gives
// FactorStatus::zero_pivot. inertia() reports the signs of D of the last factorization so
// that a caller can verify a quasi-definite matrix factorized with the expected inertia.
//
// Memory: analyze() allocates; factorize() on the analysed pattern (compressed input) and
// solve() allocate nothing once the first solve() has created CHOLMOD's solve workspace.
#include <lcprelax/sparse/factorization.hpp>

#include <memory>

namespace lcprelax::sparse {

class CholmodLdlt final : public Factorization {
 public:
  /// dynamic_regularization: CHOLMOD dbound (0 disables; see header comment).
  explicit CholmodLdlt(double dynamic_regularization = 0.0);
  ~CholmodLdlt() override;
  CholmodLdlt(const CholmodLdlt&) = delete;
  CholmodLdlt& operator=(const CholmodLdlt&) = delete;
  CholmodLdlt(CholmodLdlt&&) noexcept;
  CholmodLdlt& operator=(CholmodLdlt&&) noexcept;

  FactorResult analyze(const SparseMatrix& A) override;
  FactorResult factorize(const SparseMatrix& A) override;
  FactorResult solve(Eigen::Ref<DenseMatrix> B) const override;
  long factor_nnz() const override;
  Index rows() const override;
  const char* name() const override { return "cholmod_ldlt"; }

  /// Signs of D in the last numeric factorization.
  bool reports_inertia() const override { return true; }
  Inertia inertia() const override;
  /// A copy that shares nothing but holds the same symbolic analysis (ordering,
  /// elimination tree), so that another thread can factorize matrices of the same
  /// pattern without analysing again. Valid after analyze().
  CholmodLdlt clone_analysis() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lcprelax::sparse
