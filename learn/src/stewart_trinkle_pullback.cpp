// The Stewart–Trinkle prediction map and the chain rule from ∂ℓ/∂(M_lcp, q, P, p) to the
// island's data (stewart_trinkle_pullback.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/stewart_trinkle_pullback.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace lcprelax::learn {
namespace {

// ∂ℓ/∂X on the pattern of `pattern` (rows offset by `first` in X), read from X by lookup.
void on_pattern(const SparseMatrix& X, Index first, const SparseMatrix& pattern, const Vector& d, const Vector& v_star,
                const Vector& dq_rows, SparseMatrix& out) {
  out = pattern;
  for (Index k = 0; k < out.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(out, k); it; ++it) {
      const Index i = first + it.row();
      it.valueRef() = X.coeff(i, k) * d(k) + dq_rows(i) * v_star(k);
    }
}

}  // namespace

StewartTrinklePrediction stewart_trinkle_prediction(const ContactSystem& s) {
  const Index nc = s.num_contacts(), nf = s.num_friction(), nd = s.num_dofs();
  const Index n = nc + 3 * nf;
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(s.Jn.nonZeros() + 2 * s.Jt.nonZeros()));
  for (Index k = 0; k < s.Jn.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(s.Jn, k); it; ++it) t.emplace_back(k, it.row(), s.minv(k) * it.value());
  for (Index k = 0; k < s.Jt.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(s.Jt, k); it; ++it) {
      t.emplace_back(k, nc + it.row(), s.minv(k) * it.value());
      t.emplace_back(k, nc + nf + it.row(), -s.minv(k) * it.value());
    }
  StewartTrinklePrediction out;
  out.P.resize(nd, n);
  out.P.setFromTriplets(t.begin(), t.end());
  out.P.makeCompressed();
  out.p = s.v_star;
  return out;
}

ContactSystemCotangent stewart_trinkle_pullback(const ContactSystem& s, double dt, const SparseMatrix& dM,
                                                const Vector& dq, const SparseMatrix& dP, const Vector& dp) {
  const Index nc = s.num_contacts(), nf = s.num_friction(), nd = s.num_dofs();
  const Index n = nc + 3 * nf, nr = nc + nf, bm = nc + nf, gm = nc + 2 * nf;
  auto fail = [](const std::string& m) { throw InputError("stewart_trinkle_pullback: " + m); };
  if (!(dt > 0.0) || !std::isfinite(dt)) fail("dt: must be finite and > 0");
  if (dM.rows() != n || dM.cols() != n) fail("dM: must be (nc + 3nf) square");
  if (dq.size() != n) fail("dq: must have nc + 3nf entries");
  if (dP.rows() != nd || dP.cols() != n) fail("dP: must be 3·bodies × (nc + 3nf)");
  if (dp.size() != nd) fail("dp: must have 3·bodies entries");

  ContactSystemCotangent ct;
  ct.mu = Vector::Zero(nf);
  // LCP row/column → J row (β⁻ with sign −1), or −1 for γ.
  auto jrow = [&](Index R, double& sign) -> Index {
    sign = 1.0;
    if (R < bm) return R;  // λn_c → c, β⁺_f → nc + f
    if (R < gm) {
      sign = -1.0;
      return R - nf;
    }
    return -1;
  };
  std::vector<Triplet> gt;
  gt.reserve(static_cast<std::size_t>(2 * dM.nonZeros()));
  for (Index C = 0; C < dM.outerSize(); ++C)
    for (SparseMatrix::InnerIterator it(dM, C); it; ++it) {
      const Index R = it.row();
      if (R >= gm) {  // μ enters at (γ_f, λn_c(f)) only
        const Index f = R - gm;
        if (C == s.friction_rows[static_cast<std::size_t>(f)]) ct.mu(f) += it.value();
        continue;
      }
      double sr = 0.0, sc = 0.0;
      const Index rr = jrow(R, sr), cc = jrow(C, sc);
      if (rr < 0 || cc < 0) continue;
      // G + Gᵀ directly: both (r, c) and (c, r) receive the entry.
      gt.emplace_back(rr, cc, sr * sc * it.value());
      gt.emplace_back(cc, rr, sr * sc * it.value());
    }
  SparseMatrix Gs(nr, nr);  // G + Gᵀ
  Gs.setFromTriplets(gt.begin(), gt.end());
  // Q (J-space, nr × nd) from dP's λn and β± columns.
  std::vector<Triplet> qt;
  qt.reserve(static_cast<std::size_t>(dP.nonZeros()));
  for (Index C = 0; C < dP.outerSize(); ++C) {
    double sign = 0.0;
    const Index r = jrow(C, sign);
    if (r < 0) continue;
    for (SparseMatrix::InnerIterator it(dP, C); it; ++it) qt.emplace_back(r, it.row(), sign * it.value());
  }
  SparseMatrix Q(nr, nd);
  Q.setFromTriplets(qt.begin(), qt.end());

  SparseMatrix J(nr, nd);
  {
    std::vector<Triplet> t;
    t.reserve(static_cast<std::size_t>(s.Jn.nonZeros() + s.Jt.nonZeros()));
    for (Index k = 0; k < s.Jn.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(s.Jn, k); it; ++it) t.emplace_back(it.row(), k, it.value());
    for (Index k = 0; k < s.Jt.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(s.Jt, k); it; ++it) t.emplace_back(nc + it.row(), k, it.value());
    J.setFromTriplets(t.begin(), t.end());
  }
  // A = (G + Gᵀ) J + Q: then ∂ℓ/∂J_ik = A_ik D_k + dq_i v*_k.
  const SparseMatrix GsJ = Gs * J;
  const SparseMatrix A = GsJ + Q;
  Vector dq_rows(nr);
  dq_rows.head(nc) = dq.head(nc);
  dq_rows.tail(nf) = dq.segment(nc, nf) - dq.segment(bm, nf);
  on_pattern(A, 0, s.Jn, s.minv, s.v_star, dq_rows, ct.Jn);
  on_pattern(A, nc, s.Jt, s.minv, s.v_star, dq_rows, ct.Jt);
  // ∂ℓ/∂D_k = (Jᵀ G J)_kk + Σ_i Q_ik J_ik = Σ_i J_ik (½ GsJ + Q)_ik.
  ct.minv = Vector::Zero(nd);
  for (Index k = 0; k < J.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(J, k); it; ++it)
      ct.minv(k) += it.value() * (0.5 * GsJ.coeff(it.row(), k) + Q.coeff(it.row(), k));
  ct.v_star = dp + s.Jn.transpose() * dq_rows.head(nc) + s.Jt.transpose() * dq_rows.tail(nf);
  // q_n = Jn v* + (max(φ, 0) + e·min(φ, 0))/Δt and M_nn = W_nn + diag(c) (contact_system.hpp).
  ct.phi = Vector::Zero(nc);
  ct.compliance = Vector::Zero(nc);
  ct.erp = Vector::Zero(nc);
  for (Index c = 0; c < nc; ++c) {
    const double e = s.erp.size() > 0 ? s.erp(c) : 0.0;
    ct.phi(c) = s.phi(c) > 0.0 ? dq(c) / dt : e * dq(c) / dt;
    ct.erp(c) = dq(c) * std::min(s.phi(c), 0.0) / dt;
    ct.compliance(c) = dM.coeff(c, c);
  }
  return ct;
}

}  // namespace lcprelax::learn
