// CHOLMOD engine: views a compressed lcprelax::SparseMatrix as a cholmod_sparse (upper
// triangle, no copy), analyses once (AMD, or the fewest-flops of AMD, METIS and NESDIS:
// CholmodOrdering in cholmod_ldlt.hpp), refactorizes numerically, solves in place,
// and turns every CHOLMOD outcome into a FactorResult (CHOLMOD never prints or aborts).
#include "cholmod_engine.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <string>

namespace lcprelax::sparse::detail {
namespace {

// CHOLMOD reports errors through Common->status; this handler keeps it quiet.
void silent_error_handler(int /*status*/, const char* /*file*/, int /*line*/,
                          const char* /*message*/) {}

FactorResult from_common(const cholmod_common& c, const char* where) {
  const std::string what = std::string(where) + " failed (CHOLMOD status " +
                           std::to_string(c.status) + ")";
  switch (c.status) {
    case CHOLMOD_OUT_OF_MEMORY:
    case CHOLMOD_TOO_LARGE:
      return make_result(FactorStatus::out_of_memory, what + ": out of memory");
    case CHOLMOD_INVALID:
      return make_result(FactorStatus::invalid_input, what + ": invalid input");
    default:
      return make_result(FactorStatus::internal_error, what);
  }
}

}  // namespace

CholmodEngine::CholmodEngine(CholmodKind kind, double dbound, CholmodOrdering ordering)
    : kind_(kind), dbound_(dbound > 0.0 ? dbound : 0.0), ordering_(ordering) {
  cholmod_start(&common_);
  common_.print = 0;
  common_.error_handler = silent_error_handler;
  common_.supernodal =
      kind_ == CholmodKind::simplicial_ldlt ? CHOLMOD_SIMPLICIAL : CHOLMOD_SUPERNODAL;
  common_.final_ll = 0;  // a simplicial factor stays LDLᵀ (never converted to LLᵀ)
  common_.final_asis = 1;
  common_.nmethods = 1;  // one method per cholmod_analyze call; analyze() compares them
  common_.method[0].ordering = CHOLMOD_AMD;
  common_.postorder = 1;
  common_.dbound = kind_ == CholmodKind::simplicial_ldlt ? dbound_ : 0.0;
}

CholmodEngine::~CholmodEngine() {
  release();
  cholmod_finish(&common_);
}

void CholmodEngine::release() {
  if (L_) cholmod_free_factor(&L_, &common_);
  if (X_) cholmod_free_dense(&X_, &common_);
  if (Y_) cholmod_free_dense(&Y_, &common_);
  if (E_) cholmod_free_dense(&E_, &common_);
  pattern_.clear();
  perm_.clear();
  slot_.clear();
  S_ = SparseMatrix();
  n_ = 0;
  factored_ = false;
  inertia_ = Inertia{};
  ordering_used_ = -1;
  flops_ = 0.0;
}

const char* CholmodEngine::ordering_name() const {
  switch (ordering_used_) {
    case CHOLMOD_AMD: return "amd";
    case CHOLMOD_METIS: return "metis";
    case CHOLMOD_NESDIS: return "nesdis";
    case CHOLMOD_NATURAL: return "natural";
    default: return "";
  }
}

cholmod_factor* CholmodEngine::analyze_with(cholmod_sparse& a, int ordering, double& flops) {
  common_.method[0].ordering = ordering;
  common_.status = CHOLMOD_OK;
  cholmod_factor* L = cholmod_analyze(&a, &common_);
  if (L && common_.status < CHOLMOD_OK) cholmod_free_factor(&L, &common_);
  flops = L ? common_.method[0].fl : 0.0;
  return L;
}

cholmod_sparse CholmodEngine::view(const SparseMatrix& A) const {
  cholmod_sparse s{};
  s.nrow = static_cast<size_t>(A.rows());
  s.ncol = static_cast<size_t>(A.cols());
  s.nzmax = static_cast<size_t>(A.nonZeros());
  s.p = const_cast<Index*>(A.outerIndexPtr());
  // An empty matrix has no inner/value arrays; CHOLMOD wants non-null pointers anyway.
  static Index no_index = 0;
  static double no_value = 0.0;
  s.i = A.nonZeros() > 0 ? const_cast<Index*>(A.innerIndexPtr()) : &no_index;
  s.nz = nullptr;
  s.x = A.nonZeros() > 0 ? const_cast<double*>(A.valuePtr()) : &no_value;
  s.z = nullptr;
  s.stype = 1;  // upper triangle used, lower ignored
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = pattern_.sorted() ? 1 : 0;
  s.packed = 1;
  return s;
}

FactorResult CholmodEngine::analyze(const SparseMatrix& A) {
  release();
  if (auto r = check_square(A); !r.ok()) return r;
  CompressedRef ref(A);
  pattern_.assign(ref.get());
  cholmod_sparse a = view(ref.get());
  L_ = analyze_with(a, CHOLMOD_AMD, flops_);
  if (!L_) {
    FactorResult r = from_common(common_, "cholmod_analyze");
    release();
    return r;
  }
  ordering_used_ = L_->ordering;
  if (ordering_ == CholmodOrdering::best && flops_ > kNestedDissectionFlops) {
    // Nested dissection where AMD's factor is expensive; the fewest predicted flops wins. A
    // failed analysis (e.g. METIS out of memory) only drops that candidate.
    for (const int candidate : {CHOLMOD_METIS, CHOLMOD_NESDIS}) {
      double fl = 0.0;
      cholmod_factor* L = analyze_with(a, candidate, fl);
      if (L && fl < flops_) {
        cholmod_free_factor(&L_, &common_);
        L_ = L;
        flops_ = fl;
        ordering_used_ = L_->ordering;  // CHOLMOD's METIS falls back to AMD on too dense graphs
      } else if (L) {
        cholmod_free_factor(&L, &common_);
      }
    }
    common_.method[0].ordering = CHOLMOD_AMD;
    common_.status = CHOLMOD_OK;
  }
  n_ = static_cast<Index>(A.rows());
  if (kind_ == CholmodKind::simplicial_ldlt && n_ > 0) return analyze_prepermuted(ref.get());
  return {};
}

FactorResult CholmodEngine::analyze_prepermuted(const SparseMatrix& A) {
  const Index n = n_;
  const Index* p = static_cast<const Index*>(L_->Perm);
  perm_.resize(n);
  if (p)
    std::copy(p, p + n, perm_.begin());
  else
    std::iota(perm_.begin(), perm_.end(), 0);
  std::vector<Index> pinv(n);
  for (Index k = 0; k < n; ++k) pinv[perm_[k]] = k;
  // Entries of upper(P A Pᵀ): input entry (i, j), i ≤ j, lands at (min, max) of
  // (pinv i, pinv j). Bucketed by column, rows sorted within a column; duplicates share
  // a slot.
  struct Entry {
    Index row, input;
  };
  std::vector<Index> start(n + 1, 0);
  const auto target = [&](Index i, Index j, Index& r, Index& c) {
    r = std::min(pinv[i], pinv[j]);
    c = std::max(pinv[i], pinv[j]);
  };
  Index r = 0, c = 0;
  for (Index j = 0; j < A.outerSize(); ++j)
    for (Index k = A.outerIndexPtr()[j]; k < A.outerIndexPtr()[j + 1]; ++k)
      if (A.innerIndexPtr()[k] <= j) {
        target(A.innerIndexPtr()[k], j, r, c);
        ++start[c + 1];
      }
  for (Index j = 0; j < n; ++j) start[j + 1] += start[j];
  std::vector<Entry> e(static_cast<std::size_t>(start[n]));
  std::vector<Index> next(start.begin(), start.end() - 1);
  for (Index j = 0; j < A.outerSize(); ++j)
    for (Index k = A.outerIndexPtr()[j]; k < A.outerIndexPtr()[j + 1]; ++k)
      if (A.innerIndexPtr()[k] <= j) {
        target(A.innerIndexPtr()[k], j, r, c);
        e[next[c]++] = {r, k};
      }
  slot_.assign(static_cast<std::size_t>(A.nonZeros()), -1);
  std::vector<Index> outer(n + 1, 0), inner;
  inner.reserve(e.size());
  for (Index col = 0; col < n; ++col) {
    std::sort(e.begin() + start[col], e.begin() + start[col + 1],
              [](const Entry& x, const Entry& y) { return x.row < y.row; });
    for (Index t = start[col]; t < start[col + 1]; ++t) {
      if (t == start[col] || e[t].row != e[t - 1].row) {
        inner.push_back(e[t].row);
        ++outer[col + 1];
      }
      slot_[e[t].input] = static_cast<Index>(inner.size()) - 1;
    }
  }
  for (Index j = 0; j < n; ++j) outer[j + 1] += outer[j];
  S_.resize(n, n);
  S_.resizeNonZeros(static_cast<Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), S_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), S_.innerIndexPtr());
  std::fill(S_.valuePtr(), S_.valuePtr() + S_.nonZeros(), 0.0);
  // Symbolic analysis of S in its own (natural) order; AMD's order was postordered already.
  cholmod_free_factor(&L_, &common_);
  const int ordering = common_.method[0].ordering, postorder = common_.postorder;
  common_.method[0].ordering = CHOLMOD_NATURAL;
  common_.postorder = 0;
  cholmod_sparse s = view_permuted();
  common_.status = CHOLMOD_OK;
  L_ = cholmod_analyze(&s, &common_);
  common_.method[0].ordering = ordering;
  common_.postorder = postorder;
  if (!L_ || common_.status < CHOLMOD_OK || L_->ordering != CHOLMOD_NATURAL) {
    FactorResult r = L_ ? make_result(FactorStatus::internal_error, "cholmod_analyze of the permuted matrix "
                                                                   "did not keep the natural ordering")
                        : from_common(common_, "cholmod_analyze");
    release();
    return r;
  }
  return {};
}

