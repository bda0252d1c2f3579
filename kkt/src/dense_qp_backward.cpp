// DenseQpSolver::backward(): the OptNet adjoint of the KKT conditions at the final iterate,
// reduced to the normal matrix factorized at that iterate by solve() (derivation and
// conventions: dense_qp_solver.hpp), mapped to QpGradient's conventions.
#include "dense_qp_impl.hpp"
#include "vector_norms.hpp"

#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace lcprelax {
namespace dense_qp_detail {


// Values of α_i a_j + β_i x_j on M's pattern (row i, column j).
SparseMatrix rank_two_on_pattern(const SparseMatrix& M, const Vector& alpha, const Vector& a, const Vector& beta,
                                 const Vector& x) {
  SparseMatrix out = M;
  for (Index j = 0; j < out.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(out, j); it; ++it)
      it.valueRef() = alpha(it.row()) * a(j) + beta(it.row()) * x(j);
  return out;
}

}  // namespace dense_qp_detail

using namespace dense_qp_detail;

bool DenseQpSolver::Impl::factorize_adjoint() {
  W_sides = s.cwiseQuotient(lam);
  active.clear();
  for (Index k = 0; k < mc; ++k)
    if (W_sides(k) < 1.0) active.push_back(k);
  const Index na = static_cast<Index>(active.size()), ne = me + na;
  E.setZero(ne, n);
  E.topRows(me) = Ae;
  Vector dk = lam.cwiseQuotient(s);
  for (Index r = 0; r < na; ++r) {
    const Index k = active[static_cast<std::size_t>(r)];
    const Side& sd = sides[static_cast<std::size_t>(k)];
    if (sd.on_g_row)
      E.row(me + r) = sd.sign * Gi.row(sd.gi_row);
    else
      E(me + r, sd.index) = sd.sign;
    dk(k) = 0.0;  // kept as a row, not eliminated
  }
  double reg = reg_base;
  for (int attempt = 0; attempt <= 8; ++attempt, reg *= 10.0) {
    K_adj = P;
    for (Index k = 0; k < mc; ++k) {
      if (dk(k) == 0.0) continue;
      const Side& sd = sides[static_cast<std::size_t>(k)];
      if (sd.on_g_row)
        K_adj.noalias() += (dk(k) * Gi.row(sd.gi_row).transpose()) * Gi.row(sd.gi_row);
      else
        K_adj(sd.index, sd.index) += dk(k);
    }
    K_adj.diagonal().array() += reg;
    if (!llt_Kadj.compute(K_adj)) continue;
    if (ne == 0) return true;
    WE = E.transpose();
    llt_Kadj.solve_lower_columns(WE);
    S_adj.noalias() = WE.transpose() * WE;
    for (Index r = 0; r < ne; ++r) S_adj(r, r) += r < me ? reg : W_sides(active[static_cast<std::size_t>(r - me)]) + reg;
    if (llt_Sadj.compute(S_adj)) return true;
  }
  return false;
}

void DenseQpSolver::Impl::adjoint_solve(const Vector& fx, const Vector& fy, const Vector& fl, Vector& a, Vector& b,
                                        Vector& ct) {
  // Inactive sides: c̃ = W⁻¹(C a − fl); then K_adj a + Eᵀu = fx + C_Iᵀ W_I⁻¹ fl_I,
  // E a − D_E u = (fy, fl_A), u = (b, c̃_A), D_E = (0, W_A).
  const Index na = static_cast<Index>(active.size());
  Vector wl = fl.cwiseQuotient(W_sides);
  for (Index k : active) wl(k) = 0.0;
  Vector f(n);
  apply_Ct(wl, f);
  f += fx;
  Vector ka = f, u(me + na);
  llt_Kadj.solve_in_place(ka);
  if (me + na > 0) {
    Vector rhs = E * ka;
    rhs.head(me) -= fy;
    for (Index r = 0; r < na; ++r) rhs(me + r) -= fl(active[static_cast<std::size_t>(r)]);
    u = rhs;
    llt_Sadj.solve_in_place(u);
    f.noalias() -= E.transpose() * u;
    a = f;
    llt_Kadj.solve_in_place(a);
  } else {
    a = ka;
  }
  b = u.head(me);
  Vector Ca(mc);
  apply_C(a, Ca);
  ct = (Ca - fl).cwiseQuotient(W_sides);
  for (Index r = 0; r < na; ++r) ct(active[static_cast<std::size_t>(r)]) = u(me + r);
}

