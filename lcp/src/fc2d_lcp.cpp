// fc2d ↔ LCP mapping (formulation in fc2d_lcp.hpp).
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/core/errors.hpp>

#include <vector>

namespace lcprelax {

Fc2dLcp fc2d_to_lcp(const SparseMatrix& W, const Vector& q, const Vector& mu) {
  const Index nc = static_cast<Index>(mu.size());
  if (W.rows() != 2 * nc || W.cols() != 2 * nc || q.size() != 2 * nc)
    throw InputError("fc2d: W must be 2nc×2nc and q of size 2nc for nc = " + std::to_string(nc) + " contacts");
  std::vector<Triplet> t;
  t.reserve(4 * W.nonZeros() + 6 * nc);
  // W entry (a, b): row kind of a (n or t) in contact a/2, column kind of b in contact b/2.
  // Column b = normal → LCP column 4c'+0 with sign +1; tangent → columns β⁺ (+1), β⁻ (−1).
  // Row a = normal → LCP row 4c+0 (+1); tangent → rows w⁺ (+1), w⁻ (−1).
  for (Index b = 0; b < W.outerSize(); ++b)
    for (SparseMatrix::InnerIterator it(W, b); it; ++it) {
      const Index a = it.row(), ca = a / 2, cb = b / 2;
      const bool row_t = a % 2, col_t = b % 2;
      for (int rs = 0; rs < (row_t ? 2 : 1); ++rs)
        for (int cs = 0; cs < (col_t ? 2 : 1); ++cs) {
          const double sign = (rs ? -1.0 : 1.0) * (cs ? -1.0 : 1.0);
          t.emplace_back(4 * ca + (row_t ? 1 + rs : 0), 4 * cb + (col_t ? 1 + cs : 0), sign * it.value());
        }
    }
  Fc2dLcp out;
  out.q = Vector::Zero(4 * nc);
  for (Index c = 0; c < nc; ++c) {
    t.emplace_back(4 * c + 1, 4 * c + 3, 1.0);   // w⁺ += λ
    t.emplace_back(4 * c + 2, 4 * c + 3, 1.0);   // w⁻ += λ
    t.emplace_back(4 * c + 3, 4 * c + 0, mu(c));  // w_λ = μ r_n − β⁺ − β⁻
    t.emplace_back(4 * c + 3, 4 * c + 1, -1.0);
    t.emplace_back(4 * c + 3, 4 * c + 2, -1.0);
    out.q(4 * c) = q(2 * c);
    out.q(4 * c + 1) = q(2 * c + 1);
    out.q(4 * c + 2) = -q(2 * c + 1);
  }
  out.M.resize(4 * nc, 4 * nc);
  out.M.setFromTriplets(t.begin(), t.end());
  out.M.makeCompressed();
  return out;
}

void fc2d_from_lcp(const Vector& z, const SparseMatrix& W, const Vector& q, Vector& r, Vector& u) {
  const Index nc = static_cast<Index>(q.size() / 2);
  if (z.size() != 4 * nc) throw InputError("fc2d: LCP solution has the wrong size");
  r.resize(2 * nc);
  for (Index c = 0; c < nc; ++c) {
    r(2 * c) = z(4 * c);
    r(2 * c + 1) = z(4 * c + 1) - z(4 * c + 2);
  }
  u = W * r + q;
}

}  // namespace lcprelax
