// The Stewart–Trinkle LCP contact model (contact_step.hpp).
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_step.hpp>

#include <algorithm>

namespace lcprelax {

StewartTrinkleLcp stewart_trinkle_lcp(const ContactSystem& s, const SparseMatrix& W, double dt) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  const Index bp = nc, bm = nc + nf, g = nc + 2 * nf;  // offsets of β⁺, β⁻, γ
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(4 * W.nonZeros() + 6 * nf));
  // W row/column r of J-space maps to LCP rows: normal r → (r, +); friction f → (β⁺_f, +), (β⁻_f, −).
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
  for (Index f = 0; f < nf; ++f) {
    t.emplace_back(bp + f, g + f, 1.0);
    t.emplace_back(bm + f, g + f, 1.0);
    t.emplace_back(g + f, s.friction_rows[f], s.mu(f));
    t.emplace_back(g + f, bp + f, -1.0);
    t.emplace_back(g + f, bm + f, -1.0);
  }
  StewartTrinkleLcp lcp;
  lcp.M.resize(nc + 3 * nf, nc + 3 * nf);
  lcp.M.setFromTriplets(t.begin(), t.end());
  lcp.M.makeCompressed();
  lcp.q = Vector::Zero(nc + 3 * nf);
  lcp.q.head(nc) = s.Jn * s.v_star + s.phi.cwiseMax(0.0) / dt;
  const Vector jt = s.Jt * s.v_star;
  lcp.q.segment(bp, nf) = jt;
  lcp.q.segment(bm, nf) = -jt;
  return lcp;
}

ContactSolution solve_lcp_model(const ContactSystem& s, double dt, const LemkeSettings& settings,
                                const std::vector<bool>& warm) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), dt);
  // Degenerate piles (redundant and wedged contacts) rely on Lemke's retries
  // (LemkeSettings::covering_retries, regularization_retries).
  LemkeSolver solver(settings);
  solver.setup(lcp.M, lcp.q);
  if (static_cast<Index>(warm.size()) == lcp.q.size()) solver.warm_start(warm);
  const LcpResult& r = solver.solve();
  const long pivots = r.info.pivots;
  ContactSolution out;
  out.ok = r.info.status == LcpStatus::solved;
  out.message = r.info.message;
  out.work = pivots;
  out.residual = r.info.complementarity;
  out.z_basic = r.z_basic;
  out.warm_started = r.info.warm_started;
  if (!out.ok) return out;
  out.lambda_n = r.z.head(nc);
  out.lambda_t = r.z.segment(nc, nf) - r.z.segment(nc + nf, nf);
  const Vector impulse = s.Jn.transpose() * out.lambda_n + s.Jt.transpose() * out.lambda_t;
  out.v_next = s.v_star + s.minv.cwiseProduct(impulse);
  return out;
}

}  // namespace lcprelax
