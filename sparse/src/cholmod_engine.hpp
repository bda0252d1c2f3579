#pragma once
// Internal (not installed): the CHOLMOD machinery shared by CholmodLdlt (simplicial LDLᵀ)
// and CholmodLlt (supernodal LLᵀ). One cholmod_common per engine, so engines are
// independent and may be used from different threads.
#include <lcprelax/sparse/cholmod_ldlt.hpp>

#include <cholmod.h>

#include <memory>

#include "matrix_checks.hpp"

namespace lcprelax::sparse::detail {

enum class CholmodKind { simplicial_ldlt, supernodal_llt };

class CholmodEngine {
 public:
  /// dbound > 0 enables CHOLMOD's dynamic regularization of tiny LDLᵀ pivots; ordering:
  /// see CholmodOrdering (cholmod_ldlt.hpp).
  CholmodEngine(CholmodKind kind, double dbound, CholmodOrdering ordering = CholmodOrdering::best);
  ~CholmodEngine();
  CholmodEngine(const CholmodEngine&) = delete;
  CholmodEngine& operator=(const CholmodEngine&) = delete;

  FactorResult analyze(const SparseMatrix& A);
  FactorResult factorize(const SparseMatrix& A);
  /// B ← A⁻¹B; uses workspace held by the engine (not safe to call concurrently).
  FactorResult solve(Eigen::Ref<DenseMatrix> B);
  long factor_nnz() const;
  /// Flops of one numeric factorization predicted by analyze() (CHOLMOD's fl).
  double factor_flops() const { return L_ ? flops_ : 0.0; }
  /// "amd", "metis" or "nesdis": the ordering analyze() kept ("" before).
  const char* ordering_name() const;
  Index rows() const { return L_ ? n_ : 0; }
  /// Signs of D of the last successful LDLᵀ factorization (all zero otherwise).
  Inertia inertia() const { return inertia_; }
  /// A new engine holding a copy of the symbolic analysis and no numeric factor.
  std::unique_ptr<CholmodEngine> clone_analysis() const;

 private:
  void release();
  cholmod_sparse view(const SparseMatrix& A) const;
  FactorResult failed_pivot();
  FactorResult scan_diagonal();

  /// cholmod_analyze of a with one ordering method; null on failure (status reset).
  cholmod_factor* analyze_with(cholmod_sparse& a, int ordering, double& flops);
  FactorResult analyze_prepermuted(const SparseMatrix& A);
  cholmod_sparse view_permuted();
  Index input_column(Index pivot) const;

  CholmodKind kind_;
  double dbound_;
  CholmodOrdering ordering_;
  int ordering_used_ = -1;    // CHOLMOD_AMD, CHOLMOD_METIS or CHOLMOD_NESDIS after analyze()
  double flops_ = 0.0;        // predicted flops of the kept ordering
  // Simplicial LDLᵀ is factorized from a pre-permuted copy S = upper(P A Pᵀ) under the
  // natural ordering: CHOLMOD then factorizes S in place, where with its own permutation
  // it would build A(p,p) by two transposes (allocating) on every factorize (7.5% of a
  // pile step's instructions in a profile). The fill-reducing P is AMD's, from a first
  // analysis of A. Refactorization and solves of a simplicial factor allocate nothing
  // once the first solve has created the X/Y workspaces; the supernodal LLᵀ allocates
  // inside CHOLMOD on every numeric factorization.
  std::vector<Index> perm_;   // pivot k is input row/column perm_[k]; empty: not used
  std::vector<Index> slot_;   // input entry → value slot of S (−1: lower entry, ignored)
  SparseMatrix S_;
  DenseMatrix rhs_;           // permuted right-hand sides of solve()
  cholmod_common common_{};
  cholmod_factor* L_ = nullptr;
  cholmod_dense* X_ = nullptr;  // cholmod_solve2 workspaces, reused between solves
  cholmod_dense* Y_ = nullptr;
  cholmod_dense* E_ = nullptr;
  Pattern pattern_;
  Index n_ = 0;
  bool factored_ = false;
  Inertia inertia_;
};

}  // namespace lcprelax::sparse::detail
