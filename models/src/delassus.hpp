#pragma once
// Internal (models/src): W = J M⁻¹ Jᵀ for J = [A; B] stacked by rows (delassus.cpp), the
// kernel of delassus() and of the post-stabilization's normal block Jn M⁻¹ Jnᵀ.
#include <lcprelax/sparse/types.hpp>

namespace lcprelax::detail {

/// A: rows 0..a−1 of J, B: rows a.. (either may have no rows), both with minv.size()
/// columns; minv the diagonal of M⁻¹. drop_zeros: entries that sum to exactly zero are
/// not stored (Eigen's pruned()); else every entry of the product's pattern is. Compressed
/// CSC with sorted rows. Throws InputError when the column counts differ from minv's size.
SparseMatrix stacked_delassus(const SparseMatrix& A, const SparseMatrix& B, const Vector& minv, bool drop_zeros);

}  // namespace lcprelax::detail
