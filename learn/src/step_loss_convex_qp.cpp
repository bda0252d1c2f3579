// The convex step loss's phase QPs (dual and lifted) and the pullback of their gradients to
// the island data (step_loss_convex_qp.hpp; formulas in step_loss_convex.hpp).
#include "step_loss_convex_qp.hpp"

#include <lcprelax/sparse/triplets.hpp>

#include <cmath>
#include <utility>
#include <vector>

namespace lcprelax::learn::detail {
namespace {

lcprelax::detail::ConvexPhaseQp build(bool phase1, const ConvexLossData& d, double r,
                                      const NormalSofteningTerms& softening) {
  lcprelax::detail::ConvexPhaseTerms terms;
  terms.hessian_scale = 1.0 + d.w;
  if (phase1) {
    terms.qn = &d.qn1;
    terms.regularization = r;
    // Wnn λn + bn ≥ 0: implied by optimality when w = 0 (and then weakly active wherever
    // λn > 0, a degenerate row the adjoint would only interpolate), so posed only for w > 0.
    terms.contact_rows = d.w > 0.0;
    return lcprelax::detail::convex_phase1_qp(d.model, softening, terms);
  }
  terms.qn = &d.qn2;
  terms.qt = &d.qt2;
  return lcprelax::detail::convex_phase2_qp(d.model, softening, terms);
}

ConvexLossQp as_loss_qp(lcprelax::detail::ConvexPhaseQp&& qp, const NormalSofteningTerms& softening) {
  ConvexLossQp out;
  out.problem = std::move(qp.problem);
  out.lambda_offset = qp.lambda_offset;
  out.softening = softening;
  return out;
}

}  // namespace

SparseMatrix zero_like(const SparseMatrix& A) {
  SparseMatrix Z = A;
  Z.makeCompressed();
  for (Index k = 0; k < Z.nonZeros(); ++k) Z.valuePtr()[k] = 0.0;
  return Z;
}

ConvexLossData::ConvexLossData(const ContactSystem& system, const Vector& target, double dt_in, double w_in,
                               bool lifted_in)
    : s(system), dt(dt_in), w(w_in), lifted(lifted_in), nc(system.num_contacts()), nf(system.num_friction()),
      nv(system.num_dofs()), gap(system.phi.cwiseMax(0.0) / dt_in),
      c((1.0 + w_in) * system.v_star - w_in * target), qn1(system.Jn * c + gap), qn2(system.Jn * c),
      qt2(system.Jt * c),
      model(system, system.Jn * system.v_star + gap,
            lifted_in ? ConvexFormulation::lifted : ConvexFormulation::dual),
      bn(model.bn), w_nn(model.w_nn), W(model.W) {
  if (!lifted) {
    std::vector<Triplet> t;
    append_triplets(t, s.Jn, 0, 0, 1.0);
    append_triplets(t, s.Jt, nc, 0, 1.0);
    J = from_triplets(nc + nf, nv, t);
  }
}

ConvexLossQp convex_loss_phase1(const ConvexLossData& d, double r, const NormalSofteningTerms& softening) {
  return as_loss_qp(build(true, d, r, softening), softening);
}

ConvexLossQp convex_loss_phase2(const ConvexLossData& d, const NormalSofteningTerms& softening) {
  return as_loss_qp(build(false, d, 0.0, softening), softening);
}

ConvexLossPullback::ConvexLossPullback(const ConvexLossData& data)
    : d(data), Jn_bar(zero_like(data.s.Jn)), Jt_bar(zero_like(data.s.Jt)) {
  if (!d.lifted) W_bar = zero_like(d.W);
  bn_bar = gap_bar = w_nn_bar = phi_bar = vn_bar = compliance_bar = erp_bar = Vector::Zero(d.nc);
  mu_bar = Vector::Zero(d.nf);
  c_bar = minv_bar = Vector::Zero(d.nv);
}

void ConvexLossPullback::add_J(Index row, Index col, double v) {
  if (row < d.nc)
    Jn_bar.coeffRef(row, col) += v;
  else
    Jt_bar.coeffRef(row - d.nc, col) += v;
}

void ConvexLossPullback::add_outer(const Vector& a, const Vector& b) {
  for (Index k = 0; k < d.nv; ++k) {
    for (SparseMatrix::InnerIterator it(Jn_bar, k); it; ++it) it.valueRef() += a(it.row()) * b(k);
    for (SparseMatrix::InnerIterator it(Jt_bar, k); it; ++it) it.valueRef() += a(d.nc + it.row()) * b(k);
  }
}

double ConvexLossPullback::add_phase(int phase, const ConvexLossQp& qp, const QpGradient& g, double rho) {
  const ContactSystem& s = d.s;
  const Index nc = d.nc, nf = d.nf, nv = d.nv, off = qp.lambda_offset;
  // q = J c (+ gap on λn in phase 1).
  Vector q_bar = Vector::Zero(nc + nf);
  q_bar.head(nc) = g.dq.segment(off, nc);
  if (phase == 2) q_bar.tail(nf) = g.dq.segment(off + nc, nf);
  add_outer(q_bar, d.c);
  c_bar += s.Jn.transpose() * q_bar.head(nc) + s.Jt.transpose() * q_bar.tail(nf);
  if (phase == 1) gap_bar += q_bar.head(nc);
  // Both phases' λn terms subtract the softening's v_ref(φ, vn) (normal_softening.hpp).
  if (qp.softening.v_ref.size() == nc)
    for (Index i = 0; i < nc; ++i) {
      const double vref_bar = -q_bar(i);
      phi_bar(i) += vref_bar * qp.softening.dvref_dphi(i);
      vn_bar(i) += vref_bar * qp.softening.dvref_dvn(i);
      if (qp.softening.dvref_derp.size() == nc) erp_bar(i) += vref_bar * qp.softening.dvref_derp(i);
    }
  // l = −bn on the contact rows.
  if (g.dl.size() >= nc) bn_bar -= g.dl.head(nc);
  // P: (1+w)W or (1+w)M, and the softening's diagonal r_i = g(φ_i)·Wnn_i on λn (phase 2).
  auto add_rho = [&](Index i, double v) {
    phi_bar(i) += v * qp.softening.dg_dphi(i) * d.w_nn(i);
    w_nn_bar(i) += v * qp.softening.g(i);
    compliance_bar(i) += v;  // r_i = g_i Wnn_i + c_i
  };
  for (Index j = 0; j < g.dP.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(g.dP, j); it; ++it) {
      const Index i = it.row();
      const double v = it.value();
      if (!d.lifted) {
        W_bar.coeffRef(i, j) += (1.0 + d.w) * v;
        if (phase == 2 && i == j && i < nc) add_rho(i, v);
        if (phase == 1 && i == j) w_nn_bar(i) += rho * v;  // phase 1: ρ is the regularization r
      } else if (i == j && j < nv) {
        minv_bar(j) -= (1.0 + d.w) * v / (s.minv(j) * s.minv(j));
      } else if (i == j && phase == 2 && j - nv < nc) {
        add_rho(j - nv, v);
      } else if (i == j && phase == 1) {
        w_nn_bar(j - nv) += rho * v;  // phase 1: ρ is the regularization r
      }
    }
  // A (lifted): [M, −Jnᵀ, −Jtᵀ].
  if (d.lifted)
    for (Index col = 0; col < g.dA.outerSize(); ++col)
      for (SparseMatrix::InnerIterator it(g.dA, col); it; ++it) {
        const Index r = it.row();
        if (col < nv)
          minv_bar(col) -= it.value() / (s.minv(col) * s.minv(col));
        else
          add_J(col - nv, r, -it.value());
      }
  // G: contact rows (Wn or Jn), eᵀ row, friction rows.
  for (Index col = 0; col < g.dG.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(g.dG, col); it; ++it) {
      const Index r = it.row();
      if (r < nc) {
        if (!d.lifted)
          W_bar.coeffRef(r, col) += it.value();
        else if (col < nv)
          Jn_bar.coeffRef(r, col) += it.value();
      } else if (r > nc) {
        const Index f = (r - nc - 1) / 2;
        if (col == off + s.friction_rows[f]) mu_bar(f) += ((r - nc - 1) % 2 == 0 ? -1.0 : 1.0) * it.value();
      }
    }
  return phase == 2 ? g.du(nc) : 0.0;
}

void ConvexLossPullback::finish(ContactSystemCotangent& out) {
  const ContactSystem& s = d.s;
  if (!d.lifted) {  // W = J D Jᵀ: J̄ += 2 W̄ₛ J D, D̄_k += (Jᵀ W̄ₛ J)_kk
    const SparseMatrix Ws = 0.5 * (SparseMatrix(W_bar.transpose()) + W_bar);
    const SparseMatrix B = Ws * d.J;
    Vector col = Vector::Zero(d.nc + d.nf);
    for (Index k = 0; k < d.nv; ++k) {
      for (SparseMatrix::InnerIterator it(B, k); it; ++it) col(it.row()) = it.value();
      for (SparseMatrix::InnerIterator it(d.J, k); it; ++it) {
        add_J(it.row(), k, 2.0 * col(it.row()) * s.minv(k));
        minv_bar(k) += it.value() * col(it.row());
      }
      for (SparseMatrix::InnerIterator it(B, k); it; ++it) col(it.row()) = 0.0;
    }
  }
  // w_nn_i = Σ_j Jn_ij² minv_j.
  for (Index k = 0; k < d.nv; ++k) {
    SparseMatrix::InnerIterator b(Jn_bar, k);
    for (SparseMatrix::InnerIterator it(s.Jn, k); it; ++it, ++b) {
      b.valueRef() += 2.0 * it.value() * s.minv(k) * w_nn_bar(it.row());
      minv_bar(k) += it.value() * it.value() * w_nn_bar(it.row());
    }
  }
  // bn = Jn v* + gap, gap = max(φ, 0)/Δt, c = (1 + w)v* − w v̄.
  Vector a = Vector::Zero(d.nc + d.nf);
  a.head(d.nc) = bn_bar;
  add_outer(a, s.v_star);
  if ((vn_bar.array() != 0.0).any()) {  // vn = Jn v* (the softening's target velocity)
    a.head(d.nc) = vn_bar;
    add_outer(a, s.v_star);
    out.v_star += s.Jn.transpose() * vn_bar;
  }
  out.v_star += s.Jn.transpose() * bn_bar + (1.0 + d.w) * c_bar;
  gap_bar += bn_bar;
  for (Index i = 0; i < d.nc; ++i)
    if (s.phi(i) > 0.0) phi_bar(i) += gap_bar(i) / d.dt;
  out.phi += phi_bar;
  if (out.compliance.size() == d.nc) out.compliance += compliance_bar;
  if (out.erp.size() == d.nc) out.erp += erp_bar;
  out.mu += mu_bar;
  out.minv += minv_bar;
  out.Jn += Jn_bar;
  out.Jt += Jt_bar;
}

}  // namespace lcprelax::learn::detail
