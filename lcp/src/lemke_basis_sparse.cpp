// Sparse Lemke basis: KLU LU of B₀ plus a Schur-complement block update for the columns
// replaced since (formulas in lemke_basis.hpp). An update is refused, forcing a fresh
// factorization of the current basis, when |P| reaches min(refactor_interval,
// kMaxSchurUpdates) or the Schur complement's reciprocal condition estimate falls below
// kSchurRcondFloor = 1e-15; between that and kSchurRcondCheck = 1e-12 the update is kept
// but flagged (update_needs_check), and the pivot loop refactorizes only if the updated
// basic values' residual is above its bound (lemke_pivot.cpp): refactorization on measured
// error rather than on the estimate alone (on bases of M + εI of a settled 1,000-body pile
// the estimate fell below 1e-12 every 10-13 pivots). B₀ = I (the all-w basis Lemke starts
// from) is represented without KLU. Rows of B⁻¹ for the lexicographic tie-breaks come
// from hypersparse transposed solves with B₀'s
// factors (sparse/hypersparse_solve.hpp), copied row-wise from KLU at the first tie after
// a factorization (a dense transposed solve if they cannot be extracted), and each
// entering column's B₀⁻¹c from a hypersparse solve with the same factors, or from a dense
// solve with them that skips zero entries once the solved columns are denser than 10%
// (sparse/hypersparse_column_solve.hpp; KLU's dense solve if they cannot be extracted).
// KLU pivots with the threshold LemkeSettings::lu_pivot_tolerance (1: true partial pivoting,
// the default; KLU's own 0.001 lost accuracy on degenerate pile bases, lcp_types.hpp). Its
// symbolic analysis takes the slack columns e_i of B₀ first as 1×1 blocks and analyses the
// basic z columns in the other rows only (KluLu::analyze, column singletons first).
// B₀ is factorized in the basis' own KLU object or in a shared one (lemke.hpp
// LemkeSharedFactorization); either way KLU's symbolic analysis is skipped when B₀ has the
// pattern analysed last (the orderings depend on the pattern only: same factors).
//
// W is kept dense (for S and the rows of B⁻¹) and by its nonzeros per column (for the
// correction of each solved column, work Σ nnz(W_j) instead of n·|P|). A replacement writes
// both in one pass over the solved column and updates S in one column and row (O(|P|)),
// then refactorizes S's dense LU (|P| ≤ kMaxSchurUpdates).
// Work arrays (W, S and its LU, the CSC arrays of B₀, the solved column) are sized at
// construction; S and its LU have fixed capacity kMaxSchurUpdates², and the small blocks
// of the Schur updates live on the stack, so only klu_analyze/klu_factor allocate, and
// the storage of the factors' row-wise copy, reserved right after each factorization.
// Lifted (lemke_basis.hpp): the factorization is of K, (n + m)-square, and every solve
// pads its right-hand side with m zeros and keeps the first n entries of the solution
// (aug_, sized at construction; solve_transposed and inverse_rows, outside the pivot
// loop, use temporaries).
#include "lemke_basis.hpp"

#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/sparse/hypersparse_column_solve.hpp>
#include <lcprelax/sparse/hypersparse_solve.hpp>
#include <lcprelax/sparse/klu_lu.hpp>

#include <Eigen/LU>

#include <algorithm>

