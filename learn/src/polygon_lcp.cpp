// The dense Stewart–Trinkle LCP of one polygon (polygon_lcp.hpp).
#include <lcprelax/learn/polygon_lcp.hpp>

namespace lcprelax::learn {
namespace {

// Fills M, q, P, p from W (and its pieces) given J-space data.
void fill(Index nc, const DenseMatrix& W, const Vector& mu, const Vector& qn, const Vector& qt, const DenseMatrix& Pn,
          const DenseMatrix& Pt, const Vector& p, PolygonLcp& out) {
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
  const DenseMatrix I = DenseMatrix::Identity(nc, nc);
  out.M.block(nc, 3 * nc, nc, nc) = I;
  out.M.block(2 * nc, 3 * nc, nc, nc) = I;
  out.M.block(3 * nc, nc, nc, nc) = -I;
  out.M.block(3 * nc, 2 * nc, nc, nc) = -I;
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

void PolygonContactData::set_zero(Index nc) {
  Jn.setZero(nc, 3);
  Jt.setZero(nc, 3);
  phi.setZero(nc);
  mu.setZero(nc);
  minv.setZero(3);
  v_star.setZero(3);
}

void polygon_lcp(const PolygonContactData& d, double dt, PolygonLcp& out) {
  const Index nc = d.num_contacts();
  const DenseMatrix J = stack(d.Jn, d.Jt);
  const DenseMatrix W = J * d.minv.asDiagonal() * J.transpose();
  const Vector qn = d.Jn * d.v_star + d.phi.cwiseMax(0.0) / dt;
  fill(nc, W, d.mu, qn, d.Jt * d.v_star, d.minv.asDiagonal() * d.Jn.transpose(),
       d.minv.asDiagonal() * d.Jt.transpose(), d.v_star, out);
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

}  // namespace lcprelax::learn
