// MUMPS LDLᵀ through PETSc (petsc_mumps_ldlt.hpp).
#include <lcprelax/mpi/mpi_session.hpp>
#include <lcprelax/sparse/petsc_mumps_ldlt.hpp>

#include "matrix_checks.hpp"

#ifdef LCPRELAX_HAS_PETSC
#include <petscmat.h>
#endif

#include <string>
#include <vector>

namespace lcprelax::sparse {

#ifdef LCPRELAX_HAS_PETSC

namespace {

FactorResult petsc_failure(PetscErrorCode e, const char* what) {
  const char* text = nullptr;
  PetscErrorMessage(e, &text, nullptr);
  return detail::make_result(e == PETSC_ERR_MEM ? FactorStatus::out_of_memory : FactorStatus::internal_error,
                             std::string("PETSc/MUMPS ") + what + ": " + (text ? text : "error ") +
                                 " (PETSc error " + std::to_string(static_cast<int>(e)) + ")");
}

#define LCPRELAX_PETSC(call, what)                 \
  do {                                             \
    const PetscErrorCode e_ = (call);              \
    if (e_) return petsc_failure(e_, what);        \
  } while (0)

// MUMPS' pivoting: threshold_null_detection for pivoting = true; static_order without;
// threshold for one refactorize_pivoted() of the static-order backend.
enum class Pivoting { threshold_null_detection, static_order, threshold };

}  // namespace

struct PetscMumpsLdlt::Impl {
  MPI_Comm comm = MPI_COMM_SELF;
  Mat A = nullptr, F = nullptr;
  Vec b = nullptr, x = nullptr, x_all = nullptr;
  VecScatter to_all = nullptr;
  detail::Pattern pattern;
  PetscInt n = 0, lo = 0, hi = 0;
  bool factored = false;
  bool filled = false;  // A holds the values of a factorize() call (refactorize_pivoted() reuses them)
  long nnz = 0;
  PetscInt workspace_margin = 50;  // ICNTL(14), percent over the analysis' estimate
  Inertia inertia;
  Pivoting home = Pivoting::static_order;  // the backend's mode (pivoting_ or not)
  // Owned rows [lo, hi) of the full symmetric pattern (CSR, global column indices) and, per
  // entry, the index of its value in the upper-triangle input: built once in analyze(), so
  // that each refactorization is a gather plus MatSetValues, without allocations.
  std::vector<PetscInt> row_start, columns;
  std::vector<Index> source;
  std::vector<PetscScalar> values;

  ~Impl() { destroy(); }
  void destroy() {
    if (to_all) VecScatterDestroy(&to_all);
    if (x_all) VecDestroy(&x_all);
    if (x) VecDestroy(&x);
    if (b) VecDestroy(&b);
    if (F) MatDestroy(&F);
    if (A) MatDestroy(&A);
    factored = false;
    filled = false;
    nnz = 0;
  }

  // The owned rows of the full pattern and their sources in the upper triangle U: the
  // entries of U's values are numbered 1..nnz, mirrored by selfadjointView, read back.
  void build_pattern(const SparseMatrix& upper) {
    SparseMatrix numbered = upper;
    for (Index k = 0; k < numbered.nonZeros(); ++k) numbered.valuePtr()[k] = static_cast<double>(k + 1);
    const Eigen::SparseMatrix<double, Eigen::RowMajor, int> rows =
        SparseMatrix(numbered.selfadjointView<Eigen::Upper>());
    row_start.assign(1, 0);
    columns.clear();
    source.clear();
    for (PetscInt r = lo; r < hi; ++r) {
      for (int k = rows.outerIndexPtr()[r]; k < rows.outerIndexPtr()[r + 1]; ++k) {
        columns.push_back(rows.innerIndexPtr()[k]);
        source.push_back(static_cast<Index>(rows.valuePtr()[k]) - 1);
      }
      row_start.push_back(static_cast<PetscInt>(columns.size()));
    }
    values.resize(columns.size());
  }

