// The hard loss of one island (step_loss_hard.hpp): the sparse Stewart–Trinkle LCP by
// Lemke, LemkeSolver::backward, and the chain rule to ∂ℓ/∂(Jn, Jt, φ, μ, M⁻¹, v*).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/learn/step_loss_hard.hpp>
#include <lcprelax/models/lcp_model_attempts.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace lcprelax::learn {
namespace {

bool finite(const Vector& v) { return v.allFinite(); }
bool finite(const SparseMatrix& A) {
  for (Index k = 0; k < A.nonZeros(); ++k)
    if (!std::isfinite(A.valuePtr()[k])) return false;
  return true;
}

// [Jn; Jt] as one sparse matrix (rows: contacts, then friction rows).
SparseMatrix stack_rows(const SparseMatrix& Jn, const SparseMatrix& Jt) {
  SparseMatrix J(Jn.rows() + Jt.rows(), Jn.cols());
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(Jn.nonZeros() + Jt.nonZeros()));
  for (Index c = 0; c < Jn.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(Jn, c); it; ++it) t.emplace_back(it.row(), c, it.value());
  for (Index c = 0; c < Jt.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(Jt, c); it; ++it) t.emplace_back(Jn.rows() + it.row(), c, it.value());
  J.setFromTriplets(t.begin(), t.end());
  J.makeCompressed();
  return J;
}

// Copies the rows [first, first + rows) of the values of Jg (J's pattern) into out (the
// pattern of the block it came from, with the same entries).
void split_rows(const SparseMatrix& Jg, Index first, const SparseMatrix& block, SparseMatrix& out) {
  out = block;
  for (Index c = 0; c < out.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(out, c); it; ++it) it.valueRef() = Jg.coeff(first + it.row(), c);
}

}  // namespace

void validate_step_loss_input(const ContactSystem& s, const Vector& target, double dt) {
  const Index nc = s.num_contacts(), nf = s.num_friction(), nd = s.num_dofs();
  auto fail = [](const std::string& m) { throw InputError("step loss: " + m); };
  if (!(dt > 0.0) || !std::isfinite(dt)) fail("dt: must be finite and > 0");
  if (s.minv.size() != nd) fail("minv: size must be 3·bodies");
  if (!finite(s.minv) || (s.minv.array() <= 0.0).any()) fail("minv: must be finite and > 0");
  if (s.Jn.rows() != nc || s.Jn.cols() != nd) fail("Jn: must be contacts × 3·bodies");
  if (s.Jt.rows() != nf || s.Jt.cols() != nd) fail("Jt: must be friction rows × 3·bodies");
  if (!finite(s.Jn)) fail("Jn: non-finite entry");
  if (!finite(s.Jt)) fail("Jt: non-finite entry");
  if (s.phi.size() != nc || !finite(s.phi)) fail("phi: must be finite, one per contact");
  if (s.mu.size() != nf || !finite(s.mu) || (s.mu.array() < 0.0).any())
    fail("mu: must be finite and >= 0, one per friction row");
  for (int r : s.friction_rows)
    if (r < 0 || r >= nc) fail("friction_rows: entry out of range");
  if (s.v_star.size() != nd || !finite(s.v_star)) fail("v_star: must be finite, 3 per body");
  if (const std::string e = normal_softness_error(s); !e.empty()) fail(e);
  if (target.size() != nd || !finite(target)) fail("target: must be finite, 3 per body");
}

std::string HardStepLossSettings::validation_error() const {
  const std::string e = lemke.validation_error();
  return e.empty() ? e : "lemke: " + e;
}

