// Dense Lemke basis: explicit B⁻¹ with product-form (Gauss–Jordan) column replacement and
// a partial-pivoting LU refactorization every refactor_interval pivots (lemke_basis.hpp).
// All work arrays are sized at construction; nothing but solve_transposed allocates.
#include "lemke_basis.hpp"

#include <Eigen/LU>

namespace lcprelax::detail {

namespace {

class DenseLemkeBasis final : public LemkeBasis {
 public:
  DenseLemkeBasis(const LemkeColumns& columns, int refactor_interval)
      : cols_(columns),
        interval_(refactor_interval),
        lu_(columns.n),
        binv_(columns.n, columns.n),
        col_(columns.n),
        row_(columns.n) {}

  bool refactor(const std::vector<Index>& basic) override {
    const Index n = cols_.n;
    for (Index k = 0; k < n; ++k) cols_.dense(basic[k], binv_.col(k));  // B, in B⁻¹'s storage
    lu_.compute(binv_);
    // B⁻¹ = U⁻¹ L⁻¹ P: P into binv_, then the two triangular solves in place.
    const auto& perm = lu_.permutationP().indices();
    binv_.setZero();
    for (Index k = 0; k < n; ++k) binv_(perm(k), k) = 1.0;
    lu_.matrixLU().template triangularView<Eigen::UnitLower>().solveInPlace(binv_);
    lu_.matrixLU().template triangularView<Eigen::Upper>().solveInPlace(binv_);
    updates_ = 0;
    // Singular bases give non-finite inverses; ill-conditioned ones are accepted (the
    // final residual check decides).
    return binv_.allFinite();
  }

  void solve_column(Index var, Vector& a) override {
    cols_.dense(var, col_);
    a.noalias() = binv_ * col_;
  }

  // Right after a refactorization the LU solve (more accurate than B⁻¹x) is used.
  void solve(Vector& x) override {
    col_ = x;
    if (updates_ == 0) x = lu_.solve(col_);
    else x.noalias() = binv_ * col_;
  }

  void solve_transposed(Vector& x) const override {
    const Vector y = x;
    if (updates_ == 0) x = lu_.transpose().solve(y);
    else x.noalias() = binv_.transpose() * y;
  }

  void inverse_rows(const std::vector<Index>& rows, Eigen::Ref<DenseMatrix> out) override {
    for (std::size_t k = 0; k < rows.size(); ++k) out.col(static_cast<Index>(k)) = binv_.row(rows[k]).transpose();
  }

  void inverse_row_nonzeros(Index r, std::vector<int>& index, std::vector<double>& value) override {
    index.clear();
    value.clear();
    for (Index j = 0; j < cols_.n; ++j)
      if (binv_(r, j) != 0.0) {
        index.push_back(static_cast<int>(j));
        value.push_back(binv_(r, j));
      }
  }

  // Gauss–Jordan step on B⁻¹: row r /= a_r, then row i −= a_i · row r for i ≠ r (one
  // rank-1 update with a_r set to 0).
  bool replace(Index r, const Vector& a) override {
    binv_.row(r) /= a(r);
    row_ = binv_.row(r).transpose();
    col_ = a;
    col_(r) = 0.0;
    binv_.noalias() -= col_ * row_.transpose();
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
  Vector col_, row_;  // work vectors
};

}  // namespace

std::unique_ptr<LemkeBasis> make_dense_lemke_basis(const LemkeColumns& columns, int refactor_interval) {
  return std::make_unique<DenseLemkeBasis>(columns, refactor_interval);
}

}  // namespace lcprelax::detail