namespace lcprelax::detail {
namespace {

constexpr int kCap = kMaxSchurUpdates;
constexpr double kSchurRcondCheck = 1e-12;  // below: the update's accuracy is measured
constexpr double kSchurRcondFloor = 1e-15;  // below: refused (κ(S) near 1/ε_machine)
constexpr Index kChunk = 8;  // right-hand sides per Schur block solve in inverse_rows
using SchurMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kCap, kCap>;
using SchurVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kCap, 1>;
using SchurBlock = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kCap, kChunk>;

class SparseLemkeBasis final : public LemkeBasis {
 public:
  SparseLemkeBasis(const LemkeColumns& columns, int refactor_interval, bool sparse_columns,
                   LemkeSharedFactorization* shared, double lu_pivot_tolerance, LuOrdering lu_ordering)
      : cols_(columns),
        lu_pivot_tolerance_(lu_pivot_tolerance),
        ordering_(lu_ordering == LuOrdering::colamd ? sparse::KluLu::Ordering::colamd : sparse::KluLu::Ordering::amd),
        sparse_columns_(sparse_columns),
        max_updates_(std::min(refactor_interval, kCap)),
        shared_(shared),
        klu_(shared ? shared->klu : own_klu_),
        slot_(static_cast<std::size_t>(columns.n), -1),
        W_(columns.n, max_updates_),
        B0_(columns.factor_size(), columns.factor_size()),
        pending_(columns.n),
        aug_(columns.lifted() ? columns.factor_size() : 0) {
    pos_.reserve(static_cast<std::size_t>(max_updates_));
    rhs_index_.reserve(static_cast<std::size_t>(max_updates_) + 1);
    rhs_value_.reserve(static_cast<std::size_t>(max_updates_) + 1);
    w_index_.resize(static_cast<std::size_t>(max_updates_));
    w_value_.resize(static_cast<std::size_t>(max_updates_));
    w_dense_.assign(static_cast<std::size_t>(max_updates_), false);
    w_count_.assign(static_cast<std::size_t>(max_updates_), 0);
    for (int j = 0; j < max_updates_; ++j) {
      // Uninitialized storage (new T[n], not a vector's zero fill): written before it is read.
      w_index_[static_cast<std::size_t>(j)].reset(new int[static_cast<std::size_t>(columns.n)]);
      w_value_[static_cast<std::size_t>(j)].reset(new double[static_cast<std::size_t>(columns.n)]);
    }
    col_index_.resize(static_cast<std::size_t>(columns.n));
    col_value_.resize(static_cast<std::size_t>(columns.n));
    x_index_.reserve(static_cast<std::size_t>(columns.factor_size()));
    x_value_.reserve(static_cast<std::size_t>(columns.factor_size()));
    B0_.data().resize(nonzeros_bound());
  }

  bool refactor(const std::vector<Index>& basic) override {
    const Index n = cols_.n;
    for (Index p : pos_) slot_[p] = -1;
    pos_.clear();
    rows_.invalidate();
    columns_.invalidate();
    identity_ = true;
    for (Index k = 0; k < n && identity_; ++k) identity_ = basic[k] == k;
    if (identity_) return true;
    // B₀ (or K) in CSC, written into B0_'s arrays (nonzeros_bound() bounds any basis).
    B0_.data().resize(nonzeros_bound());
    int* outer = B0_.outerIndexPtr();
    int* inner = B0_.innerIndexPtr();
    double* values = B0_.valuePtr();
    const bool lifted = cols_.lifted();
    const Index size = cols_.factor_size();
    Index p = 0;
    for (Index k = 0; k < n; ++k) {
      outer[k] = static_cast<int>(p);
      p += lifted ? cols_.write_lifted_column(basic[k], inner + p, values + p)
                  : cols_.write_column(basic[k], inner + p, values + p);
    }
    for (Index k = n; k < size; ++k) {
      outer[k] = static_cast<int>(p);
      p += cols_.write_dof_column(k - n, inner + p, values + p);
    }
    outer[size] = static_cast<int>(p);
    B0_.data().resize(p);
    // A shared factorization (LemkeSharedFactorization) may hold the analysis of this
    // pattern, and then also a numeric factorization of it: of the basis a simulator's
    // previous time step ended on, when this step starts from that basis. Its pivot order
    // is reused (klu_refactor) unless the condition estimate falls below
    // kReusedPivotsRcondRatio times the pivoted factorization's.
    const bool same_pattern = klu_.analyzed_for(B0_);
    if (!same_pattern) {
      klu_.set_ordering(ordering_);
      if (!klu_.analyze(B0_).ok()) return false;
      if (shared_) ++shared_->analyses;
    }
    if (shared_) ++shared_->factorizations;
    klu_.set_pivot_tolerance(lu_pivot_tolerance_);
    const sparse::FactorResult factored =
        same_pattern ? klu_.factorize_reusing_pivots(B0_, kReusedPivotsRcondRatio) : klu_.factorize(B0_);
    if (!factored.ok()) return false;
    if (shared_ && klu_.reused_pivots()) ++shared_->reused_pivots;
    rows_.reserve(klu_);  // storage for rows_ (built at the first tie) allocated with KLU's
    columns_.reserve(klu_);  // and for columns_ (built at the next solve_column)
    return true;
  }

