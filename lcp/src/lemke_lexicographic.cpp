// The lexicographic tie-break on rows of B⁻¹, full rows or nonzeros only
// (lemke_lexicographic.hpp).
#include "lemke_lexicographic.hpp"

#include <algorithm>

namespace lcprelax::detail {

void LexicographicTie::reserve(Index n, Index dense_cols) {
  n_ = n;
  slot_.assign(static_cast<std::size_t>(n), 0);
  inv_rows_.resize(n, sparse_rows ? 0 : dense_cols);
  entries_.clear();
  entries_.reserve(static_cast<std::size_t>(4 * n));
  index_.reserve(static_cast<std::size_t>(n));
  value_.reserve(static_cast<std::size_t>(n));
  column_.reserve(static_cast<std::size_t>(std::min<Index>(n, 64)));
  ratios.reserve(static_cast<std::size_t>(n));
}

bool LexicographicTie::reduce(std::vector<Index>& rows, std::vector<Index>& keep, const Vector& den, double tol,
                              LemkeBasis& basis) {
  columns_visited_ = 0;
  if (rows.size() < 2) return true;
  for (std::size_t k = 0; k < rows.size(); ++k) slot_[static_cast<std::size_t>(rows[k])] = static_cast<Index>(k);
  return sparse_rows ? reduce_sparse(rows, keep, den, tol, basis) : reduce_full(rows, keep, den, tol, basis);
}

bool LexicographicTie::reduce_full(std::vector<Index>& rows, std::vector<Index>& keep, const Vector& den, double tol,
                                   LemkeBasis& basis) {
  const Index m = static_cast<Index>(rows.size());
  if (inv_rows_.cols() < m) inv_rows_.resize(n_, std::max<Index>(m, std::min<Index>(n_, 2 * inv_rows_.cols())));
  auto inv = inv_rows_.leftCols(m);  // column k: row rows[k] of B⁻¹
  basis.inverse_rows(rows, inv);
  for (Index col = 0; col < n_ && rows.size() > 1; ++col) {
    ++columns_visited_;
    if (!keep_minimal_ratio(rows, keep, ratios, den, tol, 1.0, [&](Index i) { return inv(col, slot_[i]); })) return false;
  }
  return true;
}

// The nonzeros of all tied rows, sorted by column; a column where no tied row has a
// nonzero would keep every row (θ = 0), so only the columns present are visited.
bool LexicographicTie::reduce_sparse(std::vector<Index>& rows, std::vector<Index>& keep, const Vector& den,
                                     double tol, LemkeBasis& basis) {
  const Index m = static_cast<Index>(rows.size());
  entries_.clear();
  for (Index k = 0; k < m; ++k) {
    basis.inverse_row_nonzeros(rows[static_cast<std::size_t>(k)], index_, value_);
    for (std::size_t p = 0; p < index_.size(); ++p)
      if (value_[p] != 0.0) entries_.push_back({index_[p], static_cast<int>(k), value_[p]});
  }
  std::sort(entries_.begin(), entries_.end(), [](const Entry& x, const Entry& y) { return x.col < y.col; });
  column_.assign(static_cast<std::size_t>(m), 0.0);
  const std::size_t total = entries_.size();
  for (std::size_t p = 0; p < total && rows.size() > 1;) {
    const int col = entries_[p].col;
    std::size_t e = p;
    for (; e < total && entries_[e].col == col; ++e) column_[static_cast<std::size_t>(entries_[e].slot)] = entries_[e].value;
    ++columns_visited_;
    const bool finite = keep_minimal_ratio(rows, keep, ratios, den, tol, 1.0,
                                           [&](Index i) { return column_[static_cast<std::size_t>(slot_[i])]; });
    for (std::size_t q = p; q < e; ++q) column_[static_cast<std::size_t>(entries_[q].slot)] = 0.0;
    if (!finite) return false;
    p = e;
  }
  return true;
}

}  // namespace lcprelax::detail
