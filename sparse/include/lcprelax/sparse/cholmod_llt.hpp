#pragma once
// CHOLMOD supernodal LLᵀ for symmetric positive definite matrices. A pivot ≤ 0 gives
// FactorStatus::not_positive_definite with the failing column in FactorResult::pivot.
// Each numeric factorization allocates inside CHOLMOD (the permuted transpose of A, the
// dense update workspace, OpenMP teams); solves reuse their workspace. Ordering: as
// CholmodLdlt's (CholmodOrdering, cholmod_ldlt.hpp).
#include <lcprelax/sparse/cholmod_ldlt.hpp>
#include <lcprelax/sparse/factorization.hpp>

#include <memory>

namespace lcprelax::sparse {

class CholmodLlt final : public Factorization {
 public:
  explicit CholmodLlt(CholmodOrdering ordering = CholmodOrdering::best);
  ~CholmodLlt() override;
  CholmodLlt(const CholmodLlt&) = delete;
  CholmodLlt& operator=(const CholmodLlt&) = delete;
  CholmodLlt(CholmodLlt&&) noexcept;
  CholmodLlt& operator=(CholmodLlt&&) noexcept;

  FactorResult analyze(const SparseMatrix& A) override;
  FactorResult factorize(const SparseMatrix& A) override;
  FactorResult solve(Eigen::Ref<DenseMatrix> B) const override;
  long factor_nnz() const override;
  double factor_flops() const override;
  Index rows() const override;
  const char* name() const override { return "cholmod_llt"; }
  /// See CholmodLdlt::ordering_name().
  const char* ordering_name() const;
  /// See CholmodLdlt::clone_analysis().
  CholmodLlt clone_analysis() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lcprelax::sparse
