#pragma once
// Shared by the factorization tests (sparse_factorization_test.cpp and the backend-specific
// sparse_*_test.cpp files): seeded right-hand sides, the residuals of a solve, the full
// matrix of an upper triangle, and seeded random SPD, quasi-definite and grid matrices.
#include <lcprelax/sparse/types.hpp>

#include <cmath>
#include <random>
#include <vector>

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

/// ‖A X − B‖∞ / ‖B‖∞ (A full): the residual relative to the right-hand side, stricter than
/// the backward error for a well-conditioned A.
inline double residual_over_rhs(const DenseMatrix& A, const DenseMatrix& X, const DenseMatrix& B) {
  return (A * X - B).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff();
}

/// The full symmetric matrix whose upper triangle (with diagonal) is `upper`.
inline DenseMatrix symmetric_from_upper(const SparseMatrix& upper) {
  const DenseMatrix U = DenseMatrix(upper);
  return U.selfadjointView<Eigen::Upper>();
}

/// Full symmetric SPD n×n, diagonally dominant, about 15% of the entries; the pattern
/// depends on n only, the values on seed, times scale.
inline SparseMatrix spd(int n, unsigned seed, double scale = 1.0) {
  std::mt19937 gen(seed), pattern(4321);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::bernoulli_distribution keep(0.15);
  std::vector<Triplet> t;
  std::vector<double> row_sum(static_cast<std::size_t>(n), 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = j + 1; i < n; ++i) {
      if (!keep(pattern)) continue;
      const double v = scale * val(gen);
      t.emplace_back(i, j, v);
      t.emplace_back(j, i, v);
      row_sum[static_cast<std::size_t>(i)] += std::abs(v);
      row_sum[static_cast<std::size_t>(j)] += std::abs(v);
    }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, row_sum[static_cast<std::size_t>(i)] + scale * (1.0 + std::abs(val(gen))));
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

/// Full symmetric quasi-definite K = [H Bᵀ; B −D]: H = spd(n, seed, scale), B m×n with
/// about 15% of its entries and B(r, r mod n) ≠ 0, D positive diagonal; the pattern depends
/// on (n, m) only, the values on seed, times scale.
inline SparseMatrix quasi_definite_kkt(int n, int m, unsigned seed, double scale = 1.0) {
  const SparseMatrix H = spd(n, seed, scale);
  std::mt19937 gen(seed + 1000), pattern(8765);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::bernoulli_distribution keep(0.15);
  std::vector<Triplet> t;
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(H, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  for (int r = 0; r < m; ++r) {
    for (int c = 0; c < n; ++c) {
      if (!keep(pattern) && c != r % n) continue;
      const double v = scale * val(gen);
      t.emplace_back(n + r, c, v);
      t.emplace_back(c, n + r, v);
    }
    t.emplace_back(n + r, n + r, -scale * (0.1 + std::abs(val(gen))));
  }
  SparseMatrix K(n + m, n + m);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

/// Full symmetric SPD 2-D Laplacian-like matrix on a k×k grid with random positive weights
/// (U(0.5, 2) from std::mt19937(seed)) plus shift·I: dense enough after fill-in to give
/// CholmodLlt real supernodes.
inline SparseMatrix grid_spd(int k, unsigned seed, double shift = 0.1) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> w(0.5, 2.0);
  const int n = k * k;
  std::vector<double> diag(static_cast<std::size_t>(n), shift);
  std::vector<Triplet> t;
  auto edge = [&](int a, int b) {
    const double v = w(gen);
    t.emplace_back(a, b, -v);
    t.emplace_back(b, a, -v);
    diag[static_cast<std::size_t>(a)] += v;
    diag[static_cast<std::size_t>(b)] += v;
  };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      if (i + 1 < k) edge(i * k + j, (i + 1) * k + j);
      if (j + 1 < k) edge(i * k + j, i * k + j + 1);
    }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, diag[static_cast<std::size_t>(i)]);
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace lcprelax::test