QpGradient DenseQpSolver::backward(const Vector& dl_dx, const Vector& dl_dy, const Vector& dl_dz) {
  Impl& m = *impl_;
  const QpStatus st = m.result.info.status;
  if (!has_solution(st))
    throw std::logic_error(std::string("DenseQpSolver::backward(): status ") + to_string(st) + ", no solution to differentiate");
  const QpProblem& p = m.problem;
  const Index n = m.n, ma = p.num_equalities(), mi = p.num_inequalities();
  if (dl_dx.size() != n || (dl_dy.size() != 0 && dl_dy.size() != ma) || (dl_dz.size() != 0 && dl_dz.size() != mi))
    throw InputError("DenseQpSolver::backward(): dl_dx must have " + std::to_string(n) + " entries, dl_dy " +
                     std::to_string(ma) + " or none, dl_dz " + std::to_string(mi) + " or none");
  if (m.used_fallback) return m.fallback->backward(dl_dx, dl_dy, dl_dz);
  if (!m.factorized_at_final) throw std::logic_error("DenseQpSolver::backward(): no factorization at the solution");

  // Loss gradients in the internal variables: y' = −(y, z of equality rows), λ from z.
  Vector g_y = Vector::Zero(m.me), g_l = Vector::Zero(m.mc);
  for (Index r = 0; r < m.me; ++r) {
    const Impl::EqRow& e = m.eq_rows[static_cast<std::size_t>(r)];
    if (e.source == Impl::EqSource::a_row && dl_dy.size() > 0) g_y(r) = -dl_dy(e.index);
    if (e.source == Impl::EqSource::g_row && dl_dz.size() > 0) g_y(r) = -dl_dz(e.index);
  }
  if (dl_dz.size() > 0)
    for (Index k = 0; k < m.mc; ++k) {
      const Impl::Side& sd = m.sides[static_cast<std::size_t>(k)];
      if (sd.on_g_row) g_l(k) = -sd.sign * dl_dz(sd.index);
    }
  // Jᵀ(a, b, c) = g:  P a + Aeᵀb + CᵀΛc = g_x,  −Ae a = g_y,  −C a + S c = g_λ. With
  // c̃ = Λc (= ∂ℓ/∂d) it is the symmetric quasi-definite system
  //   [P Aeᵀ Cᵀ; Ae 0 0; C 0 −W] (a, b, c̃) = (g_x, −g_y, −g_λ),  W = S Λ⁻¹,
  // solved with the factorization of the solution's active/inactive split and refined
  // against the unregularized matrix.
  const Vector& lam = m.lam;
  const Vector& W = m.W_sides;
  const Index me = m.me, mc = m.mc;
  const Vector fy = -g_y, fl = -g_l;
  Vector a = Vector::Zero(n), b = Vector::Zero(me), ct = Vector::Zero(mc);
  Vector r1 = dl_dx, r2 = fy, r3 = fl;  // residuals (v = 0)
  Vector da(n), db(me), dct(mc), Ctv(n), Cv(mc);
  const double scale = 1.0 + std::max({detail::inf_norm(dl_dx), detail::inf_norm(g_y), detail::inf_norm(g_l)});
  double res = std::max({detail::inf_norm(r1), detail::inf_norm(r2), detail::inf_norm(r3)});
  constexpr int kRefinementSteps = 3;
  for (int step = 0; step <= kRefinementSteps && res > 1e-15 * scale; ++step) {
    m.adjoint_solve(r1, r2, r3, da, db, dct);
    a += da, b += db, ct += dct;
    r1.noalias() = m.P * a;
    r1 = dl_dx - r1;
    if (me > 0) r1.noalias() -= m.Ae.transpose() * b;
    m.apply_Ct(ct, Ctv);
    r1 -= Ctv;
    if (me > 0) {
      r2.noalias() = m.Ae * a;
      r2 = fy - r2;
    }
    m.apply_C(a, Cv);
    r3 = fl - Cv + W.cwiseProduct(ct);
    res = std::max({detail::inf_norm(r1), detail::inf_norm(r2), detail::inf_norm(r3)});
  }

  QpGradient g;
  g.adjoint_residual = res / scale;
  g.dq = -a;
  // ∂ℓ/∂P_ij = −a_i x_j, symmetrized on the upper pattern (an off-diagonal entry counts twice).
  g.dP = p.P;
  for (Index j = 0; j < g.dP.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(g.dP, j); it; ++it) {
      const Index i = it.row();
      it.valueRef() = i == j ? -a(i) * m.x(j) : -(a(i) * m.x(j) + a(j) * m.x(i));
    }
  g.db = Vector::Zero(ma), g.dl = Vector::Zero(mi), g.du = Vector::Zero(mi);
  g.dxl = Vector::Zero(n), g.dxu = Vector::Zero(n);
  // Row i of A or G: ∂ℓ/∂row = α_i a + β_i x.
  Vector alpha_a = Vector::Zero(ma), beta_a = Vector::Zero(ma), alpha_g = Vector::Zero(mi), beta_g = Vector::Zero(mi);
  for (Index r = 0; r < me; ++r) {
    const Impl::EqRow& e = m.eq_rows[static_cast<std::size_t>(r)];
    const double yr = m.y(r);  // internal multiplier y' (user's multiplier is −y')
    switch (e.source) {
      case Impl::EqSource::a_row:
        alpha_a(e.index) = yr, beta_a(e.index) = -b(r), g.db(e.index) = b(r);
        break;
      case Impl::EqSource::g_row:
        alpha_g(e.index) = yr, beta_g(e.index) = -b(r);
        (-yr >= 0 ? g.du : g.dl)(e.index) = b(r);
        break;
      case Impl::EqSource::fixed_variable: (-yr >= 0 ? g.dxu : g.dxl)(e.index) = b(r); break;
    }
  }
  for (Index k = 0; k < mc; ++k) {
    const Impl::Side& sd = m.sides[static_cast<std::size_t>(k)];
    const double dd = ct(k);  // ∂ℓ/∂d_k = λ_k c_k; d_k = l (lower side) or −u (upper side)
    if (sd.on_g_row) {
      alpha_g(sd.index) += sd.sign * lam(k), beta_g(sd.index) -= sd.sign * dd;
      (sd.sign > 0 ? g.dl : g.du)(sd.index) += sd.sign * dd;
    } else {
      (sd.sign > 0 ? g.dxl : g.dxu)(sd.index) += sd.sign * dd;
    }
  }
  g.dA = rank_two_on_pattern(p.A, alpha_a, a, beta_a, m.x);
  g.dG = rank_two_on_pattern(p.G, alpha_g, a, beta_g, m.x);
  return g;
}

}  // namespace lcprelax