cholmod_sparse CholmodEngine::view_permuted() {
  cholmod_sparse s{};
  s.nrow = s.ncol = static_cast<size_t>(n_);
  s.nzmax = static_cast<size_t>(S_.nonZeros());
  s.p = S_.outerIndexPtr();
  static Index no_index = 0;
  static double no_value = 0.0;
  s.i = S_.nonZeros() > 0 ? S_.innerIndexPtr() : &no_index;
  s.x = S_.nonZeros() > 0 ? S_.valuePtr() : &no_value;
  s.stype = 1;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

Index CholmodEngine::input_column(Index pivot) const {
  if (!perm_.empty()) return perm_[pivot];
  const Index* perm = static_cast<const Index*>(L_->Perm);
  return perm ? perm[pivot] : pivot;
}

FactorResult CholmodEngine::factorize(const SparseMatrix& A) {
  if (!L_) return make_result(FactorStatus::not_analyzed, "factorize() before analyze()");
  CompressedRef ref(A);
  if (auto r = check_pattern(pattern_, ref.get()); !r.ok()) return r;
  if (auto r = check_finite(ref.get()); !r.ok()) return r;
  factored_ = false;
  inertia_ = Inertia{};
  cholmod_sparse a;
  if (!perm_.empty()) {
    double* sv = S_.valuePtr();
    std::fill(sv, sv + S_.nonZeros(), 0.0);
    const double* av = ref.get().valuePtr();
    for (std::size_t k = 0; k < slot_.size(); ++k)
      if (slot_[k] >= 0) sv[slot_[k]] += av[k];
    a = view_permuted();
  } else {
    a = view(ref.get());
  }
  common_.status = CHOLMOD_OK;
  const int done = cholmod_factorize(&a, L_, &common_);
  if (!done || common_.status < CHOLMOD_OK) return from_common(common_, "cholmod_factorize");
  if (common_.status == CHOLMOD_NOT_POSDEF || L_->minor < static_cast<size_t>(n_)) {
    return failed_pivot();
  }
  if (kind_ == CholmodKind::simplicial_ldlt) {
    if (L_->is_ll || L_->is_super || L_->xtype != CHOLMOD_REAL) {
      return make_result(FactorStatus::internal_error,
                         "cholmod_factorize did not return a simplicial LDL' factor");
    }
    if (auto r = scan_diagonal(); !r.ok()) return r;
  }
  factored_ = true;
  return {};
}

FactorResult CholmodEngine::failed_pivot() {
  const Index k = static_cast<Index>(L_->minor);
  const Index column = input_column(k);
  const std::string where = "pivot " + std::to_string(k) + " (column " +
                            std::to_string(column) + " of the input matrix)";
  if (kind_ == CholmodKind::simplicial_ldlt) {
    return make_result(FactorStatus::zero_pivot, "zero pivot in LDL': " + where, column);
  }
  return make_result(FactorStatus::not_positive_definite,
                     "matrix is not positive definite: " + where, column);
}

FactorResult CholmodEngine::scan_diagonal() {
  // Simplicial LDLᵀ: the first entry of column j of L is D(j,j).
  const Index* Lp = static_cast<const Index*>(L_->p);
  const double* Lx = static_cast<const double*>(L_->x);
  Inertia in;
  for (Index j = 0; j < n_; ++j) {
    const double d = Lx[Lp[j]];
    if (std::isnan(d)) {
      const Index column = input_column(j);
      return make_result(FactorStatus::zero_pivot,
                         "NaN pivot in LDL': pivot " + std::to_string(j) + " (column " +
                             std::to_string(column) + " of the input matrix)",
                         column);
    }
    if (d > 0.0) {
      ++in.positive;
    } else if (d < 0.0) {
      ++in.negative;
    } else {
      ++in.zero;
    }
  }
  inertia_ = in;
  return {};
}

FactorResult CholmodEngine::solve(Eigen::Ref<DenseMatrix> B) {
  if (!factored_) {
    return make_result(FactorStatus::not_analyzed, "solve() before a successful factorize()");
  }
  if (auto r = check_rhs(n_, static_cast<Index>(B.rows())); !r.ok()) return r;
  if (B.cols() == 0 || n_ == 0) return {};
  const bool permuted = !perm_.empty();
  if (permuted) {  // S y = c with c_k = b_perm[k], then x_perm[k] = y_k
    rhs_.resize(n_, B.cols());
    for (Eigen::Index j = 0; j < B.cols(); ++j)
      for (Index k = 0; k < n_; ++k) rhs_(k, j) = B(perm_[k], j);
  }
  cholmod_dense b{};
  b.nrow = static_cast<size_t>(n_);
  b.ncol = static_cast<size_t>(B.cols());
  b.d = permuted ? static_cast<size_t>(n_) : static_cast<size_t>(B.outerStride());
  b.nzmax = b.d * b.ncol;
  b.x = permuted ? rhs_.data() : B.data();
  b.z = nullptr;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  // cholmod_solve2 keeps X_, Y_, E_ between calls when their shapes are what it asks for.
  // Its simplicial path asks for Y as max(4, nrhs) × n (leading dimension the same) and then
  // shrinks Y's header to the columns it used (nrow = d = nrhs when nrhs < 4), so the next
  // call would free and reallocate Y: the header is restored to the allocated shape first.
  const std::size_t nr = std::max<std::size_t>(4, static_cast<std::size_t>(B.cols()));
  if (Y_ && !L_->is_super && Y_->nzmax >= nr * static_cast<std::size_t>(n_)) {
    Y_->nrow = nr;
    Y_->ncol = static_cast<std::size_t>(n_);
    Y_->d = nr;
  }
  common_.status = CHOLMOD_OK;
  if (!cholmod_solve2(CHOLMOD_A, L_, &b, nullptr, &X_, nullptr, &Y_, &E_, &common_)) {
    return from_common(common_, "cholmod_solve2");
  }
  const double* x = static_cast<const double*>(X_->x);
  for (Eigen::Index j = 0; j < B.cols(); ++j) {
    if (permuted) {
      for (Index k = 0; k < n_; ++k) B(perm_[k], j) = x[k + j * X_->d];
    } else {
      std::memcpy(B.col(j).data(), x + j * X_->d, sizeof(double) * static_cast<size_t>(n_));
    }
  }
  return {};
}

long CholmodEngine::factor_nnz() const {
  if (!L_) return 0;
  long count = 0;
  if (L_->is_super) {
    // Each supernode stores a lower trapezoid: nscol columns over nsrow rows.
    const Index* super = static_cast<const Index*>(L_->super);
    const Index* pi = static_cast<const Index*>(L_->pi);
    for (size_t s = 0; s < L_->nsuper; ++s) {
      const long ncol = super[s + 1] - super[s];
      const long nrow = pi[s + 1] - pi[s];
      count += ncol * nrow - ncol * (ncol - 1) / 2;
    }
  } else if (L_->xtype == CHOLMOD_PATTERN) {
    const Index* colcount = static_cast<const Index*>(L_->ColCount);
    for (Index j = 0; j < n_; ++j) count += colcount[j];
  } else {
    const Index* nz = static_cast<const Index*>(L_->nz);
    for (Index j = 0; j < n_; ++j) count += nz[j];
  }
  return count;
}

std::unique_ptr<CholmodEngine> CholmodEngine::clone_analysis() const {
  auto clone = std::make_unique<CholmodEngine>(kind_, dbound_, ordering_);
  if (!L_) return clone;
  cholmod_common& c = clone->common_;
  clone->L_ = cholmod_copy_factor(L_, &c);
  if (clone->L_ && clone->L_->xtype != CHOLMOD_PATTERN) {
    // Drop the numeric values; the ordering and symbolic structure stay.
    cholmod_change_factor(CHOLMOD_PATTERN, L_->is_ll, L_->is_super, 1, 1, clone->L_, &c);
  }
  if (!clone->L_ || c.status < CHOLMOD_OK) {
    clone->release();
    return clone;
  }
  clone->pattern_ = pattern_;
  clone->perm_ = perm_;
  clone->slot_ = slot_;
  clone->S_ = S_;
  clone->n_ = n_;
  clone->ordering_used_ = ordering_used_;
  clone->flops_ = flops_;
  return clone;
}

}  // namespace lcprelax::sparse::detail