  // MUMPS' factor object and its analysis of A's pattern (MatGetFactor + symbolic phase).
  // Also the way back from a failed numeric phase: PETSc's MatCholeskyFactorNumeric for
  // MUMPS returns at once, without factorizing, while INFOG(1) < 0 from the previous phase
  // (it takes it for a failed analysis), so after any failure the factor is created anew.
  FactorResult create_factor(Pivoting mode) {
    if (F) MatDestroy(&F);
    factored = false;
    LCPRELAX_PETSC(MatGetFactor(A, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F), "MatGetFactor(mumps, cholesky)");
    LCPRELAX_PETSC(MatMumpsSetIcntl(F, 14, workspace_margin), "ICNTL(14)");  // before the analysis
    if (mode == Pivoting::threshold_null_detection) {
      LCPRELAX_PETSC(MatMumpsSetIcntl(F, 24, 1), "ICNTL(24)");  // detect null pivots
    } else {
      // static_order: static pivot order (CNTL(1) = 0) with MUMPS' static pivoting
      // (CNTL(4) = 1e-300: pivots of magnitude below 1e-300 are replaced by that threshold
      // with their sign; factorize() reports any such replacement, INFOG(25), as
      // zero_pivot), like CHOLMOD's LDLᵀ of a quasi-definite matrix; wrong-signed pivots
      // still show in the inertia. threshold: CNTL(1) = 0.01, static pivoting off.
      set_cntl(mode);
    }
    IS rowperm = nullptr, colperm = nullptr;
    LCPRELAX_PETSC(MatGetOrdering(A, MATORDERINGNATURAL, &rowperm, &colperm), "MatGetOrdering");
    MatFactorInfo info;
    MatFactorInfoInitialize(&info);
    const PetscErrorCode e = MatCholeskyFactorSymbolic(F, A, rowperm, &info);
    ISDestroy(&rowperm);
    ISDestroy(&colperm);
    LCPRELAX_PETSC(e, "symbolic factorization");
    return {};
  }
  void set_cntl(Pivoting mode) {
    MatMumpsSetCntl(F, 1, mode == Pivoting::static_order ? 0.0 : 0.01);
    MatMumpsSetCntl(F, 4, mode == Pivoting::static_order ? 1e-300 : -1.0);
  }

  // MUMPS' numeric phase on the filled matrix A. MUMPS sizes its workspace from the
  // analysis' estimate plus ICNTL(14) percent; numerical pivoting (delayed pivots of
  // indefinite KKT matrices) can exceed it (INFOG(1) = −9): then the margin is doubled, the
  // factor created anew (see create_factor) and the factorization repeated, up to
  // kMaxMargin (measured: the default 20% failed on STCQP1's KKT with pivoting; LISWET1's
  // threshold-pivoted refactorization needed more than 50%). After any other failure the
  // factor is created anew in the home mode, so the next factorize() runs.
  static constexpr PetscInt kMaxMargin = 800;
  FactorResult numeric(Pivoting mode) {
    factored = false;
    PetscErrorCode e = 0;
    PetscInt infog1 = 0, infog2 = 0;
    for (;;) {
      MatMumpsSetIcntl(F, 14, workspace_margin);
      MatFactorInfo info;
      MatFactorInfoInitialize(&info);
      e = MatCholeskyFactorNumeric(F, A, &info);
      MatMumpsGetInfog(F, 1, &infog1);
      if (!e && infog1 >= 0) break;
      MatMumpsGetInfog(F, 2, &infog2);
      const bool grow = infog1 == -9 && workspace_margin < kMaxMargin;
      if (grow) workspace_margin *= 2;
      if (auto r = create_factor(grow ? mode : home); !r.ok()) return r;
      if (!grow) break;
    }
    if (e || infog1 < 0) {
      const std::string codes = " (INFOG(1) = " + std::to_string(infog1) + ", INFOG(2) = " + std::to_string(infog2) + ")";
      if (infog1 == -9 || infog1 == -13) return detail::make_result(FactorStatus::out_of_memory, "MUMPS: out of memory" + codes);
      if (infog1 == -10) return detail::make_result(FactorStatus::zero_pivot, "MUMPS: numerically singular matrix" + codes);
      if (e) return petsc_failure(e, "numeric factorization");
      return detail::make_result(FactorStatus::internal_error, "MUMPS INFOG(1) = " + std::to_string(infog1));
    }
    if (mode == Pivoting::static_order) {
      // INFOG(25): pivots that MUMPS' static pivoting replaced (|d| < CNTL(4) = 1e-300, i.e.
      // zero to working precision). The factor is then that of another matrix, with entries
      // ~1e300: the refined solves returned NaN and the interior point diverged (QADLITTL
      // with kkt_backend = mumps: 1 or 2 replaced pivots in three factorizations up to
      // iteration 17, then NaN residuals and "iterates diverge"). CHOLMOD's LDLᵀ
      // reports such a pivot; so does this backend now, and the QP solver raises its
      // regularization and refactorizes (kkt/src/qp_solver.cpp, Impl::factorize).
      PetscInt replaced = 0;
      MatMumpsGetInfog(F, 25, &replaced);
      if (replaced > 0)
        return detail::make_result(FactorStatus::zero_pivot, "MUMPS static pivoting replaced " +
                                                                 std::to_string(replaced) + " tiny pivot(s)");
    }
    PetscInt negative = 0, null_pivots = 0, entries = 0;
    MatMumpsGetInfog(F, 12, &negative);
    MatMumpsGetInfog(F, 28, &null_pivots);
    MatMumpsGetInfog(F, 29, &entries);
    nnz = entries >= 0 ? static_cast<long>(entries) : -static_cast<long>(entries) * 1000000L;
    inertia.negative = negative;
    inertia.zero = null_pivots;
    inertia.positive = static_cast<Index>(n) - negative - null_pivots;
    if (null_pivots > 0)
      return detail::make_result(FactorStatus::zero_pivot, "MUMPS found " + std::to_string(null_pivots) + " null pivot(s)");
    factored = true;
    return {};
  }

