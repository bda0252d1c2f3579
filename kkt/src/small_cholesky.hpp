#pragma once
// Cholesky factorization A = LLᵀ of a small dense SPD matrix (n ≲ 100) with plain loops on
// contiguous column-major storage whose capacity is kept between factorizations of varying
// size (DenseQpSolver factorizes matrices of a few to a few tens of rows thousands of times
// per batch; Eigen::LLT reallocates on each size change and runs blocked dynamic-size code).
// compute() fails (returns false) on a pivot that is not positive and finite. Internal to the
// dense QP solver.
#include <lcprelax/sparse/types.hpp>

#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace lcprelax::detail {

class SmallCholesky {
 public:
  /// Factorizes the n×n matrix A (any Eigen expression); the storage only grows, so
  /// factorizations of varying sizes up to the largest one seen do not allocate.
  template <class Derived>
  bool compute(const Eigen::MatrixBase<Derived>& A) {
    const Index n = A.rows();
    n_ = n;
    if (static_cast<Index>(buf_.size()) < n * n) buf_.resize(static_cast<std::size_t>(n * n));
    Eigen::Map<Eigen::MatrixXd>(buf_.data(), n, n) = A;
    double* l = buf_.data();
    for (Index j = 0; j < n; ++j) {
      double* cj = l + j * n;
      for (Index k = 0; k < j; ++k) {  // column j −= L(j,k)·column k (rows ≥ j)
        const double* ck = l + k * n;
        const double ljk = ck[j];
        for (Index i = j; i < n; ++i) cj[i] -= ljk * ck[i];
      }
      const double pivot = cj[j];
      if (!(pivot > 0.0) || !std::isfinite(pivot)) return false;
      const double root = std::sqrt(pivot), inv = 1.0 / root;
      cj[j] = root;
      for (Index i = j + 1; i < n; ++i) cj[i] *= inv;
    }
    return true;
  }

  /// b ← L⁻¹ b.
  template <class V>
  void solve_lower(V& b) const {
    const Index n = n_;
    const double* l = buf_.data();
    for (Index j = 0; j < n; ++j) {
      const double* cj = l + j * n;
      const double v = b[j] / cj[j];
      b[j] = v;
      for (Index i = j + 1; i < n; ++i) b[i] -= cj[i] * v;
    }
  }

  /// b ← L⁻ᵀ b.
  template <class V>
  void solve_upper(V& b) const {
    const Index n = n_;
    const double* l = buf_.data();
    for (Index j = n - 1; j >= 0; --j) {
      const double* cj = l + j * n;
      double v = b[j];
      for (Index i = j + 1; i < n; ++i) v -= cj[i] * b[i];
      b[j] = v / cj[j];
    }
  }

  /// b ← A⁻¹ b.
  void solve_in_place(Vector& b) const {
    solve_lower(b);
    solve_upper(b);
  }

  /// Each column of B ← L⁻¹ column.
  template <class M>
  void solve_lower_columns(M&& B) const {
    for (Index c = 0; c < B.cols(); ++c) {
      auto col = B.col(c);
      solve_lower(col);
    }
  }

 private:
  std::vector<double> buf_;  // L, column-major n_×n_ (capacity kept)
  Index n_ = 0;
};

}  // namespace lcprelax::detail
