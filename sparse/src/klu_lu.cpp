// KluLu: KLU sparse LU (BTF + AMD or COLAMD, partial pivoting) behind the Factorization interface.
// The matrix is passed to KLU as its own CSC arrays (no copy); the pattern is saved at
// analyze() and checked on every numeric (re)factorization.
#include <lcprelax/sparse/klu_lu.hpp>

#include <klu.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "klu_singleton_analysis.hpp"
#include "matrix_checks.hpp"

namespace lcprelax::sparse {

using detail::make_result;

struct KluLu::Impl {
  klu_common common{};
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  detail::Pattern pattern;
  Index n = 0;
  bool analysed = false;  // KLU rejects n = 0, so an empty matrix has no symbolic object
  bool factored = false;
  double rcond = 0.0;
  double factor_rcond = 0.0;  // rcond of the last factorize() (the pivots' own values)
  int peeled = 0;             // column singletons put first by the last analyze()
  bool singletons_first = true;
  detail::SingletonAnalysisWork singleton_work;
  bool reused = false;        // the last successful factorization was klu_refactor

  Impl() {
    klu_defaults(&common);
    common.halt_if_singular = 1;
  }
  ~Impl() { release(); }

  void free_numeric() {
    if (numeric) klu_free_numeric(&numeric, &common);
    factored = false;
    rcond = 0.0;
  }
  void release() {
    free_numeric();
    if (symbolic) klu_free_symbolic(&symbolic, &common);
    pattern.clear();
    n = 0;
    peeled = 0;
    analysed = false;
  }

  FactorResult from_common(const char* where) const {
    const std::string what = std::string(where) + " failed (KLU status " +
                             std::to_string(common.status) + ")";
    switch (common.status) {
      case KLU_SINGULAR: {
        const Index col = common.singular_col;
        return make_result(FactorStatus::singular,
                           "matrix is singular: zero pivot in column " + std::to_string(col),
                           col >= 0 && col < n ? col : -1);
      }
      case KLU_OUT_OF_MEMORY:
      case KLU_TOO_LARGE:
        return make_result(FactorStatus::out_of_memory, what + ": out of memory");
      case KLU_INVALID:
        return make_result(FactorStatus::invalid_input, what + ": invalid input");
      default:
        return make_result(FactorStatus::internal_error, what);
    }
  }

  // Pattern and value checks shared by factorize() and refactorize().
  FactorResult check(const SparseMatrix& A) const {
    if (auto r = detail::check_pattern(pattern, A); !r.ok()) return r;
    return detail::check_finite(A);
  }

  // B ← A⁻¹B or A⁻ᵀB in place; KLU reads B with leading dimension B.outerStride().
  FactorResult solve(Eigen::Ref<DenseMatrix> B, bool transposed) {
    if (!factored) {
      return make_result(FactorStatus::not_analyzed, "solve() before a successful factorize()");
    }
    if (auto r = detail::check_rhs(n, static_cast<Index>(B.rows())); !r.ok()) return r;
    if (B.cols() == 0 || n == 0) return {};
    const Index ldim = static_cast<Index>(B.outerStride());
    const Index nrhs = static_cast<Index>(B.cols());
    const int done = transposed ? klu_tsolve(symbolic, numeric, ldim, nrhs, B.data(), &common)
                                : klu_solve(symbolic, numeric, ldim, nrhs, B.data(), &common);
    if (!done) return from_common(transposed ? "klu_tsolve" : "klu_solve");
    return {};
  }

  // The 0×0 matrix: trivially factorized, perfectly conditioned.
  FactorResult factor_empty(int& count) {
    factored = true;
    rcond = 1.0;
    ++count;
    return {};
  }