  // B₀⁻¹c by a hypersparse solve from c's nonzeros (sparse/hypersparse_column_solve.hpp):
  // work in proportion to the factors' entries reached, not to nnz(L + U), while the
  // solved columns are expected sparse; a dense solve when they are not (the depth-first
  // search then costs as much as the solve: measured on piles, whose contacts form one
  // connected network) or when the factors cannot be extracted. The expectation is a
  // running mean of the solved columns' densities with the switch at 10%, as simplex codes
  // switch between hypersparse and dense solves (Hall & McKinnon 2005, "Hyper-sparsity in
  // the revised simplex method and how to exploit it", Comput. Optim. Appl. 32).
  // Above the switch, the dense solve skips the factors' columns of zero solution entries
  // (HypersparseColumnSolver::solve_dense: ~40% of the entries are nonzero on piles of
  // hundreds of bodies, where klu_solve's scatter of every column was most of a pivot).
  void solve_column(Index var, Vector& a) override {
    const bool factors = !identity_ && sparse_columns_ && (columns_.built() || columns_.build(klu_));
    if (!factors) {
      cols_.dense(var, pending_);
      b0_solve(pending_);
    } else if (column_density_ >= kHypersparseDensity) {
      const Index c = cols_.write_column(var, col_index_.data(), col_value_.data());
      const bool lifted = cols_.lifted();
      const Index nonzeros =
          columns_.solve_dense(static_cast<int>(c), col_index_.data(), col_value_.data(), lifted ? aug_ : pending_);
      if (lifted) pending_ = aug_.head(cols_.n);
      column_density_ = 0.9 * column_density_ + 0.1 * static_cast<double>(nonzeros) / static_cast<double>(aug_rows());
    } else {
      const Index c = cols_.write_column(var, col_index_.data(), col_value_.data());
      columns_.solve(static_cast<int>(c), col_index_.data(), col_value_.data(), x_index_, x_value_);
      pending_.setZero();
      for (std::size_t k = 0; k < x_index_.size(); ++k)
        if (x_index_[k] < cols_.n) pending_(x_index_[k]) = x_value_[k];  // K's momentum rows dropped
      column_density_ =
          0.9 * column_density_ + 0.1 * static_cast<double>(x_index_.size()) / static_cast<double>(aug_rows());
    }
    a = pending_;
    correct(a);
  }

  void solve(Vector& x) override {
    b0_solve(x);
    correct(x);
  }

  // x ← B⁻ᵀ x = B₀⁻ᵀ (x − E_P S⁻ᵀ (W − E_P)ᵀ x).
  void solve_transposed(Vector& x) const override {
    const Index k = static_cast<Index>(pos_.size());
    if (k > 0) {
      SchurVector s = W_.leftCols(k).transpose() * x;
      for (Index j = 0; j < k; ++j) s(j) -= x(pos_[j]);
      const SchurVector t = s_lu_.transpose().solve(s);
      for (Index j = 0; j < k; ++j) x(pos_[j]) -= t(j);
    }
    if (identity_) return;
    if (!cols_.lifted()) {
      klu_.solve_transposed(x);
      return;
    }
    Vector padded = Vector::Zero(cols_.factor_size());  // allocates: backward() only
    padded.head(cols_.n) = x;
    klu_.solve_transposed(padded);
    x = padded.head(cols_.n);
  }

