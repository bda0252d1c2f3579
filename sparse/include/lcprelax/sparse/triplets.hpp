#pragma once
// Small helpers for assembling sparse matrices from triplets (block by block), shared by
// the QP assemblies of the contact models and the learning losses.
#include <lcprelax/sparse/types.hpp>

#include <vector>

namespace lcprelax {

/// The compressed rows × cols matrix of the triplets (duplicates summed).
inline SparseMatrix from_triplets(Index rows, Index cols, const std::vector<Triplet>& t) {
  SparseMatrix A(rows, cols);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

/// Appends the entries of A at (row_offset + i, col_offset + j), each times `scale`;
/// `transpose` appends Aᵀ instead.
inline void append_triplets(std::vector<Triplet>& t, const SparseMatrix& A, Index row_offset, Index col_offset,
                            double scale, bool transpose = false) {
  for (Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const Index r = transpose ? j : it.row(), c = transpose ? it.row() : j;
      t.emplace_back(row_offset + r, col_offset + c, scale * it.value());
    }
}

/// The upper triangle of A, compressed (the QP's P convention).
inline SparseMatrix upper_triangle(const SparseMatrix& A) {
  SparseMatrix U = A.triangularView<Eigen::Upper>();
  U.makeCompressed();
  return U;
}

}  // namespace lcprelax