  void update_rcond() {
    klu_rcond(symbolic, numeric, &common);
    rcond = common.rcond;
  }
};

namespace {
Index* ptr(const Index* p) { return const_cast<Index*>(p); }
double* ptr(const double* p) { return const_cast<double*>(p); }
}  // namespace

KluLu::KluLu() : impl_(std::make_unique<Impl>()) {}
KluLu::~KluLu() = default;
KluLu::KluLu(KluLu&&) noexcept = default;
KluLu& KluLu::operator=(KluLu&&) noexcept = default;

FactorResult KluLu::analyze(const SparseMatrix& A) {
  if (!impl_) return detail::moved_from_result();
  Impl& m = *impl_;
  m.release();
  if (auto r = detail::check_square(A); !r.ok()) return r;
  detail::CompressedRef ref(A);
  const SparseMatrix& M = ref.get();
  const Index n = static_cast<Index>(M.rows());
  if (n > 0) {
    // Column singletons first, KLU's analysis of the rest (klu_singleton_analysis.hpp);
    // KLU's analysis of the whole matrix when that does not apply.
    if (m.singletons_first)
      m.symbolic = detail::analyze_singletons_first(static_cast<int>(n), M.outerIndexPtr(), M.innerIndexPtr(),
                                                    &m.common, m.singleton_work, m.peeled);
    if (!m.symbolic) m.symbolic = klu_analyze(n, ptr(M.outerIndexPtr()), ptr(M.innerIndexPtr()), &m.common);
    if (!m.symbolic) return m.from_common("klu_analyze");
  }
  m.pattern.assign(M);
  m.n = n;
  m.analysed = true;
  return {};
}

void KluLu::set_pivot_tolerance(double u) {
  if (!(u > 0.0 && u <= 1.0))
    throw std::invalid_argument("KluLu: pivot tolerance " + std::to_string(u) + " must be in (0, 1]");
  if (impl_) impl_->common.tol = u;
}

double KluLu::pivot_tolerance() const { return impl_ ? impl_->common.tol : 0.0; }

void KluLu::set_ordering(Ordering ordering) {
  if (impl_) impl_->common.ordering = ordering == Ordering::colamd ? 1 : 0;
}

KluLu::Ordering KluLu::ordering() const {
  return impl_ && impl_->common.ordering == 1 ? Ordering::colamd : Ordering::amd;
}

bool KluLu::analyzed_for(const SparseMatrix& A) const {
  return impl_ && impl_->analysed && A.isCompressed() && impl_->pattern.matches(A);
}

FactorResult KluLu::factorize(const SparseMatrix& A) {
  if (!impl_) return detail::moved_from_result();
  Impl& m = *impl_;
  if (!m.analysed) {
    return make_result(FactorStatus::not_analyzed, "factorize() before analyze()");
  }
  detail::CompressedRef ref(A);
  const SparseMatrix& M = ref.get();
  if (auto r = m.check(M); !r.ok()) return r;
  m.free_numeric();
  if (m.n == 0) return m.factor_empty(numeric_factorizations_);
  m.numeric = klu_factor(ptr(M.outerIndexPtr()), ptr(M.innerIndexPtr()), ptr(M.valuePtr()),
                         m.symbolic, &m.common);
  if (!m.numeric || m.common.status != KLU_OK) {
    FactorResult r = m.from_common("klu_factor");
    m.free_numeric();
    return r;
  }
  m.update_rcond();
  m.factor_rcond = m.rcond;
  m.reused = false;
  m.factored = true;
  ++numeric_factorizations_;
  return {};
}

FactorResult KluLu::factorize_reusing_pivots(const SparseMatrix& A, double min_rcond_ratio) {
  if (!impl_) return detail::moved_from_result();
  Impl& m = *impl_;
  // analyze() frees the Numeric object, so one that exists is of the analysed pattern.
  if (m.analysed && m.numeric && m.n > 0 && refactorize(A).ok() && m.rcond >= min_rcond_ratio * m.factor_rcond)
    return {};
  return factorize(A);
}

bool KluLu::reused_pivots() const { return impl_ && impl_->factored && impl_->reused; }

std::vector<Index> KluLu::zero_pivot_columns(const SparseMatrix& A, double relative_tolerance) {
  std::vector<Index> out;
  if (!impl_) return out;
  Impl& m = *impl_;
  if (!m.analysed || m.n == 0) return out;
  detail::CompressedRef ref(A);
  const SparseMatrix& M = ref.get();
  if (!m.check(M).ok()) return out;
  m.free_numeric();
  m.common.halt_if_singular = 0;
  m.numeric = klu_factor(ptr(M.outerIndexPtr()), ptr(M.innerIndexPtr()), ptr(M.valuePtr()), m.symbolic, &m.common);
  m.common.halt_if_singular = 1;
  if (!m.numeric) return out;
  // Udiag holds U's diagonal in KLU's factored order; Symbolic->Q maps position → column.
  const double* udiag = static_cast<const double*>(m.numeric->Udiag);
  const int* q = m.symbolic->Q;
  double largest = 0.0;
  for (Index k = 0; k < m.n; ++k) largest = std::max(largest, std::abs(udiag[k]));
  for (Index k = 0; k < m.n; ++k)
    if (!(std::abs(udiag[k]) > relative_tolerance * largest)) out.push_back(q[k]);
  m.free_numeric();
  return out;
}

void KluLu::factor_counts(Index& lnz, Index& unz, Index& offdiagonal) const {
  lnz = unz = offdiagonal = 0;
  if (!impl_ || !impl_->factored || !impl_->numeric) return;
  lnz = impl_->numeric->lnz;
  unz = impl_->numeric->unz;
  offdiagonal = impl_->numeric->nzoff;
}

bool KluLu::extract(Factors& out) const {
  if (!impl_) return false;
  const Impl& m = *impl_;
  out.n = m.n;
  if (!m.factored) return false;
  const auto sz = [](Index k) { return static_cast<std::size_t>(std::max<Index>(k, 1)); };
  const Index n = m.n;
  out.Lp.resize(sz(n + 1));
  out.Up.resize(sz(n + 1));
  out.Fp.resize(sz(n + 1));
  out.P.resize(sz(n));
  out.Q.resize(sz(n));
  out.Rs.resize(sz(n));
  if (n == 0) {
    out.R.assign(1, 0);
    return true;
  }
  out.R.resize(static_cast<std::size_t>(m.symbolic->nblocks) + 1);
  const Index lnz = m.numeric->lnz, unz = m.numeric->unz, fnz = m.numeric->nzoff;
  out.Li.resize(sz(lnz));
  out.Lx.resize(sz(lnz));
  out.Ui.resize(sz(unz));
  out.Ux.resize(sz(unz));
  out.Fi.resize(sz(fnz));
  out.Fx.resize(sz(fnz));
  klu_common common = m.common;
  return klu_extract(m.numeric, m.symbolic, out.Lp.data(), out.Li.data(), out.Lx.data(), out.Up.data(), out.Ui.data(),
                     out.Ux.data(), out.Fp.data(), out.Fi.data(), out.Fx.data(), out.P.data(), out.Q.data(),
                     out.Rs.data(), out.R.data(), &common) != 0;
}

FactorResult KluLu::refactorize(const SparseMatrix& A) {
  if (!impl_) return detail::moved_from_result();
  Impl& m = *impl_;
  if (!m.numeric && !(m.analysed && m.n == 0)) {
    return make_result(FactorStatus::not_analyzed,
                       "refactorize() needs a successful factorize() first");
  }
  detail::CompressedRef ref(A);
  const SparseMatrix& M = ref.get();
  if (auto r = m.check(M); !r.ok()) return r;
  if (m.n == 0) return m.factor_empty(numeric_factorizations_);
  m.factored = false;
  m.rcond = 0.0;
  // On failure the Numeric object keeps its pivot order, so a later refactorize() may work.
  const int done = klu_refactor(ptr(M.outerIndexPtr()), ptr(M.innerIndexPtr()),
                                ptr(M.valuePtr()), m.symbolic, m.numeric, &m.common);
  if (!done || m.common.status != KLU_OK) return m.from_common("klu_refactor");
  m.update_rcond();
  m.reused = true;
  m.factored = true;
  ++numeric_factorizations_;
  return {};
}

FactorResult KluLu::solve(Eigen::Ref<DenseMatrix> B) const {
  if (!impl_) return detail::moved_from_result();
  return impl_->solve(B, false);
}

FactorResult KluLu::solve_transposed(Eigen::Ref<DenseMatrix> B) const {
  if (!impl_) return detail::moved_from_result();
  return impl_->solve(B, true);
}

long KluLu::factor_nnz() const {
  if (!impl_) return 0;
  const Impl& m = *impl_;
  if (m.numeric) {
    return static_cast<long>(m.numeric->lnz) + m.numeric->unz + m.numeric->nzoff;
  }
  if (m.symbolic) {
    return static_cast<long>(m.symbolic->lnz + m.symbolic->unz) + m.symbolic->nzoff;
  }
  return 0;
}

Index KluLu::rows() const { return impl_ ? impl_->n : 0; }

Index KluLu::leading_singletons() const { return impl_ ? impl_->peeled : 0; }

void KluLu::set_singletons_first(bool on) {
  if (impl_) impl_->singletons_first = on;
}

bool KluLu::singletons_first() const { return impl_ && impl_->singletons_first; }

double KluLu::rcond() const { return impl_ ? impl_->rcond : 0.0; }

}  // namespace lcprelax::sparse
