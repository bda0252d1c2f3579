#pragma once
// Symmetric-indefinite LDLᵀ of a sparse matrix by MUMPS through PETSc (MatGetFactor with
// MATSOLVERMUMPS and MAT_FACTOR_CHOLESKY; Amestoy, Duff, L'Excellent & Koster 2001,
// "A fully asynchronous multifrontal solver using distributed dynamic scheduling", SIAM
// J. Matrix Anal. Appl. 23(1)). The KKT backend alternative to CholmodLdlt
// (kkt/qp_settings.hpp, KktBackend).
//
// Same contract as every Factorization (factorization.hpp): analyze() once per pattern
// (the upper triangle is read, entries below the diagonal ignored), factorize() on new
// values of that pattern (numeric refactorization only: the MUMPS analysis is kept),
// solve() with many right-hand sides, failures as statuses. With pivoting (the default)
// MUMPS pivots (1×1 and 2×2, threshold CNTL(1) = 0.01), so any nonsingular symmetric
// matrix factorizes; without (pivoting = false, CNTL(1) = 0: static pivot order, as
// CHOLMOD's LDLᵀ, and MUMPS' static pivoting with threshold CNTL(4) = 1e-300: only pivots
// below 1e-300 in magnitude would be replaced; factorize() returns zero_pivot when one
// was (INFOG(25) > 0), as CHOLMOD does for a zero pivot, and the pivot signs count in
// inertia()) it is meant for
// quasi-definite matrices (Vanderbei 1995), which need no pivoting, and avoids the delayed pivots that made MUMPS run out of its workspace on
// interior-point KKT matrices near the solution (measured on STCQP1: INFOG(1) = −9 at every
// regularization). The KKT backend (kkt/src/kkt_system.cpp) uses pivoting = false.
// Roundoff can flip a pivot's sign in that static order where CHOLMOD's order does not
// (LISWET1 near its optimum with the inequality block's δ dropped: INFOG(12) = 10,001
// negative pivots for 10,000 constraint rows): refactorize_pivoted() then repeats the
// numeric phase once with threshold pivoting (CNTL(1) = 0.01, static pivoting off,
// CNTL(4) = −1; the analysis is kept), whose inertia is correct (measured: 10,000 negative,
// INFOG(13) = 19,201 delayed pivots, 127,671 factor entries against 89,410), and the next
// factorize() is in the static order again. Where
// CHOLMOD's LDLᵀ finds a wrong-signed pivot and the QP solver raises its regularization ρ
// tenfold, MUMPS may accept the same matrix: then the two backends end a solve at
// different ρ, which only matters where the KKT matrix is singular to working precision
// (a non-unique optimum, e.g. QAFIRO: there the adjoint grows like 1/ρ with either
// backend; tests/mpi/mpi_qp_mumps_distributed_test.cpp). inertia() reports the signs of D from
// MUMPS (INFOG(12) negative pivots; with pivoting, null pivots detected with
// ICNTL(24) = 1 give zero_pivot).
//
// After a failed numeric phase (INFOG(1) < 0) the MUMPS factor is created and analysed
// anew: PETSc's numeric factorization for MUMPS returns without factorizing while the
// previous phase's INFOG(1) is negative, so otherwise every later factorize() of the same
// analysis would fail with the first error (on LISWET1 a workspace shortage, INFOG(1) =
// −9, of the pivoted factorization would fail all later ones at any regularization).
// INFOG(1) = −9 doubles the workspace margin ICNTL(14) (from 50%, up to 800%) and retries.
//
// Communicator:
//   distributed = false: PETSC_COMM_SELF: each process factorizes its own matrices (the
//     data-parallel learning case: every rank solves different problems);
//   distributed = true:  PETSC_COMM_WORLD: the matrix is distributed by rows over all
//     ranks and factorized by MUMPS in parallel. Every rank must call analyze/factorize/
//     solve collectively with the same matrix and right-hand sides; solve() returns the
//     full solution on every rank.
// Not thread-safe: one PetscMumpsLdlt per process at a time in a parallel region is not
// supported by PETSc; lcprelax's batch solvers use it from one thread.
// Built without PETSc, analyze() returns invalid_input with a message saying so.
#include <lcprelax/sparse/factorization.hpp>

#include <memory>

namespace lcprelax::sparse {

class PetscMumpsLdlt final : public Factorization {
 public:
  explicit PetscMumpsLdlt(bool distributed = false, bool pivoting = true);
  ~PetscMumpsLdlt() override;
  PetscMumpsLdlt(const PetscMumpsLdlt&) = delete;
  PetscMumpsLdlt& operator=(const PetscMumpsLdlt&) = delete;

  FactorResult analyze(const SparseMatrix& A) override;
  FactorResult factorize(const SparseMatrix& A) override;
  FactorResult solve(Eigen::Ref<DenseMatrix> B) const override;
  long factor_nnz() const override;
  Index rows() const override;
  const char* name() const override { return distributed_ ? "mumps_ldlt_distributed" : "mumps_ldlt"; }

  /// Signs of D in the last numeric factorization (from MUMPS).
  bool reports_inertia() const override { return true; }
  Inertia inertia() const override;
  bool distributed() const { return distributed_; }
  /// Without pivoting: the last factorize()'s matrix again with threshold pivoting
  /// (CNTL(1) = 0.01, static pivoting off), for this one factorization; with pivoting it
  /// repeats factorize()'s numeric phase.
  bool can_refactorize_pivoted() const override { return !pivoting_; }
  FactorResult refactorize_pivoted() override;
  /// refactorize_pivoted() calls since construction.
  int pivoted_refactorizations() const { return pivoted_refactorizations_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int pivoted_refactorizations_ = 0;
  bool distributed_;
  bool pivoting_;
};

}  // namespace lcprelax::sparse