  // B⁻ᵀ E_rows as above, with (W − E_P)ᵀ E_rows read off W's rows (no product); the
  // Schur solve runs on kChunk columns at a time in stack storage.
  void inverse_rows(const std::vector<Index>& rows, Eigen::Ref<DenseMatrix> out) override {
    const Index m = static_cast<Index>(rows.size()), k = static_cast<Index>(pos_.size());
    out.setZero();
    for (Index c = 0; c < m; ++c) out(rows[c], c) = 1.0;
    for (Index c0 = 0; k > 0 && c0 < m; c0 += kChunk) {
      const Index w = std::min(kChunk, m - c0);
      SchurBlock s(k, w);
      for (Index c = 0; c < w; ++c) s.col(c) = W_.row(rows[c0 + c]).head(k).transpose();
      for (Index j = 0; j < k; ++j) s.row(j) -= out.row(pos_[j]).segment(c0, w);
      const SchurBlock t = s_lu_.transpose().solve(s);
      for (Index j = 0; j < k; ++j) out.row(pos_[j]).segment(c0, w) -= t.row(j);
    }
    if (identity_) return;
    if (!cols_.lifted()) {
      klu_.solve_transposed(out);
      return;
    }
    DenseMatrix padded = DenseMatrix::Zero(cols_.factor_size(), m);  // full tie rows: the reference path
    padded.topRows(cols_.n) = out;
    klu_.solve_transposed(padded);
    out = padded.topRows(cols_.n);
  }

  // Row r of B⁻¹ = (B⁻ᵀe_r)ᵀ with B⁻ᵀe_r = B₀⁻ᵀ(e_r − E_P t), t = S⁻ᵀ(W − E_P)ᵀe_r (as in
  // solve_transposed): a right-hand side with at most |P| + 1 nonzeros, solved hypersparsely
  // with B₀'s factors (extracted from KLU at the first row after a refactorization).
  void inverse_row_nonzeros(Index r, std::vector<int>& index, std::vector<double>& value) override {
    const Index k = static_cast<Index>(pos_.size());
    rhs_index_.clear();
    rhs_value_.clear();
    rhs_index_.push_back(static_cast<int>(r));
    rhs_value_.push_back(1.0);
    if (k > 0) {
      SchurVector s(k);
      for (Index j = 0; j < k; ++j) s(j) = W_(r, j) - (pos_[j] == r ? 1.0 : 0.0);
      const SchurVector t = s_lu_.transpose().solve(s);
      for (Index j = 0; j < k; ++j) {
        if (pos_[j] == r) rhs_value_[0] -= t(j);  // distinct indices
        else if (t(j) != 0.0) {
          rhs_index_.push_back(static_cast<int>(pos_[j]));
          rhs_value_.push_back(-t(j));
        }
      }
    }
    if (identity_) {
      index = rhs_index_;
      value = rhs_value_;
      return;
    }
    if (!rows_.built() && !rows_.build(klu_)) return dense_row(r, index, value);
    rows_.solve(static_cast<int>(rhs_index_.size()), rhs_index_.data(), rhs_value_.data(), index, value);
    if (!cols_.lifted()) return;
    std::size_t kept = 0;  // K's momentum columns dropped, in place
    for (std::size_t e = 0; e < index.size(); ++e)
      if (index[e] < cols_.n) {
        index[kept] = index[e];
        value[kept++] = value[e];
      }
    index.resize(kept);
    value.resize(kept);
  }

