#pragma once
// Internal: the lexicographic tie-break of Lemke's minimum-ratio test on rows of B⁻¹.
//
// Rows i still tied after the x_B column are compared on the columns of B⁻¹ in order,
// key B⁻¹(i, col)/den_i: at each column the rows whose key exceeds the column minimum θ by
// more than tol·(1 + |θ|) drop out (absolute tolerance: lemke_pivot.cpp says why), until
// one row is left or the columns are exhausted (then the first remaining row wins).
//
// Two ways of forming the rows, same decisions (up to the roundoff of the solves):
// - full rows (`sparse_rows = false`): one transposed solve per tied row, n entries each,
//   and the walk visits every column until the tie breaks. Degenerate contact LCPs tie
//   ~20 rows that agree (all zero) on the first thousands of columns (granular fc2d, 2,020
//   contacts: ties broken after ~2,700 of 6,060 columns), so this costs O(m·nnz(LU) + m·n)
//   per tie.
// - sparse rows (default): each row of B⁻¹ is formed with its nonzeros only
//   (LemkeBasis::inverse_row_nonzeros: a hypersparse transposed solve on the sparse basis,
//   sparse/hypersparse_solve.hpp), the entries of all tied rows are sorted by column, and
//   the walk visits only columns where some tied row has a nonzero. A column where every
//   remaining row is zero has θ = 0 and keeps every row, so skipping it changes nothing:
//   the decisions are those of the full-row walk. This is the standard use of sparsity in
//   the lexicographic ratio test; rows of the inverse by sparse triangular solves are the
//   "hypersparse" BTRAN of simplex codes (Hall & McKinnon, "Hyper-sparsity in the revised
//   simplex method and how to exploit it", Comput. Optim. Appl. 32, 2005).
//
// Storage: work arrays sized by reserve(); they grow only when a tie is larger than any
// before on this object.
#include "lemke_basis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace lcprelax::detail {

/// One step of the lexicographic test: θ = min over `rows` of value(i)/den(i); keeps the
/// rows with value(i)/den(i) ≤ θ + tol·(|θ| + absolute). False (rows unchanged) when a
/// ratio is not finite. `ratio` is scratch (each ratio is divided out once; capacity n
/// avoids allocation).
template <class Value>
bool keep_minimal_ratio(std::vector<Index>& rows, std::vector<Index>& keep, std::vector<double>& ratio,
                        const Vector& den, double tol, double absolute, Value value) {
  double best = std::numeric_limits<double>::infinity();
  ratio.resize(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double r = value(rows[k]) / den(rows[k]);
    if (!std::isfinite(r)) return false;
    ratio[k] = r;
    best = std::min(best, r);
  }
  const double t = tol * (std::abs(best) + absolute);
  keep.clear();
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (ratio[k] <= best + t) keep.push_back(rows[k]);
  rows.swap(keep);
  return true;
}

class LexicographicTie {
 public:
  /// Full rows (false) or nonzeros only (true); see above.
  bool sparse_rows = true;
  /// Scratch of keep_minimal_ratio (capacity n after reserve()).
  std::vector<double> ratios;

  /// Sizes the work arrays for n and up to `dense_cols` full rows at once.
  void reserve(Index n, Index dense_cols);

  /// rows: the candidate rows tied on x_B (at least two); den: the ratio denominators.
  /// Reduces `rows` to the lexicographic minimum (rows.front() is the winner); `keep` is
  /// scratch. Returns false when a key is not finite (the basis has lost all accuracy).
  bool reduce(std::vector<Index>& rows, std::vector<Index>& keep, const Vector& den, double tol,
              LemkeBasis& basis);

  /// Columns of B⁻¹ visited by the last reduce() (instrumentation).
  Index columns_visited() const { return columns_visited_; }

 private:
  bool reduce_full(std::vector<Index>& rows, std::vector<Index>& keep, const Vector& den, double tol,
                   LemkeBasis& basis);
  bool reduce_sparse(std::vector<Index>& rows, std::vector<Index>& keep, const Vector& den, double tol,
                     LemkeBasis& basis);

  struct Entry {
    int col;
    int slot;  // index of the row in the tied set
    double value;
  };
  Index n_ = 0;
  std::vector<Index> slot_;    // row → index in the tied set
  DenseMatrix inv_rows_;       // full rows: column k = row rows[k] of B⁻¹
  std::vector<Entry> entries_;  // sparse rows: all nonzeros of the tied rows
  std::vector<int> index_;     // one sparse row
  std::vector<double> value_;
  std::vector<double> column_;  // values of the tied rows in the current column (by slot)
  Index columns_visited_ = 0;
};

}  // namespace lcprelax::detail
