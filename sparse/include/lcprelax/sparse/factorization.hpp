#pragma once
// A common interface for sparse direct factorizations: symbolic analysis once per
// sparsity pattern, numeric refactorization on new values with the same pattern, and
// in-place solves with one or many right-hand sides.
//
// Conventions
// - Matrices are lcprelax::SparseMatrix (CSC, int indices). Symmetric factorizations
//   (CholmodLdlt, CholmodLlt) read only the upper triangle including the diagonal; entries
//   below the diagonal are ignored. KluLu reads the whole matrix.
// - factorize() requires the pattern (outer and inner index arrays) given to analyze();
//   a different pattern returns FactorStatus::pattern_mismatch, never a wrong factor.
// - Nothing aborts: every failure is a FactorResult with a status and a message.
#include <lcprelax/sparse/types.hpp>

#include <string>

namespace lcprelax::sparse {

enum class FactorStatus {
  ok,
  not_analyzed,           ///< factorize()/solve() before analyze()/factorize()
  pattern_mismatch,       ///< factorize() got another sparsity pattern than analyze()
  not_positive_definite,  ///< LLᵀ: a pivot ≤ 0 (pivot holds its column)
  zero_pivot,             ///< LDLᵀ: a zero or NaN pivot (pivot holds its column)
  singular,               ///< LU: structurally or numerically singular
  out_of_memory,
  invalid_input,          ///< wrong dimensions, NaN/Inf values, non-square matrix
  internal_error          ///< any other SuiteSparse error code
};

constexpr const char* to_string(FactorStatus s) {
  switch (s) {
    case FactorStatus::ok: return "ok";
    case FactorStatus::not_analyzed: return "not_analyzed";
    case FactorStatus::pattern_mismatch: return "pattern_mismatch";
    case FactorStatus::not_positive_definite: return "not_positive_definite";
    case FactorStatus::zero_pivot: return "zero_pivot";
    case FactorStatus::singular: return "singular";
    case FactorStatus::out_of_memory: return "out_of_memory";
    case FactorStatus::invalid_input: return "invalid_input";
    case FactorStatus::internal_error: return "internal_error";
  }
  return "unknown";
}

struct FactorResult {
  FactorStatus status = FactorStatus::ok;
  Index pivot = -1;     ///< column of the failing pivot where known, else -1
  std::string message;  ///< human-readable detail, empty when ok
  bool ok() const { return status == FactorStatus::ok; }
};

/// Signs of the pivots D of an LDLᵀ factorization.
struct Inertia {
  Index positive = 0;
  Index negative = 0;
  Index zero = 0;
};

class Factorization {
 public:
  virtual ~Factorization() = default;
  /// Symbolic analysis (fill-reducing ordering, elimination tree) of A's pattern.
  virtual FactorResult analyze(const SparseMatrix& A) = 0;
  /// Numeric factorization of A, whose pattern must equal the analysed one.
  virtual FactorResult factorize(const SparseMatrix& A) = 0;
  /// B ← A⁻¹ B in place (B has rows() rows and any number of columns).
  virtual FactorResult solve(Eigen::Ref<DenseMatrix> B) const = 0;
  /// B ← A⁻ᵀ B in place; equals solve() for the symmetric factorizations.
  virtual FactorResult solve_transposed(Eigen::Ref<DenseMatrix> B) const { return solve(B); }
  /// Number of entries in the factor(s): predicted after analyze(), actual after factorize().
  virtual long factor_nnz() const = 0;
  /// Floating-point operations of one numeric factorization as predicted by the symbolic
  /// analysis (0 when the backend does not predict them).
  virtual double factor_flops() const { return 0.0; }
  /// Dimension of the analysed matrix (0 before analyze()).
  virtual Index rows() const = 0;
  virtual const char* name() const = 0;
  /// Whether inertia() is meaningful: the LDLᵀ factorizations report the signs of D of the
  /// last numeric factorization (a caller verifies a quasi-definite matrix with it); LLᵀ
  /// and LU do not (LLᵀ fails on a matrix that is not positive definite anyway).
  virtual bool reports_inertia() const { return false; }
  virtual Inertia inertia() const { return {}; }
  /// Whether refactorize_pivoted() can differ from factorize(): a backend that factorizes
  /// in a static pivot order (PetscMumpsLdlt without pivoting) can repeat its last numeric
  /// factorization with numerical (threshold) pivoting, for a caller whose inertia check
  /// rejected the static-order factor (roundoff can flip a pivot's sign there).
  virtual bool can_refactorize_pivoted() const { return false; }
  /// The last factorize()'s matrix factorized again, with numerical pivoting; the factor,
  /// inertia() and solve() are then this one's. Only after a factorize() of the same
  /// analysis; the next factorize() is in the static order again. Default: invalid_input.
  virtual FactorResult refactorize_pivoted() {
    return {FactorStatus::invalid_input, -1, std::string(name()) + " has no pivoted refactorization"};
  }
  /// Numeric factorizations performed since construction (so tests can count reuse).
  int numeric_factorizations() const { return numeric_factorizations_; }

 protected:
  int numeric_factorizations_ = 0;
};

}  // namespace lcprelax::sparse