  bool replace(Index r, const Vector& /*a*/) override {
    Index j = slot_[r];
    const bool slot_reused = j >= 0;
    if (j < 0) {
      if (static_cast<int>(pos_.size()) >= max_updates_) return false;
      j = static_cast<Index>(pos_.size());
      pos_.push_back(r);
      slot_[r] = static_cast<int>(j);
    }
    // W's column j, and the same column by its nonzeros (correct() walks them), in one pass
    // over pending_ (branch-free: every entry is written at the list's end, which advances on
    // a nonzero). A column with more than kDenseColumn·n nonzeros is marked dense: correct()
    // then runs a contiguous axpy over the whole of it and ignores the list.
    const std::size_t js = static_cast<std::size_t>(j);
    double* w = W_.col(j).data();
    const double* v = pending_.data();
    int* wi = w_index_[js].get();
    double* wv = w_value_[js].get();
    Index nonzeros = 0;
    for (Index i = 0; i < cols_.n; ++i) {
      const double x = v[i];
      w[i] = x;
      wi[nonzeros] = static_cast<int>(i);
      wv[nonzeros] = x;
      nonzeros += x != 0.0;
    }
    w_count_[js] = nonzeros;
    w_dense_[js] = static_cast<double>(nonzeros) > kDenseColumn * static_cast<double>(cols_.n);
    const Index k = static_cast<Index>(pos_.size());
    // S = E_Pᵀ W changes in column j (W's new column at the positions P) and, for a new
    // position, in row j (row r of W's earlier columns): O(|P|) entries, not |P|².
    for (Index a = 0; a < k; ++a) S_(a, j) = w[pos_[a]];
    if (!slot_reused)
      for (Index b = 0; b < j; ++b) S_(j, b) = W_(r, b);
    s_lu_.compute(S_.topLeftCorner(k, k));
    const double rcond = s_lu_.rcond();
    needs_check_ = rcond <= kSchurRcondCheck;
    return rcond > kSchurRcondFloor;
  }

  bool update_needs_check() const override { return needs_check_; }

  long memory_bytes() const override {
    const long factor = identity_ ? 0 : klu_.factor_nnz();
    const long w_nonzeros = static_cast<long>(w_index_.size()) * static_cast<long>(cols_.n);
    return static_cast<long>(sizeof(double)) * (factor + W_.size() + w_nonzeros) +
           static_cast<long>(sizeof(int)) * (factor + w_nonzeros);
  }

 private:
  // X ← B₀⁻¹ X.
  void b0_solve(Vector& x) {
    if (identity_) return;
    if (!cols_.lifted()) {
      klu_.solve(x);
      return;
    }
    aug_.head(cols_.n) = x;
    aug_.tail(aug_.size() - cols_.n).setZero();
    klu_.solve(aug_);
    x = aug_.head(cols_.n);
  }

  // Entries of the CSC arrays that any basis' B₀ (or K) fits in.
  Index nonzeros_bound() const {
    return cols_.lifted() ? cols_.lifted_nonzeros_bound() : cols_.M->nonZeros() + 2 * cols_.n;
  }
  Index aug_rows() const { return cols_.factor_size(); }

  // Fallback of inverse_row_nonzeros (factors not extractable): a dense transposed solve.
  void dense_row(Index r, std::vector<int>& index, std::vector<double>& value) {
    Vector e = Vector::Zero(cols_.n);
    e(r) = 1.0;
    solve_transposed(e);
    index.clear();
    value.clear();
    for (Index j = 0; j < cols_.n; ++j)
      if (e(j) != 0.0) {
        index.push_back(static_cast<int>(j));
        value.push_back(e(j));
      }
  }

  // y ← y − (W − E_P) S⁻¹ y_P, turning B₀⁻¹r into B⁻¹r.
  void correct(Vector& y) const {
    const Index k = static_cast<Index>(pos_.size());
    if (k == 0) return;
    SchurVector yp(k);
    for (Index j = 0; j < k; ++j) yp(j) = y(pos_[j]);
    const SchurVector t = s_lu_.solve(yp);
    for (Index j = 0; j < k; ++j) {  // y −= W t over W's nonzeros (W is sparse when B₀⁻¹C is)
      const double tj = t(j);
      if (tj == 0.0) continue;
      if (w_dense_[static_cast<std::size_t>(j)]) {
        y.noalias() -= tj * W_.col(j);
        continue;
      }
      const int* wi = w_index_[static_cast<std::size_t>(j)].get();
      const double* wv = w_value_[static_cast<std::size_t>(j)].get();
      const Index count = w_count_[static_cast<std::size_t>(j)];
      for (Index e = 0; e < count; ++e) y(wi[e]) -= wv[e] * tj;
    }
    for (Index j = 0; j < k; ++j) y(pos_[j]) += t(j);
  }

