// DenseLdlt: dense LDLᵀ with largest-|diagonal| symmetric pivoting for small quasi-definite
// matrices (method, contract and the choice of pivoting in dense_ldlt.hpp).
//
// Storage: L_ (n×n, column-major) holds the working matrix in its lower triangle. Step k
// picks p = argmax_{j ≥ k} |L_(j,j)|, exchanges row/column k and p of the lower triangle
// (the already computed multipliers of rows k and p move with them, as in LAPACK's
// sytrf), then the right-looking update of the trailing lower triangle
//     S(i,j) ← S(i,j) − w_i w_j / d      (i ≥ j > k, w = column k below the pivot)
// runs column by column on contiguous segments, and column k is scaled by 1/d into L.
// At the end ΠKΠᵀ = L D̂ Lᵀ with Π = T_{n−1}···T_0 (T_k exchanges k and swap_[k]).
#include <lcprelax/sparse/dense_ldlt.hpp>

#include "matrix_checks.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

namespace lcprelax::sparse {

DenseLdlt::DenseLdlt(double dynamic_regularization)
    : tau_(dynamic_regularization > 0.0 && std::isfinite(dynamic_regularization) ? dynamic_regularization : 0.0) {}

FactorResult DenseLdlt::analyze(const SparseMatrix& A) {
  analysed_ = factored_ = false;
  n_ = 0;
  inertia_ = Inertia{};
  regularized_ = 0;
  if (auto r = detail::check_square(A); !r.ok()) return r;
  if (A.rows() > kMaxDimension)
    return detail::make_result(FactorStatus::out_of_memory, "dense LDL' refused: dimension " +
                                                                std::to_string(A.rows()) + " > " +
                                                                std::to_string(kMaxDimension));
  detail::CompressedRef ref(A);
  const SparseMatrix& a = ref.get();
  n_ = static_cast<Index>(a.rows());
  outer_.assign(a.outerIndexPtr(), a.outerIndexPtr() + n_ + 1);
  inner_.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
  L_.setZero(n_, n_);
  swap_.resize(static_cast<std::size_t>(n_));
  perm_.resize(static_cast<std::size_t>(n_));
  analysed_ = true;
  return {};
}

FactorResult DenseLdlt::factorize(const SparseMatrix& A) {
  if (!analysed_) return detail::make_result(FactorStatus::not_analyzed, "factorize() before analyze()");
  detail::CompressedRef ref(A);
  const SparseMatrix& a = ref.get();
  if (a.rows() != n_ || a.cols() != n_ || static_cast<std::size_t>(a.nonZeros()) != inner_.size() ||
      !std::equal(outer_.begin(), outer_.end(), a.outerIndexPtr()) ||
      !std::equal(inner_.begin(), inner_.end(), a.innerIndexPtr()))
    return detail::make_result(FactorStatus::pattern_mismatch,
                               "sparsity pattern differs from the one given to analyze()");
  if (auto r = detail::check_finite(a); !r.ok()) return r;
  factored_ = false;
  inertia_ = Inertia{};
  regularized_ = 0;

  // Scatter the upper triangle of A into the lower triangle of L_ (a_ij → L_(j,i)).
  const Index n = n_;
  L_.setZero();
  for (Index j = 0; j < n; ++j)
    for (Index s = outer_[j]; s < outer_[j + 1]; ++s)
      if (inner_[s] <= j) L_(j, inner_[s]) += a.valuePtr()[s];
  std::iota(perm_.begin(), perm_.end(), Index{0});

  for (Index k = 0; k < n; ++k) {
    Index p = k;  // largest |diagonal| of the Schur complement (NaN never wins)
    double best = -1.0;
    for (Index j = k; j < n; ++j)
      if (std::abs(L_(j, j)) > best) {
        best = std::abs(L_(j, j));
        p = j;
      }
    swap_[static_cast<std::size_t>(k)] = p;
    if (p != k) {
      const Index tail = n - p - 1;
      L_.row(k).head(k).swap(L_.row(p).head(k));
      L_.col(k).tail(tail).swap(L_.col(p).tail(tail));
      std::swap(L_(k, k), L_(p, p));
      for (Index i = k + 1; i < p; ++i) std::swap(L_(i, k), L_(p, i));
      std::swap(perm_[static_cast<std::size_t>(k)], perm_[static_cast<std::size_t>(p)]);
    }
    double d = L_(k, k);
    const Index column = perm_[static_cast<std::size_t>(k)];
    if (tau_ > 0.0 && std::abs(d) < tau_) {  // CHOLMOD's dbound rule (NaN is not < τ)
      d = d < 0.0 ? -tau_ : tau_;
      L_(k, k) = d;
      ++regularized_;
    }
    if (!(d != 0.0) || !std::isfinite(d))
      return detail::make_result(FactorStatus::zero_pivot,
                                 std::string(d == 0.0 ? "zero" : "non-finite") + " pivot in dense LDL': step " +
                                     std::to_string(k) + " (column " + std::to_string(column) +
                                     " of the input matrix)",
                                 column);
    const Index r = n - k - 1;
    for (Index j = k + 1; j < n; ++j) {
      const double c = L_(j, k) / d;
      if (c != 0.0) L_.col(j).segment(j, n - j).noalias() -= c * L_.col(k).segment(j, n - j);
    }
    L_.col(k).tail(r) /= d;
    if (d > 0.0)
      ++inertia_.positive;
    else
      ++inertia_.negative;
  }
  factored_ = true;
  ++numeric_factorizations_;
  return {};
}

FactorResult DenseLdlt::solve(Eigen::Ref<DenseMatrix> B) const {
  if (!factored_) return detail::make_result(FactorStatus::not_analyzed, "solve() before a successful factorize()");
  if (auto r = detail::check_rhs(n_, static_cast<Index>(B.rows())); !r.ok()) return r;
  const Index n = n_;
  for (Eigen::Index c = 0; c < B.cols(); ++c) {
    auto b = B.col(c);
    for (Index k = 0; k < n; ++k)  // y = Π b
      if (swap_[static_cast<std::size_t>(k)] != k) std::swap(b(k), b(swap_[static_cast<std::size_t>(k)]));
    for (Index k = 0; k < n; ++k)  // L y' = y (unit lower, column-oriented)
      if (b(k) != 0.0) b.tail(n - k - 1).noalias() -= b(k) * L_.col(k).tail(n - k - 1);
    for (Index k = 0; k < n; ++k) b(k) /= L_(k, k);
    for (Index k = n - 1; k >= 0; --k)  // Lᵀ z = D̂⁻¹ y' (row-oriented on L's columns)
      b(k) -= L_.col(k).tail(n - k - 1).dot(b.tail(n - k - 1));
    for (Index k = n - 1; k >= 0; --k)  // x = Πᵀ z
      if (swap_[static_cast<std::size_t>(k)] != k) std::swap(b(k), b(swap_[static_cast<std::size_t>(k)]));
  }
  return {};
}

long DenseLdlt::factor_nnz() const { return static_cast<long>(n_) * (static_cast<long>(n_) + 1) / 2; }

}  // namespace lcprelax::sparse