StepLossResult hard_step_loss(const ContactSystem& s, const Vector& target, double dt,
                              const HardStepLossSettings& settings, const std::vector<bool>& warm_basis,
                              std::vector<bool>* final_basis, bool skip_exact_cold, bool warm_from_regularized) {
  if (const std::string e = settings.validation_error(); !e.empty()) throw InputError("HardStepLossSettings: " + e);
  validate_step_loss_input(s, target, dt);
  const Index nc = s.num_contacts(), nf = s.num_friction(), nd = s.num_dofs();
  const Index n = nc + 3 * nf, bp = nc, bm = nc + nf, gm = nc + 2 * nf;
  StepLossResult r;
  r.grad.set_zero(s);
  if (final_basis) final_basis->clear();
  if (n == 0) {  // no contact: v⁺ = v*
    r.status = ContactStatus::solved;
    r.v_next = s.v_star;
    r.loss = (s.v_star - target).squaredNorm();
    r.grad.v_star = 2.0 * (s.v_star - target);
    return r;
  }

  // Solve: the lcp model's attempts (models/lcp_model_attempts.hpp), as the simulator does.
  const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), dt);
  LcpModelAttempts attempts;
  const LcpLiftedForm lifted = stewart_trinkle_lifted_form(s, dt);
  run_lcp_model_attempts(s, lcp, settings.lemke, warm_basis, attempts, skip_exact_cold, {}, false, &lifted,
                         warm_from_regularized);
  r.work = attempts.pivots;
  const LemkeSolver* sol = attempts.used;
  if (!has_solution(attempts.status)) {
    r.status = ContactStatus::failed;
    r.message = attempts.message;
    r.loss = std::numeric_limits<double>::quiet_NaN();
    r.v_next = s.v_star;
    return r;
  }
  r.status = attempts.status;
  r.regularized = attempts.source == LcpModelSource::regularized;
  if (attempts.source != LcpModelSource::exact) r.message = attempts.message;
  const LcpResult& res = sol->result();
  if (final_basis) *final_basis = res.z_basic;
  const Vector ln = res.z.head(nc);
  const Vector lt = res.z.segment(bp, nf) - res.z.segment(bm, nf);
  const Vector jtl = s.Jn.transpose() * ln + s.Jt.transpose() * lt;  // Jᵀλ
  r.v_next = s.v_star + s.minv.cwiseProduct(jtl);
  const Vector g = 2.0 * (r.v_next - target);
  r.loss = 0.25 * g.squaredNorm();

  // Backward through Lemke.
  const Vector a = s.minv.cwiseProduct(g);
  const Vector jna = s.Jn * a, jta = s.Jt * a;
  Vector dz = Vector::Zero(n);
  dz.head(nc) = jna;
  dz.segment(bp, nf) = jta;
  dz.segment(bm, nf) = -jta;
  const LcpGradient lg = sol->backward(dz);

  // G = ∂ℓ/∂W from ∂ℓ/∂M_lcp, and ∂ℓ/∂μ.
  const Index nr = nc + nf;
  auto jrow = [&](Index R, double& sign) -> Index {  // LCP row/column → J row (or −1)
    sign = 1.0;
    if (R < nc) return R;
    if (R < bm) return R;  // β⁺_f → J row nc + f = R
    if (R < gm) {
      sign = -1.0;
      return R - nf;  // β⁻_f → J row nc + f
    }
    return -1;
  };
  std::vector<Triplet> gt;
  gt.reserve(static_cast<std::size_t>(lg.dM.nonZeros()));
  for (Index C = 0; C < lg.dM.outerSize(); ++C)
    for (SparseMatrix::InnerIterator it(lg.dM, C); it; ++it) {
      double sr = 0.0, sc = 0.0;
      const Index rr = jrow(it.row(), sr), cc = jrow(C, sc);
      if (rr >= 0 && cc >= 0) gt.emplace_back(rr, cc, sr * sc * it.value());
    }
  SparseMatrix G(nr, nr);
  G.setFromTriplets(gt.begin(), gt.end());
  for (Index f = 0; f < nf; ++f) r.grad.mu(f) = lg.dM.coeff(gm + f, s.friction_rows[static_cast<std::size_t>(f)]);
  if (s.lcp_block.enabled) {  // ∂ℓ/∂(B, d) of World::lcp_block: the sum over the contacts' blocks
    const std::vector<Index> block_index = stewart_trinkle_contact_indices(s);
    for (Index c = 0; c < nc; ++c) {
      const Index* idx = &block_index[static_cast<std::size_t>(4 * c)];
      for (int k = 0; k < 4; ++k) {
        if (idx[k] < 0) continue;
        r.grad.lcp_block_q(k) += lg.dq(idx[k]);
        for (int l = 0; l < 4; ++l)
          if (idx[l] >= 0) r.grad.lcp_block_M(k, l) += lg.dM.coeff(idx[k], idx[l]);
      }
    }
  }
  const Vector dqn = lg.dq.head(nc);
  const Vector dqt = lg.dq.segment(bp, nf) - lg.dq.segment(bm, nf);

  // ∂ℓ/∂J on J's pattern, ∂ℓ/∂M⁻¹.
  const SparseMatrix J = stack_rows(s.Jn, s.Jt);
  const SparseMatrix GJ = G * J;
  const SparseMatrix GtJ = SparseMatrix(G.transpose()) * J;
  Vector dq_all(nr), lam(nr);
  dq_all << dqn, dqt;
  lam << ln, lt;
  SparseMatrix dJ = J;
  for (Index k = 0; k < nd; ++k)
    for (SparseMatrix::InnerIterator it(dJ, k); it; ++it) {
      const Index i = it.row();
      const double gj = GJ.coeff(i, k);
      it.valueRef() = (gj + GtJ.coeff(i, k)) * s.minv(k) + dq_all(i) * s.v_star(k) + lam(i) * a(k);
      r.grad.minv(k) += J.coeff(i, k) * gj;  // (Jᵀ G J)_kk = Σ_i J_ik (GJ)_ik
    }
  r.grad.minv += g.cwiseProduct(jtl);
  split_rows(dJ, 0, s.Jn, r.grad.Jn);
  split_rows(dJ, nc, s.Jt, r.grad.Jt);
  r.grad.v_star = g + s.Jn.transpose() * dqn + s.Jt.transpose() * dqt;
  // q_n = Jn v* + (max(φ, 0) + e·min(φ, 0))/Δt and M_nn = W_nn + diag(c) (contact_system.hpp).
  for (Index c = 0; c < nc; ++c) {
    const double e = s.erp.size() > 0 ? s.erp(c) : 0.0;
    r.grad.phi(c) = s.phi(c) > 0.0 ? dqn(c) / dt : e * dqn(c) / dt;
    r.grad.erp(c) = dqn(c) * std::min(s.phi(c), 0.0) / dt;
    r.grad.compliance(c) = lg.dM.coeff(c, c);
  }
  return r;
}

}  // namespace lcprelax::learn
