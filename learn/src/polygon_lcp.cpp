// The Stewart–Trinkle LCP of a polygon sample and its tangent (polygon_lcp.hpp).
#include <lcprelax/learn/polygon_lcp.hpp>

namespace lcprelax::learn {
namespace {

// Fills M, q, P, p from W (and its pieces) given J-space data; shared by value and tangent:
// the map (W, μ, q-blocks, P-blocks) → (M, q, P, p) is linear except for the constant
// identity blocks, which `with_identity` switches off for the tangent.
void fill(Index nc, const DenseMatrix& W, const Vector& mu, const Vector& qn, const Vector& qt, const DenseMatrix& Pn,
          const DenseMatrix& Pt, const Vector& p, bool with_identity, PolygonLcp& out) {
  const Index n = 4 * nc;
  out.M.setZero(n, n);
  const DenseMatrix Wnn = W.topLeftCorner(nc, nc), Wnt = W.topRightCorner(nc, nc);
  const DenseMatrix Wtn = W.bottomLeftCorner(nc, nc), Wtt = W.bottomRightCorner(nc, nc);
  out.M.block(0, 0, nc, nc) = Wnn;
  out.M.block(0, nc, nc, nc) = Wnt;
  out.M.block(0, 2 * nc, nc, nc) = -Wnt;
  out.M.block(nc, 0, nc, nc) = Wtn;
  out.M.block(nc, nc, nc, nc) = Wtt;
  out.M.block(nc, 2 * nc, nc, nc) = -Wtt;
  out.M.block(2 * nc, 0, nc, nc) = -Wtn;
  out.M.block(2 * nc, nc, nc, nc) = -Wtt;
  out.M.block(2 * nc, 2 * nc, nc, nc) = Wtt;
  out.M.block(3 * nc, 0, nc, nc) = mu.asDiagonal();
  if (with_identity) {
    const DenseMatrix I = DenseMatrix::Identity(nc, nc);
    out.M.block(nc, 3 * nc, nc, nc) = I;
    out.M.block(2 * nc, 3 * nc, nc, nc) = I;
    out.M.block(3 * nc, nc, nc, nc) = -I;
    out.M.block(3 * nc, 2 * nc, nc, nc) = -I;
  }
  out.q.setZero(n);
  out.q.head(nc) = qn;
  out.q.segment(nc, nc) = qt;
  out.q.segment(2 * nc, nc) = -qt;
  out.P.setZero(3, n);
  out.P.leftCols(nc) = Pn;
  out.P.middleCols(nc, nc) = Pt;
  out.P.middleCols(2 * nc, nc) = -Pt;
  out.p = p;
}

DenseMatrix stack(const DenseMatrix& Jn, const DenseMatrix& Jt) {
  DenseMatrix J(Jn.rows() + Jt.rows(), 3);
  J << Jn, Jt;
  return J;
}

}  // namespace

void polygon_lcp(const PolygonContactData& d, double dt, PolygonLcp& out) {
  const Index nc = d.num_contacts();
  const DenseMatrix J = stack(d.Jn, d.Jt);
  const DenseMatrix W = J * d.minv.asDiagonal() * J.transpose();
  const Vector qn = d.Jn * d.v_star + d.phi.cwiseMax(0.0) / dt;
  fill(nc, W, d.mu, qn, d.Jt * d.v_star, d.minv.asDiagonal() * d.Jn.transpose(),
       d.minv.asDiagonal() * d.Jt.transpose(), d.v_star, true, out);
}

void polygon_lcp_tangent(const PolygonContactData& d, const PolygonContactData& dd, double dt, PolygonLcp& out) {
  const Index nc = d.num_contacts();
  const DenseMatrix J = stack(d.Jn, d.Jt), dJ = stack(dd.Jn, dd.Jt);
  const DenseMatrix JD = J * d.minv.asDiagonal();
  const DenseMatrix dW = dJ * d.minv.asDiagonal() * J.transpose() + J * dd.minv.asDiagonal() * J.transpose() +
                         JD * dJ.transpose();
  Vector dgap(nc);
  for (Index k = 0; k < nc; ++k) dgap(k) = d.phi(k) > 0 ? dd.phi(k) / dt : 0.0;
  const Vector dqn = dd.Jn * d.v_star + d.Jn * dd.v_star + dgap;
  const Vector dqt = dd.Jt * d.v_star + d.Jt * dd.v_star;
  const DenseMatrix dPn = dd.minv.asDiagonal() * d.Jn.transpose() + d.minv.asDiagonal() * dd.Jn.transpose();
  const DenseMatrix dPt = dd.minv.asDiagonal() * d.Jt.transpose() + d.minv.asDiagonal() * dd.Jt.transpose();
  fill(nc, dW, dd.mu, dqn, dqt, dPn, dPt, dd.v_star, false, out);
}

SparseMatrix full_pattern(const DenseMatrix& A) {
  SparseMatrix S(static_cast<Index>(A.rows()), static_cast<Index>(A.cols()));
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(A.size()));
  for (Index j = 0; j < A.cols(); ++j)
    for (Index i = 0; i < A.rows(); ++i) t.emplace_back(i, j, A(i, j));
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  return S;
}

double pattern_inner(const SparseMatrix& G, const DenseMatrix& T) {
  double sum = 0.0;
  for (Index j = 0; j < G.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(G, j); it; ++it) sum += it.value() * T(it.row(), j);
  return sum;
}

}  // namespace lcprelax::learn