  // Every entry of the owned rows is set (INSERT_VALUES on the whole pattern).
  FactorResult fill(const SparseMatrix& upper) {
    for (std::size_t j = 0; j < source.size(); ++j) values[j] = upper.valuePtr()[source[j]];
    for (PetscInt r = lo; r < hi; ++r) {
      const PetscInt start = row_start[static_cast<std::size_t>(r - lo)];
      const PetscInt count = row_start[static_cast<std::size_t>(r - lo) + 1] - start;
      LCPRELAX_PETSC(MatSetValues(A, 1, &r, count, columns.data() + start, values.data() + start, INSERT_VALUES),
                     "MatSetValues");
    }
    LCPRELAX_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    LCPRELAX_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    return {};
  }
};

PetscMumpsLdlt::PetscMumpsLdlt(bool distributed, bool pivoting)
    : impl_(std::make_unique<Impl>()), distributed_(distributed), pivoting_(pivoting) {}
PetscMumpsLdlt::~PetscMumpsLdlt() = default;

FactorResult PetscMumpsLdlt::analyze(const SparseMatrix& A_in) {
  mpi::ensure_petsc_initialized();
  Impl& m = *impl_;
  m.destroy();
  m.pattern.clear();
  const detail::CompressedRef ref(A_in);
  const SparseMatrix& A = ref.get();
  if (auto r = detail::check_square(A); !r.ok()) return r;
  if (auto r = detail::check_finite(A); !r.ok()) return r;
  m.comm = distributed_ ? PETSC_COMM_WORLD : PETSC_COMM_SELF;
  m.n = A.rows();
  PetscInt local = PETSC_DECIDE, global = m.n;
  LCPRELAX_PETSC(PetscSplitOwnership(m.comm, &local, &global), "PetscSplitOwnership");
  LCPRELAX_PETSC(MPI_Scan(&local, &m.hi, 1, MPIU_INT, MPI_SUM, m.comm) ? PETSC_ERR_MPI : 0, "MPI_Scan");
  m.lo = m.hi - local;

  // Preallocation of the owned rows of the full symmetric pattern.
  m.build_pattern(A);
  std::vector<PetscInt> d_nnz(static_cast<std::size_t>(local), 0), o_nnz(static_cast<std::size_t>(local), 0);
  for (PetscInt r = m.lo; r < m.hi; ++r)
    for (PetscInt k = m.row_start[static_cast<std::size_t>(r - m.lo)]; k < m.row_start[static_cast<std::size_t>(r - m.lo) + 1]; ++k) {
      const PetscInt c = m.columns[static_cast<std::size_t>(k)];
      ++(c >= m.lo && c < m.hi ? d_nnz : o_nnz)[static_cast<std::size_t>(r - m.lo)];
    }
  LCPRELAX_PETSC(MatCreateAIJ(m.comm, local, local, m.n, m.n, 0, d_nnz.data(), 0, o_nnz.data(), &m.A), "MatCreateAIJ");
  LCPRELAX_PETSC(MatSetOption(m.A, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  LCPRELAX_PETSC(MatSetOption(m.A, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
  if (auto r = m.fill(A); !r.ok()) return r;

  m.home = pivoting_ ? Pivoting::threshold_null_detection : Pivoting::static_order;
  if (auto r = m.create_factor(m.home); !r.ok()) return r;
  PetscInt estimate = 0;
  MatMumpsGetInfog(m.F, 20, &estimate);
  m.nnz = estimate >= 0 ? static_cast<long>(estimate) : -static_cast<long>(estimate) * 1000000L;

  LCPRELAX_PETSC(MatCreateVecs(m.A, &m.x, &m.b), "MatCreateVecs");
  LCPRELAX_PETSC(VecScatterCreateToAll(m.x, &m.to_all, &m.x_all), "VecScatterCreateToAll");
  m.pattern.assign(A);
  return {};
}

FactorResult PetscMumpsLdlt::factorize(const SparseMatrix& A_in) {
  Impl& m = *impl_;
  if (!m.F) return detail::make_result(FactorStatus::not_analyzed, "factorize() before analyze()");
  const detail::CompressedRef ref(A_in);
  const SparseMatrix& A = ref.get();
  if (auto r = detail::check_pattern(m.pattern, A); !r.ok()) return r;
  if (auto r = detail::check_finite(A); !r.ok()) return r;
  m.factored = false;
  m.filled = false;
  if (auto r = m.fill(A); !r.ok()) return r;
  m.filled = true;
  ++numeric_factorizations_;
  return m.numeric(m.home);
}

FactorResult PetscMumpsLdlt::refactorize_pivoted() {
  Impl& m = *impl_;
  if (!m.F || !m.filled)
    return detail::make_result(FactorStatus::not_analyzed, "refactorize_pivoted() without a factorize()");
  ++numeric_factorizations_;
  if (pivoting_) return m.numeric(Pivoting::threshold_null_detection);
  // Threshold pivoting for this factorization only: CNTL(1) = 0.01 (MUMPS' default for
  // symmetric matrices: a 1×1 pivot is accepted if |d| ≥ 0.01 × the largest entry of its
  // column in the front, else a 2×2 pivot or a delay to the parent front) and static
  // pivoting off (CNTL(4) = −1: no pivot is perturbed). The analysis is kept; the static
  // order is restored for the next factorize().
  ++pivoted_refactorizations_;
  m.set_cntl(Pivoting::threshold);
  FactorResult r = m.numeric(Pivoting::threshold);
  m.set_cntl(Pivoting::static_order);
  return r;
}

FactorResult PetscMumpsLdlt::solve(Eigen::Ref<DenseMatrix> B) const {
  Impl& m = *impl_;
  if (!m.factored) return detail::make_result(FactorStatus::not_analyzed, "solve() without a successful factorize()");
  if (auto r = detail::check_rhs(static_cast<Index>(m.n), static_cast<Index>(B.rows())); !r.ok()) return r;
  for (Index c = 0; c < B.cols(); ++c) {
    PetscScalar* bv = nullptr;
    LCPRELAX_PETSC(VecGetArray(m.b, &bv), "VecGetArray");
    for (PetscInt i = m.lo; i < m.hi; ++i) bv[i - m.lo] = B(i, c);
    LCPRELAX_PETSC(VecRestoreArray(m.b, &bv), "VecRestoreArray");
    LCPRELAX_PETSC(MatSolve(m.F, m.b, m.x), "MatSolve");
    LCPRELAX_PETSC(VecScatterBegin(m.to_all, m.x, m.x_all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    LCPRELAX_PETSC(VecScatterEnd(m.to_all, m.x, m.x_all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* xv = nullptr;
    LCPRELAX_PETSC(VecGetArrayRead(m.x_all, &xv), "VecGetArrayRead");
    for (PetscInt i = 0; i < m.n; ++i) B(i, c) = xv[i];
    LCPRELAX_PETSC(VecRestoreArrayRead(m.x_all, &xv), "VecRestoreArrayRead");
  }
  return {};
}

long PetscMumpsLdlt::factor_nnz() const { return impl_->nnz; }
Index PetscMumpsLdlt::rows() const { return static_cast<Index>(impl_->n); }
Inertia PetscMumpsLdlt::inertia() const { return impl_->inertia; }

#else  // built without PETSc

struct PetscMumpsLdlt::Impl {};
PetscMumpsLdlt::PetscMumpsLdlt(bool distributed, bool pivoting)
    : impl_(std::make_unique<Impl>()), distributed_(distributed), pivoting_(pivoting) {}
PetscMumpsLdlt::~PetscMumpsLdlt() = default;
namespace {
FactorResult unavailable() {
  return detail::make_result(FactorStatus::invalid_input,
                             "the MUMPS backend needs PETSc: lcprelax was built with LCPRELAX_WITH_PETSC=OFF");
}
}  // namespace
FactorResult PetscMumpsLdlt::analyze(const SparseMatrix&) { return unavailable(); }
FactorResult PetscMumpsLdlt::factorize(const SparseMatrix&) { return unavailable(); }
FactorResult PetscMumpsLdlt::solve(Eigen::Ref<DenseMatrix>) const { return unavailable(); }
long PetscMumpsLdlt::factor_nnz() const { return 0; }
Index PetscMumpsLdlt::rows() const { return 0; }
Inertia PetscMumpsLdlt::inertia() const { return {}; }
FactorResult PetscMumpsLdlt::refactorize_pivoted() { return unavailable(); }

#endif

}  // namespace lcprelax::sparse
