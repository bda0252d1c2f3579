#pragma once
// Internal helpers shared by the SuiteSparse wrappers (not installed): a compressed view
// of a SparseMatrix, a saved sparsity pattern for the analyse-once/refactorize contract,
// input validation, and FactorResult construction.
#include <lcprelax/sparse/factorization.hpp>

#include <optional>
#include <string>
#include <vector>

namespace lcprelax::sparse::detail {

/// Refers to A itself when A is compressed (no allocation: the numeric refactorizations
/// use it on every call), otherwise to a compressed copy it owns.
class CompressedRef {
 public:
  explicit CompressedRef(const SparseMatrix& A);
  CompressedRef(const CompressedRef&) = delete;
  CompressedRef& operator=(const CompressedRef&) = delete;
  const SparseMatrix& get() const { return *ptr_; }

 private:
  std::optional<SparseMatrix> copy_;  // even an empty SparseMatrix allocates its outer index
  const SparseMatrix* ptr_;
};

/// The outer and inner index arrays of a compressed matrix, saved at analyze().
class Pattern {
 public:
  void assign(const SparseMatrix& A);  ///< A must be compressed
  bool matches(const SparseMatrix& A) const;  ///< A must be compressed
  Index rows() const { return rows_; }
  /// Whether every column's row indices are strictly increasing.
  bool sorted() const { return sorted_; }
  void clear();

 private:
  Index rows_ = 0;
  Index cols_ = 0;
  bool sorted_ = true;
  std::vector<Index> outer_;
  std::vector<Index> inner_;
};

FactorResult make_result(FactorStatus status, std::string message, Index pivot = -1);
/// not_analyzed, "object was moved from": what every method of a moved-from factorization returns.
FactorResult moved_from_result();
/// ok, or invalid_input when A is not square.
FactorResult check_square(const SparseMatrix& A);
/// ok, or invalid_input naming the first NaN/Inf entry of A (A must be compressed).
FactorResult check_finite(const SparseMatrix& A);
/// ok, or pattern_mismatch (the analysed pattern is `analysed`, A must be compressed).
FactorResult check_pattern(const Pattern& analysed, const SparseMatrix& A);
/// ok, or invalid_input when B does not have n rows.
FactorResult check_rhs(Index n, Index b_rows);

}  // namespace lcprelax::sparse::detail