  LemkeColumns cols_;
  double lu_pivot_tolerance_;  // KLU's partial-pivoting threshold (LemkeSettings)
  sparse::KluLu::Ordering ordering_;  // KLU's column ordering (LemkeSettings::lu_ordering)
  bool sparse_columns_;     // LemkeSettings::sparse_columns
  static constexpr double kHypersparseDensity = 0.1;  // solve_column's switch
  static constexpr double kReusedPivotsRcondRatio = 0.1;  // refactor's klu_refactor test
  double column_density_ = 0.0;  // running mean of nnz(B₀⁻¹c)/n over the solved columns
  int max_updates_;
  LemkeSharedFactorization* shared_;  // or nullptr
  sparse::KluLu own_klu_;   // unused when the factorization is shared
  sparse::KluLu& klu_;      // own_klu_ or the shared one
  bool identity_ = false;   // B₀ = I: klu_ is not used
  std::vector<Index> pos_;  // replaced positions P
  std::vector<int> slot_;   // slot of a position in P, or −1
  DenseMatrix W_;           // B₀⁻¹ C, column j for position pos_[j]
  std::vector<std::unique_ptr<int[]>> w_index_;     // W's column j by its nonzeros: rows (n
  std::vector<std::unique_ptr<double[]>> w_value_;  // slots, the first w_count_[j] used), values
  std::vector<Index> w_count_;                // nonzeros of W's column j
  std::vector<bool> w_dense_;  // column j has more than kDenseColumn·n nonzeros (no lists)
  // Density above which a column of W is applied as a contiguous (vectorized) axpy instead
  // of an indexed walk over its nonzeros: 2–7% less CPU time on dropping LCP piles of 120
  // and 300 bodies, same pivots (bench/results/lemke_dense_correction.txt).
  static constexpr double kDenseColumn = 0.3;
  Eigen::Matrix<double, kCap, kCap> S_;  // S = E_Pᵀ W in its top-left |P|×|P| corner
  Eigen::PartialPivLU<SchurMatrix> s_lu_;
  bool needs_check_ = false;  // the last replace()'s S had rcond ≤ kSchurRcondCheck
  SparseMatrix B0_;         // B₀ (CSC), input of KLU
  Vector pending_;          // B₀⁻¹ c of the last solve_column
  Vector aug_;              // lifted: a solve's (n + m) right-hand side and solution
  sparse::HypersparseTransposedSolver rows_;   // rows of B₀⁻¹ (built on first use)
  std::vector<int> rhs_index_;                 // right-hand side of a row of B⁻¹
  std::vector<double> rhs_value_;
  sparse::HypersparseColumnSolver columns_;    // B₀⁻¹ times a column (built on first use)
  std::vector<int> col_index_, x_index_;       // a tableau column's nonzeros; the solve's
  std::vector<double> col_value_, x_value_;
};

}  // namespace

std::unique_ptr<LemkeBasis> make_sparse_lemke_basis(const LemkeColumns& columns, int refactor_interval,
                                                    bool sparse_columns, LemkeSharedFactorization* shared,
                                                    double lu_pivot_tolerance, LuOrdering lu_ordering) {
  return std::make_unique<SparseLemkeBasis>(columns, refactor_interval, sparse_columns, shared, lu_pivot_tolerance,
                                            lu_ordering);
}

}  // namespace lcprelax::detail
