// Sparse Lemke basis: KLU LU of B₀ plus a Schur-complement block update for the columns
// replaced since (formulas in lemke_basis.hpp). An update is refused, forcing a fresh
// KLU factorization of the current basis, when |P| reaches the refactorization interval
// or the Schur complement's reciprocal condition estimate falls below 1e-12.
#include "lemke_basis.hpp"

#include <lcprelax/sparse/klu_lu.hpp>

#include <Eigen/LU>

namespace lcprelax::detail {
namespace {

class SparseLemkeBasis final : public LemkeBasis {
 public:
  SparseLemkeBasis(const LemkeColumns& columns, int refactor_interval)
      : cols_(columns), interval_(refactor_interval), slot_(columns.n, -1) {}

  bool refactor(const std::vector<Index>& basic) override {
    const Index n = cols_.n;
    std::vector<Triplet> t;
    t.reserve(static_cast<std::size_t>(cols_.M->nonZeros() + n));
    for (Index k = 0; k < n; ++k) cols_.append(basic[k], k, t);
    SparseMatrix B0(n, n);
    B0.setFromTriplets(t.begin(), t.end());
    B0.makeCompressed();
    for (Index p : pos_) slot_[p] = -1;
    pos_.clear();
    W_.resize(n, interval_);
    if (!klu_.analyze(B0).ok()) return false;
    return klu_.factorize(B0).ok();
  }

  void solve_column(Index var, Vector& a) override {
    pending_.resize(cols_.n);
    cols_.dense(var, pending_);
    klu_.solve(pending_);
    a = pending_;
    correct(a);
  }

  void solve(Vector& x) const override {
    klu_.solve(x);
    correct(x);
  }

  void solve_transposed(Vector& x) const override { solve_transposed_block(x); }

  // B⁻ᵀ E_rows: here (W − E_P)ᵀ E_rows is read off W's rows, no product needed.
  void inverse_rows(const std::vector<Index>& rows, DenseMatrix& out) const override {
    const Index m = static_cast<Index>(rows.size()), k = static_cast<Index>(pos_.size());
    out = DenseMatrix::Zero(cols_.n, m);
    for (Index c = 0; c < m; ++c) out(rows[c], c) = 1.0;
    if (k > 0) {
      DenseMatrix s(k, m);
      for (Index c = 0; c < m; ++c) s.col(c) = W_.row(rows[c]).head(k).transpose();
      for (Index j = 0; j < k; ++j) s.row(j) -= out.row(pos_[j]);
      const DenseMatrix t = s_lu_.transpose().solve(s);
      for (Index j = 0; j < k; ++j) out.row(pos_[j]) -= t.row(j);
    }
    klu_.solve_transposed(out);
  }

  bool replace(Index r, const Vector& /*a*/) override {
    Index j = slot_[r];
    if (j < 0) {
      if (static_cast<int>(pos_.size()) >= interval_) return false;
      j = static_cast<Index>(pos_.size());
      pos_.push_back(r);
      slot_[r] = static_cast<int>(j);
    }
    W_.col(j) = pending_;
    const Index k = static_cast<Index>(pos_.size());
    DenseMatrix S(k, k);
    for (Index a = 0; a < k; ++a) S.row(a) = W_.row(pos_[a]).head(k);
    s_lu_.compute(S);
    return s_lu_.rcond() > 1e-12;
  }

  long memory_bytes() const override {
    return static_cast<long>(sizeof(double)) * (klu_.factor_nnz() + W_.size()) +
           static_cast<long>(sizeof(int)) * klu_.factor_nnz();
  }

 private:
  // X ← B⁻ᵀ X = B₀⁻ᵀ (X − E_P S⁻ᵀ (W − E_P)ᵀ X), all columns in one KLU call.
  template <class Block>
  void solve_transposed_block(Block& X) const {
    const Index k = static_cast<Index>(pos_.size());
    if (k > 0) {
      DenseMatrix s = W_.leftCols(k).transpose() * X;
      for (Index j = 0; j < k; ++j) s.row(j) -= X.row(pos_[j]);
      const DenseMatrix t = s_lu_.transpose().solve(s);
      for (Index j = 0; j < k; ++j) X.row(pos_[j]) -= t.row(j);
    }
    klu_.solve_transposed(X);
  }

  // y ← y − (W − E_P) S⁻¹ y_P, turning B₀⁻¹r into B⁻¹r.
  void correct(Vector& y) const {
    const Index k = static_cast<Index>(pos_.size());
    if (k == 0) return;
    Vector yp(k);
    for (Index j = 0; j < k; ++j) yp(j) = y(pos_[j]);
    const Vector t = s_lu_.solve(yp);
    y.noalias() -= W_.leftCols(k) * t;
    for (Index j = 0; j < k; ++j) y(pos_[j]) += t(j);
  }

  LemkeColumns cols_;
  int interval_;
  sparse::KluLu klu_;
  std::vector<Index> pos_;  // replaced positions P
  std::vector<int> slot_;   // slot of a position in P, or −1
  DenseMatrix W_;           // B₀⁻¹ C, column j for position pos_[j]
  Eigen::PartialPivLU<DenseMatrix> s_lu_;
  Vector pending_;          // B₀⁻¹ c of the last solve_column
};

}  // namespace

std::unique_ptr<LemkeBasis> make_sparse_lemke_basis(const LemkeColumns& columns, int refactor_interval) {
  return std::make_unique<SparseLemkeBasis>(columns, refactor_interval);
}

}  // namespace lcprelax::detail
