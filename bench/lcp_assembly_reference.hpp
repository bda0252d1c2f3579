#pragma once
// Straightforward reference assemblies of the lcp model's matrices (Eigen's sparse product,
// one triplet per entry) for the structured kernels of models/src/delassus.cpp and
// models/src/lcp_model.cpp: the tests check that the kernels give the same matrices bit for
// bit, bench_lcp_assembly times both.
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>

#include <vector>

namespace lcprelax::reference {

/// W = ((J·M⁻¹)·Jᵀ).pruned() by Eigen's sparse product (delassus() reproduces it term by term).
inline SparseMatrix eigen_delassus(const ContactSystem& s) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  std::vector<Triplet> t;
  for (Index j = 0; j < s.Jn.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(s.Jn, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  for (Index j = 0; j < s.Jt.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(s.Jt, j); it; ++it) t.emplace_back(nc + it.row(), j, it.value());
  SparseMatrix J(nc + nf, s.num_dofs());
  J.setFromTriplets(t.begin(), t.end());
  const SparseMatrix JMinv = J * s.minv.asDiagonal();
  SparseMatrix W = (JMinv * J.transpose()).pruned();
  W.makeCompressed();
  return W;
}

/// stewart_trinkle_lcp()'s M by one triplet per entry, duplicates summed in insertion order.
inline SparseMatrix triplet_stewart_trinkle_matrix(const ContactSystem& s, const SparseMatrix& W) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  const Index bp = nc, bm = nc + nf, g = nc + 2 * nf;
  std::vector<Triplet> t;
  auto expand = [&](Index r, auto&& emit) {
    if (r < nc) {
      emit(r, 1.0);
    } else {
      emit(bp + (r - nc), 1.0);
      emit(bm + (r - nc), -1.0);
    }
  };
  for (Index c = 0; c < W.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(W, c); it; ++it)
      expand(it.row(), [&](Index R, double sr) {
        expand(c, [&](Index C, double sc) { t.emplace_back(R, C, sr * sc * it.value()); });
      });
  for (Index c = 0; c < s.compliance.size(); ++c)
    if (s.compliance(c) != 0.0) t.emplace_back(c, c, s.compliance(c));
  for (Index f = 0; f < nf; ++f) {
    t.emplace_back(bp + f, g + f, 1.0);
    t.emplace_back(bm + f, g + f, 1.0);
    t.emplace_back(g + f, s.friction_rows[f], s.mu(f));
    t.emplace_back(g + f, bp + f, -1.0);
    t.emplace_back(g + f, bm + f, -1.0);
  }
  if (s.lcp_block.enabled) {
    const std::vector<Index> block_index = stewart_trinkle_contact_indices(s);
    for (Index c = 0; c < nc; ++c) {
      const Index* idx = &block_index[static_cast<std::size_t>(4 * c)];
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l)
          if (idx[k] >= 0 && idx[l] >= 0) t.emplace_back(idx[k], idx[l], s.lcp_block.M(k, l));
    }
  }
  SparseMatrix M(nc + 3 * nf, nc + 3 * nf);
  M.setFromTriplets(t.begin(), t.end());
  M.makeCompressed();
  return M;
}

}  // namespace lcprelax::reference
