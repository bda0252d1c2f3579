#pragma once
// Shared by the factorization tests (sparse_factorization_test.cpp and the backend-specific
// sparse_*_test.cpp files): seeded right-hand sides and the backward error of a solve.
#include <lcprelax/sparse/types.hpp>

#include <random>

namespace lcprelax::test {

/// rows × cols, entries U(−1, 1) from std::mt19937(seed), column by column.
inline DenseMatrix random_rhs(int rows, int cols, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  DenseMatrix B(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) B(i, j) = val(gen);
  return B;
}

/// ‖A X − B‖∞ / (‖A‖∞ ‖X‖∞ + ‖B‖∞), the backward error of the solve A X = B (A full, not
/// only a triangle).
inline double relative_residual(const DenseMatrix& A, const DenseMatrix& X, const DenseMatrix& B) {
  const double a_norm = A.cwiseAbs().rowwise().sum().maxCoeff();
  return (A * X - B).cwiseAbs().maxCoeff() / (a_norm * X.cwiseAbs().maxCoeff() + B.cwiseAbs().maxCoeff());
}

/// The full symmetric matrix whose upper triangle (with diagonal) is `upper`.
inline DenseMatrix symmetric_from_upper(const SparseMatrix& upper) {
  const DenseMatrix U = DenseMatrix(upper);
  return U.selfadjointView<Eigen::Upper>();
}

}  // namespace lcprelax::test
