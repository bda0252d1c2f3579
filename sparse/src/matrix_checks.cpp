// Internal helpers for the factorization wrappers: compressed views, pattern snapshots,
// and the input checks (square, finite, same pattern, right-hand-side size).
#include "matrix_checks.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace lcprelax::sparse::detail {

CompressedRef::CompressedRef(const SparseMatrix& A) : ptr_(&A) {
  if (!A.isCompressed()) {
    copy_.emplace(A);
    copy_->makeCompressed();
    ptr_ = &*copy_;
  }
}

void Pattern::assign(const SparseMatrix& A) {
  rows_ = static_cast<Index>(A.rows());
  cols_ = static_cast<Index>(A.cols());
  outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1);
  inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  sorted_ = true;
  for (Index j = 0; j < cols_ && sorted_; ++j) {
    for (Index p = outer_[j] + 1; p < outer_[j + 1]; ++p) {
      if (inner_[p - 1] >= inner_[p]) {
        sorted_ = false;
        break;
      }
    }
  }
}

bool Pattern::matches(const SparseMatrix& A) const {
  if (A.rows() != rows_ || A.cols() != cols_ ||
      static_cast<std::size_t>(A.nonZeros()) != inner_.size()) {
    return false;
  }
  return std::equal(outer_.begin(), outer_.end(), A.outerIndexPtr()) &&
         std::equal(inner_.begin(), inner_.end(), A.innerIndexPtr());
}

void Pattern::clear() {
  rows_ = 0;
  cols_ = 0;
  sorted_ = true;
  outer_.clear();
  inner_.clear();
}

FactorResult make_result(FactorStatus status, std::string message, Index pivot) {
  FactorResult r;
  r.status = status;
  r.pivot = pivot;
  r.message = std::move(message);
  return r;
}

FactorResult moved_from_result() { return make_result(FactorStatus::not_analyzed, "object was moved from"); }

FactorResult check_square(const SparseMatrix& A) {
  if (A.rows() != A.cols()) {
    return make_result(FactorStatus::invalid_input,
                       "matrix is " + std::to_string(A.rows()) + "x" +
                           std::to_string(A.cols()) + ", expected square");
  }
  return {};
}

FactorResult check_finite(const SparseMatrix& A) {
  const double* x = A.valuePtr();
  const Index* outer = A.outerIndexPtr();
  const Index* inner = A.innerIndexPtr();
  for (Index j = 0; j < A.cols(); ++j) {
    for (Index p = outer[j]; p < outer[j + 1]; ++p) {
      if (!std::isfinite(x[p])) {
        return make_result(FactorStatus::invalid_input,
                           "non-finite value " + std::to_string(x[p]) + " at (" +
                               std::to_string(inner[p]) + ", " + std::to_string(j) + ")");
      }
    }
  }
  return {};
}

FactorResult check_pattern(const Pattern& analysed, const SparseMatrix& A) {
  if (!analysed.matches(A)) {
    return make_result(FactorStatus::pattern_mismatch,
                       "sparsity pattern differs from the one given to analyze()");
  }
  return {};
}

FactorResult check_rhs(Index n, Index b_rows) {
  if (b_rows != n) {
    return make_result(FactorStatus::invalid_input,
                       "right-hand side has " + std::to_string(b_rows) +
                           " rows, expected " + std::to_string(n));
  }
  return {};
}

}  // namespace lcprelax::sparse::detail
