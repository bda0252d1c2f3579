#pragma once
// CHOLMOD simplicial LDLᵀ without pivoting for symmetric quasi-definite matrices
// K = [H  Bᵀ; B  −D] (H, D positive definite), which admit LDLᵀ under any symmetric
// permutation (Vanderbei 1995, "Symmetric quasidefinite matrices", SIAM J. Optim. 5(1)).
// The fill-reducing ordering is chosen once in analyze() and kept (CholmodOrdering):
// AMD (Amestoy, Davis, Duff 1996), and for a matrix whose AMD factor is predicted to cost
// more than kNestedDissectionFlops also METIS nested dissection (Karypis, Kumar 1998) and
// CHOLMOD's NESDIS; the ordering whose symbolic analysis predicts the fewest flops
// (CHOLMOD's Common->fl, Σ_j c_j² over the column counts c_j of L) is kept. Measured on
// the full KKT pattern of CVXQP1_L (15,000 rows): AMD 3.7e6 nonzeros in L and 4.4e9
// flops, METIS 1.9e6 and 9.8e8, NESDIS 1.8e6 and 9.2e8 (0.3 s of extra analysis).
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

/// Fill-reducing ordering of CholmodLdlt and CholmodLlt (see the header comment).
enum class CholmodOrdering {
  amd,   ///< AMD only
  best   ///< AMD, and above kNestedDissectionFlops also METIS and NESDIS: fewest flops kept
};

/// AMD-predicted flops above which the nested-dissection orderings are tried too: their
/// analysis costs ~0.1–0.3 s on a KKT matrix of 10⁵ rows, paid back within a few numeric
/// factorizations at this size (~10⁻² s each) and negligible next to larger ones.
constexpr double kNestedDissectionFlops = 1e7;

class CholmodLdlt final : public Factorization {
 public:
  /// dynamic_regularization: CHOLMOD dbound (0 disables; see header comment).
  explicit CholmodLdlt(double dynamic_regularization = 0.0, CholmodOrdering ordering = CholmodOrdering::best);
  ~CholmodLdlt() override;
  CholmodLdlt(const CholmodLdlt&) = delete;
  CholmodLdlt& operator=(const CholmodLdlt&) = delete;
  CholmodLdlt(CholmodLdlt&&) noexcept;
  CholmodLdlt& operator=(CholmodLdlt&&) noexcept;

  FactorResult analyze(const SparseMatrix& A) override;
  FactorResult factorize(const SparseMatrix& A) override;
  FactorResult solve(Eigen::Ref<DenseMatrix> B) const override;
  long factor_nnz() const override;
  double factor_flops() const override;
  Index rows() const override;
  const char* name() const override { return "cholmod_ldlt"; }
  /// The ordering kept by analyze(): "amd", "metis", "nesdis" ("" before analyze()).
  const char* ordering_name() const;

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
