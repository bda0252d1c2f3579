#pragma once
// The convex quadratic program solved by lcprelax's interior point:
//
//     minimize    ½ xᵀ P x + qᵀ x + r
//     subject to  A x = b,   l ≤ G x ≤ u,   xl ≤ x ≤ xu
//
// - P (n×n) is symmetric positive semidefinite, given as its UPPER triangle (including
//   the diagonal); an entry below the diagonal is an input error. A stored off-diagonal
//   value p at (i,j) means P(i,j) = P(j,i) = p.
// - A (me×n), G (mi×n) sparse; l, u may hold −∞ / +∞ (one-sided or free rows); a row
//   with l_i = u_i is an equality row. xl, xu may hold ±∞.
// - Multiplier convention: y (one per row of A), z (one per row of G),
//   z_bounds (one per variable) satisfy  P x + q + Aᵀ y + Gᵀ z + z_bounds = 0, with z_i > 0
//   where the upper side u_i is active and z_i < 0 where the lower side l_i is active.
#include <lcprelax/sparse/types.hpp>

#include <string>

namespace lcprelax {

struct QpProblem {
  SparseMatrix P;  ///< n×n, upper triangle of the PSD Hessian
  Vector q;        ///< n, linear cost
  double r = 0.0;  ///< constant cost term (reported in the objective only)
  SparseMatrix A;  ///< me×n equality matrix
  Vector b;        ///< me
  SparseMatrix G;  ///< mi×n inequality matrix
  Vector l;        ///< mi lower row bounds (−∞ allowed)
  Vector u;        ///< mi upper row bounds (+∞ allowed)
  Vector xl;       ///< n lower variable bounds (−∞ allowed)
  Vector xu;       ///< n upper variable bounds (+∞ allowed)

  QpProblem() = default;
  /// An unconstrained problem with n variables: P = 0, q = 0, no rows, free variables.
  explicit QpProblem(Index n);

  Index num_variables() const { return static_cast<Index>(q.size()); }
  Index num_equalities() const { return static_cast<Index>(A.rows()); }
  Index num_inequalities() const { return static_cast<Index>(G.rows()); }

  /// Empty string when the data are consistent, else a message naming the first bad field
  /// (dimension mismatch, NaN, +∞ in l or −∞ in u, l > u, P not upper triangular, ...).
  std::string validation_error() const;
  /// Throws lcprelax::InputError with validation_error() when it is not empty.
  void validate() const;
  /// True when P, A and G have the same sparsity patterns and all sizes agree with `other`.
  bool same_pattern(const QpProblem& other) const;
  /// ½ xᵀ P x + qᵀ x + r.
  double objective(const Vector& x) const;
};

}  // namespace lcprelax
