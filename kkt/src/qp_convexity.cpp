// Convexity tests of a QP's Hessian (method and tolerances in kkt/qp_convexity.hpp).
#include <lcprelax/kkt/qp_convexity.hpp>

#include <lcprelax/sparse/cholmod_llt.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace lcprelax {
namespace {

// P(j, j), or 0 when column j stores no diagonal entry. Eigen keeps the inner indices of a
// column sorted, so in an upper triangle the diagonal is the column's last entry.
double diagonal(const SparseMatrix& P, Index j) {
  const Index begin = P.outerIndexPtr()[j];
  const Index end = P.isCompressed() ? P.outerIndexPtr()[j + 1] : begin + P.innerNonZeroPtr()[j];
  if (end == begin || P.innerIndexPtr()[end - 1] != j) return 0.0;
  return P.valuePtr()[end - 1];
}

std::string zero_diagonal_error(const std::string& name, Index i, Index j, double v, Index zero) {
  std::ostringstream os;
  os << name << " is not positive semidefinite: " << name << "(" << i << ", " << j
     << ") = " << v << " while " << name << "(" << zero << ", " << zero
     << ") = 0 (a positive semidefinite matrix has a zero row where its diagonal is zero)";
  return os.str();
}

std::string minor_error(const std::string& name, Index i, Index j, double v, double di, double dj) {
  std::ostringstream os;
  os.precision(6);
  os << name << " is not positive semidefinite: " << name << "(" << i << ", " << j
     << ")² = " << v * v << " > " << name << "(" << i << ", " << i << ")·" << name << "(" << j << ", " << j
     << ") = " << di * dj;
  return os.str();
}

// τ of the header comment: kPsdRoundoff times the largest diagonal entry.
double roundoff_shift(const SparseMatrix& P) {
  double largest = 0.0;
  for (Index j = 0; j < P.outerSize(); ++j) largest = std::max(largest, diagonal(P, j));
  return kPsdRoundoff * largest;
}

}  // namespace

std::string psd_minor_error(const SparseMatrix& P, const std::string& name) {
  const double tau = roundoff_shift(P);
  for (Index j = 0; j < P.outerSize(); ++j) {
    const double dj = diagonal(P, j) + tau;
    for (SparseMatrix::InnerIterator it(P, j); it; ++it) {
      const Index i = it.row();
      const double v = it.value();
      if (i == j || v == 0.0) continue;
      const double di = diagonal(P, i) + tau;
      if (di <= 0.0 || dj <= 0.0) return zero_diagonal_error(name, i, j, v, di <= 0.0 ? i : j);
      // |S_ij| = |v| / √(di·dj) ≤ 1 + δ, written without overflow of v².
      if (std::abs(v) / std::sqrt(di) / std::sqrt(dj) > 1.0 + kPsdTolerance) {
        if (di == tau || dj == tau) return zero_diagonal_error(name, i, j, v, di == tau ? i : j);
        return minor_error(name, i, j, v, di - tau, dj - tau);
      }
    }
  }
  return {};
}

std::string psd_error(const SparseMatrix& P, const std::string& name) {
  if (std::string e = psd_minor_error(P, name); !e.empty()) return e;
  const Index n = P.outerSize();
  bool off_diagonal = false;  // a diagonal P ≥ 0 (validate()) is PSD: no factorization
  for (Index j = 0; j < n && !off_diagonal; ++j)
    for (SparseMatrix::InnerIterator it(P, j); it; ++it)
      if (it.row() != j && it.value() != 0.0) off_diagonal = true;
  if (!off_diagonal) return {};
  // Support J (columns with a nonzero entry) and the scaling D = diag(P_JJ + τI)^(-1/2).
  const double tau = roundoff_shift(P);
  std::vector<bool> used(static_cast<std::size_t>(n), false);
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(P, j); it; ++it)
      if (it.value() != 0.0) used[static_cast<std::size_t>(j)] = used[static_cast<std::size_t>(it.row())] = true;
  std::vector<Index> position(static_cast<std::size_t>(n), -1);
  std::vector<Index> support;
  Vector scale(n);
  for (Index j = 0; j < n; ++j) {
    const double d = diagonal(P, j) + tau;
    if (d > 0.0 && used[static_cast<std::size_t>(j)]) {
      position[static_cast<std::size_t>(j)] = static_cast<Index>(support.size());
      support.push_back(j);
      scale(j) = 1.0 / std::sqrt(d);
    }
  }
  const Index m = static_cast<Index>(support.size());
  if (m <= 1) return {};  // diagonal ≥ 0 (validate()) and no off-diagonal entry off J
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(P.nonZeros()));
  for (Index j = 0; j < n; ++j) {
    const Index cj = position[static_cast<std::size_t>(j)];
    if (cj < 0) continue;
    t.emplace_back(cj, cj, 1.0 + kPsdTolerance);  // (P_jj + τ)·D_jj² = 1, plus δ
    for (SparseMatrix::InnerIterator it(P, j); it; ++it) {
      if (it.value() == 0.0 || it.row() == j) continue;  // explicit zeros; the diagonal above
      const Index ci = position[static_cast<std::size_t>(it.row())];
      t.emplace_back(ci, cj, it.value() * scale(it.row()) * scale(j));
    }
  }
  SparseMatrix S(m, m);
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();

  std::ostringstream os;
  os << name << " is not positive semidefinite: ";
  if (m <= kDensePsdMax) {
    const DenseMatrix dense = DenseMatrix(S).selfadjointView<Eigen::Upper>();
    Eigen::LLT<DenseMatrix> llt(dense);
    if (llt.info() == Eigen::Success) return {};
    // The smallest eigenvalue of P itself on its support (not of S), as a witness.
    DenseMatrix PJ(m, m);
    for (Index a = 0; a < m; ++a)
      for (Index b = 0; b < m; ++b) PJ(a, b) = dense(a, b) / scale(support[a]) / scale(support[b]);
    for (Index a = 0; a < m; ++a) PJ(a, a) = diagonal(P, support[a]);
    const Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(PJ, Eigen::EigenvaluesOnly);
    os << "its smallest eigenvalue is " << eig.eigenvalues()(0);
    return os.str();
  }
  sparse::CholmodLlt llt(sparse::CholmodOrdering::amd);
  sparse::FactorResult r = llt.analyze(S);
  if (r.ok()) r = llt.factorize(S);
  if (r.ok()) return {};
  if (r.status != sparse::FactorStatus::not_positive_definite) {
    os.str("");
    os << name << ": the convexity test's Cholesky factorization failed: " << r.message;
    return os.str();
  }
  os << "the Cholesky factorization of diag(" << name << ")^(-1/2)·" << name << "·diag(" << name
     << ")^(-1/2) + " << kPsdTolerance << "·I fails";
  if (r.pivot >= 0 && r.pivot < m) os << " at column " << support[static_cast<std::size_t>(r.pivot)];
  return os.str();
}

}  // namespace lcprelax
