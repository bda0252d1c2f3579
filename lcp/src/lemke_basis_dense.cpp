// Dense Lemke basis: explicit B⁻¹ with product-form (Gauss–Jordan) column replacement and
// a partial-pivoting LU refactorization every refactor_interval pivots (lemke_basis.hpp).
#include "lemke_basis.hpp"

#include <Eigen/LU>

namespace lcprelax::detail {

void LemkeColumns::dense(Index var, Eigen::Ref<Vector> out) const {
  if (var < n) {
    out.setZero();
    out(var) = 1.0;
  } else if (var < 2 * n) {
    out.setZero();
    for (SparseMatrix::InnerIterator it(*M, var - n); it; ++it) out(it.row()) = -it.value();
  } else {
    out = -*d;
  }
}

void LemkeColumns::add_to(Index var, double alpha, Vector& y) const {
  if (alpha == 0.0) return;
  if (var < n) {
    y(var) += alpha;
  } else if (var < 2 * n) {
    for (SparseMatrix::InnerIterator it(*M, var - n); it; ++it) y(it.row()) -= alpha * it.value();
  } else {
    y -= alpha * *d;
  }
}

void LemkeColumns::append(Index var, Index col, std::vector<Triplet>& out) const {
  if (var < n) {
    out.emplace_back(static_cast<int>(var), static_cast<int>(col), 1.0);
  } else if (var < 2 * n) {
    for (SparseMatrix::InnerIterator it(*M, var - n); it; ++it)
      if (it.value() != 0.0) out.emplace_back(static_cast<int>(it.row()), static_cast<int>(col), -it.value());
  } else {
    for (Index i = 0; i < n; ++i) out.emplace_back(static_cast<int>(i), static_cast<int>(col), -(*d)(i));
  }
}

namespace {

class DenseLemkeBasis final : public LemkeBasis {
 public:
  DenseLemkeBasis(const LemkeColumns& columns, int refactor_interval)
      : cols_(columns), interval_(refactor_interval) {}

  bool refactor(const std::vector<Index>& basic) override {
    const Index n = cols_.n;
    DenseMatrix B(n, n);
    for (Index k = 0; k < n; ++k) cols_.dense(basic[k], B.col(k));
    lu_.compute(B);
    binv_ = lu_.inverse();
    updates_ = 0;
    // Singular bases give non-finite inverses; ill-conditioned ones are accepted (the
    // final residual check decides).
    return binv_.allFinite();
  }

  void solve_column(Index var, Vector& a) override {
    a.resize(cols_.n);
    cols_.dense(var, a);
    a = binv_ * a;
  }

  void solve(Vector& x) const override {
    if (updates_ == 0) x = lu_.solve(x);
    else x = binv_ * x;
  }

  void solve_transposed(Vector& x) const override {
    if (updates_ == 0) x = lu_.transpose().solve(x);
    else x = binv_.transpose() * x;
  }

  void inverse_rows(const std::vector<Index>& rows, DenseMatrix& out) const override {
    out.resize(cols_.n, static_cast<Index>(rows.size()));
    for (std::size_t k = 0; k < rows.size(); ++k) out.col(static_cast<Index>(k)) = binv_.row(rows[k]).transpose();
  }

  bool replace(Index r, const Vector& a) override {
    const double ar = a(r);
    binv_.row(r) /= ar;
    for (Index i = 0; i < cols_.n; ++i)
      if (i != r && a(i) != 0.0) binv_.row(i) -= a(i) * binv_.row(r);
    ++updates_;
    return updates_ < interval_;
  }

  long memory_bytes() const override { return 2L * cols_.n * cols_.n * static_cast<long>(sizeof(double)); }

 private:
  LemkeColumns cols_;
  int interval_;
  int updates_ = 0;
  Eigen::PartialPivLU<DenseMatrix> lu_;
  DenseMatrix binv_;
};

}  // namespace

std::unique_ptr<LemkeBasis> make_dense_lemke_basis(const LemkeColumns& columns, int refactor_interval) {
  return std::make_unique<DenseLemkeBasis>(columns, refactor_interval);
}

}  // namespace lcprelax::detail
