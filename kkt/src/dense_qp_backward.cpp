// DenseQpSolver::backward(): the OptNet adjoint of the KKT conditions at the final iterate,
// reduced to the normal matrix factorized at that iterate by solve() (derivation and
// conventions: dense_qp_solver.hpp), mapped to QpGradient's conventions.
#include "dense_qp_impl.hpp"
#include "vector_norms.hpp"

#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lcprelax {
namespace dense_qp_detail {


// out gets M's pattern (its storage reused when it already has it).
void take_pattern(const SparseMatrix& M, SparseMatrix& out) {
  const bool same = out.rows() == M.rows() && out.cols() == M.cols() && out.isCompressed() &&
                    out.nonZeros() == M.nonZeros() &&
                    std::equal(M.outerIndexPtr(), M.outerIndexPtr() + M.outerSize() + 1, out.outerIndexPtr()) &&
                    std::equal(M.innerIndexPtr(), M.innerIndexPtr() + M.nonZeros(), out.innerIndexPtr());
  if (!same) out = M;
}

// Values of α_i a_j + β_i x_j on M's pattern (row i, column j), into out.
void rank_two_on_pattern(const SparseMatrix& M, const Vector& alpha, const Vector& a, const Vector& beta,
                         const Vector& x, SparseMatrix& out) {
  take_pattern(M, out);
  for (Index j = 0; j < out.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(out, j); it; ++it)
      it.valueRef() = alpha(it.row()) * a(j) + beta(it.row()) * x(j);
}

}  // namespace dense_qp_detail

using namespace dense_qp_detail;

bool DenseQpSolver::Impl::factorize_adjoint() {
  // W = s/λ at an interior-point iterate. At an exact active set: 0 on the strictly active
  // sides, ∞ on the inactive ones, and on a weakly active side (slack and multiplier both
  // ≤ eps_abs, where the derivative does not exist) the interior point's central-path limit
  // W_k = c_kᵀ Z(ZᵀPZ)⁻¹Zᵀ c_k (Z: null space of the strictly active rows), which gives the
  // mean of the two one-sided derivatives (what central differences approach): for one
  // weakly active side exactly, for several each computed as if it were the only one.
  constexpr double kInf = std::numeric_limits<double>::infinity();
  W_sides.resize(mc);
  if (!exact_active_set) {
    W_sides = s.cwiseQuotient(lam);
    return factor_adjoint_split();
  }
  const double tau = settings.eps_abs;
  weak.clear();
  for (Index k = 0; k < mc; ++k) {
    const bool on = as_active[static_cast<std::size_t>(k)] != 0;
    const bool is_weak = on ? lam(k) <= tau : s(k) <= tau;
    W_sides(k) = on && !is_weak ? 0.0 : kInf;
    if (is_weak) weak.push_back(k);
  }
  if (factor_exact_active_set()) return true;
  // The same with regularization retries (dependent active rows): the strictly active split
  // first, then each weak W from its factors.
  for (Index k : weak) W_sides(k) = kInf;
  if (!factor_adjoint_split()) return false;
  if (weak.empty()) return true;
  // W_k = cᵀP⁻¹c − (E P⁻¹c)ᵀ (E P⁻¹Eᵀ)⁻¹ (E P⁻¹c) with the strictly active E just factorized
  // (K_adj = P): t = L⁻¹c, v = L_S⁻¹ (L⁻¹Eᵀ)ᵀ t, W_k = |t|² − |v|².
  Vector &t = aw.wl, &v = aw.rhs;
  for (Index k : weak) {
    t.setZero(n);
    const Side& sd = sides[static_cast<std::size_t>(k)];
    if (sd.on_g_row)
      t = sd.sign * Gi.row(sd.gi_row).transpose();
    else
      t(sd.index) = sd.sign;
    llt_Kadj.solve_lower(t);
    double wk = t.squaredNorm();
    if (ne_adj > 0) {
      v.noalias() = WE.leftCols(ne_adj).transpose() * t;
      llt_Sadj.solve_lower(v);
      wk -= v.squaredNorm();
    }
    W_sides(k) = std::max(wk, 0.0);
  }
  return factor_adjoint_split();
}

bool DenseQpSolver::Impl::factor_exact_active_set() {
  // Rows: equality rows, the strictly active sides, then the weak ones; K_adj = P (its
  // factor kept from the active-set method). S = E P⁻¹Eᵀ is factorized once: the leading
  // block (equality and strictly active rows) first, which gives each weak side's
  // W_k = S_kk − |L_lead⁻¹ S_lead,k|² (its Schur complement: c_kᵀ Z(ZᵀPZ)⁻¹Zᵀ c_k), added on
  // its diagonal before the whole S is factorized. No regularization: false when a block
  // is not positive definite (dependent rows).
  active.clear();
  for (Index k = 0; k < mc; ++k)
    if (W_sides(k) == 0.0) active.push_back(k);
  const Index lead = me + static_cast<Index>(active.size());
  for (Index k : weak) active.push_back(k);
  const Index ne = me + static_cast<Index>(active.size());
  ne_adj = ne;
  auto Eb = E.topRows(ne);
  Eb.setZero();
  Eb.topRows(me) = Ae;
  for (Index r = me; r < ne; ++r) {
    const Side& sd = sides[static_cast<std::size_t>(active[static_cast<std::size_t>(r - me)])];
    if (sd.on_g_row)
      Eb.row(r) = sd.sign * Gi.row(sd.gi_row);
    else
      Eb(r, sd.index) = sd.sign;
  }
  aw.dk.setZero(mc);
  llt_Kadj = llt_P;
  if (ne == 0) return true;
  auto WEb = WE.leftCols(ne);
  auto Sb = S_adj.topLeftCorner(ne, ne);
  WEb = Eb.transpose();
  llt_Kadj.solve_lower_columns(WEb);
  Sb.noalias() = WEb.transpose().lazyProduct(WEb);
  if (!weak.empty()) {
    if (lead > 0 && !llt_Sadj.compute(Sb.topLeftCorner(lead, lead))) return false;
    Vector& v = aw.rhs;
    for (Index r = lead; r < ne; ++r) {
      double wk = Sb(r, r);
      if (lead > 0) {
        v = Sb.col(r).head(lead);
        llt_Sadj.solve_lower(v);
        wk -= v.squaredNorm();
      }
      wk = std::max(wk, 0.0);
      W_sides(active[static_cast<std::size_t>(r - me)]) = wk;
      Sb(r, r) += wk;
    }
  }
  return llt_Sadj.compute(Sb);
}

bool DenseQpSolver::Impl::factor_adjoint_split() {
  // Rows: sides with W < 1 and (at an exact active set) the weakly active ones, whose W is
  // O(1); the others (W ≥ 1, ∞ off an exact active set) are eliminated into K_adj.
  active.clear();
  for (Index k = 0; k < mc; ++k)
    if (W_sides(k) < 1.0 || (exact_active_set && std::isfinite(W_sides(k)))) active.push_back(k);
  const Index na = static_cast<Index>(active.size()), ne = me + na;
  ne_adj = ne;
  auto Eb = E.topRows(ne);
  Eb.setZero();
  Eb.topRows(me) = Ae;
  Vector& dk = aw.dk;
  dk = W_sides.cwiseInverse();  // eliminated sides: λ/s (0 where W = ∞)
  for (Index r = 0; r < na; ++r) {
    const Index k = active[static_cast<std::size_t>(r)];
    const Side& sd = sides[static_cast<std::size_t>(k)];
    if (sd.on_g_row)
      Eb.row(me + r) = sd.sign * Gi.row(sd.gi_row);
    else
      Eb(me + r, sd.index) = sd.sign;
    dk(k) = 0.0;  // kept as a row, not eliminated
  }
  const bool k_is_p = exact_active_set && (dk.array() == 0.0).all();
  // K_adj = P + Σ_eliminated λ/s c cᵀ + ρI; at an exact active set without weak sides it is
  // P, already factorized.
  auto factor_k = [&](double reg) {
    if (k_is_p && reg == reg_base) {
      llt_Kadj = llt_P;
      return true;
    }
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
    return llt_Kadj.compute(K_adj);
  };
  double reg = reg_base;
  for (int attempt = 0; attempt <= 8; ++attempt, reg *= 10.0) {
    if (!factor_k(reg)) continue;
    if (ne == 0) return true;
    auto WEb = WE.leftCols(ne);
    auto Sb = S_adj.topLeftCorner(ne, ne);
    WEb = Eb.transpose();
    llt_Kadj.solve_lower_columns(WEb);
    Sb.noalias() = WEb.transpose().lazyProduct(WEb);  // coefficient-wise: these are tiny
    // No regularization of the Schur complement at the first attempt (exact when the kept
    // rows are independent); ρ from the second on.
    const double reg_s = attempt == 0 ? 0.0 : reg;
    for (Index r = 0; r < ne; ++r) Sb(r, r) += r < me ? reg_s : W_sides(active[static_cast<std::size_t>(r - me)]) + reg_s;
    if (llt_Sadj.compute(Sb)) return true;
  }
  return false;
}

void DenseQpSolver::Impl::adjoint_solve(const Vector& fx, const Vector& fy, const Vector& fl, Vector& a, Vector& b,
                                        Vector& ct) {
  // Inactive sides: c̃ = W⁻¹(C a − fl); then K_adj a + Eᵀu = fx + C_Iᵀ W_I⁻¹ fl_I,
  // E a − D_E u = (fy, fl_A), u = (b, c̃_A), D_E = (0, W_A).
  const Index na = static_cast<Index>(active.size());
  Vector &wl = aw.wl, &f = aw.f, &ka = aw.ka, &u = aw.u, &rhs = aw.rhs, &Ca = aw.Ca;
  wl = fl.cwiseQuotient(W_sides);
  for (Index k : active) wl(k) = 0.0;
  f.resize(n);
  apply_Ct(wl, f);
  f += fx;
  ka = f;
  u.resize(me + na);
  llt_Kadj.solve_in_place(ka);
  if (me + na > 0) {
    rhs.noalias() = E.topRows(me + na) * ka;
    rhs.head(me) -= fy;
    for (Index r = 0; r < na; ++r) rhs(me + r) -= fl(active[static_cast<std::size_t>(r)]);
    u = rhs;
    llt_Sadj.solve_in_place(u);
    f.noalias() -= E.topRows(me + na).transpose() * u;
    a = f;
    llt_Kadj.solve_in_place(a);
  } else {
    a = ka;
  }
  b = u.head(me);
  Ca.resize(mc);
  apply_C(a, Ca);
  ct = (Ca - fl).cwiseQuotient(W_sides);
  for (Index r = 0; r < na; ++r) ct(active[static_cast<std::size_t>(r)]) = u(me + r);
}

QpGradient DenseQpSolver::backward(const Vector& dl_dx, const Vector& dl_dy, const Vector& dl_dz) {
  QpGradient g;
  backward(dl_dx, dl_dy, dl_dz, g);
  return g;
}

void DenseQpSolver::backward(const Vector& dl_dx, const Vector& dl_dy, const Vector& dl_dz, QpGradient& g) {
  Impl& m = *impl_;
  const QpStatus st = m.result.info.status;
  if (!has_solution(st))
    throw std::logic_error(std::string("DenseQpSolver::backward(): status ") + to_string(st) + ", no solution to differentiate");
  const QpProblem& p = m.problem;
  const Index n = m.n, ma = p.num_equalities(), mi = p.num_inequalities();
  if (dl_dx.size() != n || (dl_dy.size() != 0 && dl_dy.size() != ma) || (dl_dz.size() != 0 && dl_dz.size() != mi))
    throw InputError("DenseQpSolver::backward(): dl_dx must have " + std::to_string(n) + " entries, dl_dy " +
                     std::to_string(ma) + " or none, dl_dz " + std::to_string(mi) + " or none");
  if (m.used_fallback) {
    g = m.fallback->backward(dl_dx, dl_dy, dl_dz);
    return;
  }
  if (!m.factorized_at_final) throw std::logic_error("DenseQpSolver::backward(): no factorization at the solution");

  // Loss gradients in the internal variables: y' = −(y, z of equality rows), λ from z.
  Impl::AdjointWork& w = m.aw;
  Vector &g_y = w.g_y, &g_l = w.g_l;
  g_y.setZero(m.me), g_l.setZero(m.mc);
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
  Vector &fy = w.fy, &fl = w.fl, &a = w.a, &b = w.b, &ct = w.ct, &r1 = w.r1, &r2 = w.r2, &r3 = w.r3;
  Vector &da = w.da, &db = w.db, &dct = w.dct, &Ctv = w.Ctv, &Cv = w.Cv;
  fy = -g_y, fl = -g_l;
  a.setZero(n), b.setZero(me), ct.setZero(mc);
  r1 = dl_dx, r2 = fy, r3 = fl;  // residuals (v = 0)
  da.resize(n), db.resize(me), dct.resize(mc), Ctv.resize(n), Cv.resize(mc);
  const double scale = 1.0 + std::max({detail::inf_norm(dl_dx), detail::inf_norm(g_y), detail::inf_norm(g_l)});
  double res = std::max({detail::inf_norm(r1), detail::inf_norm(r2), detail::inf_norm(r3)});
  constexpr int kRefinementSteps = 3;
  for (int step = 0; step <= kRefinementSteps && res > 1e-12 * scale; ++step) {
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
    for (Index k = 0; k < mc; ++k) r3(k) = std::isinf(W(k)) ? 0.0 : fl(k) - Cv(k) + W(k) * ct(k);
    res = std::max({detail::inf_norm(r1), detail::inf_norm(r2), detail::inf_norm(r3)});
  }

  g.adjoint_residual = res / scale;
  g.dq = -a;
  // ∂ℓ/∂P_ij = −a_i x_j, symmetrized on the upper pattern (an off-diagonal entry counts twice).
  take_pattern(p.P, g.dP);
  for (Index j = 0; j < g.dP.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(g.dP, j); it; ++it) {
      const Index i = it.row();
      it.valueRef() = i == j ? -a(i) * m.x(j) : -(a(i) * m.x(j) + a(j) * m.x(i));
    }
  g.db.setZero(ma), g.dl.setZero(mi), g.du.setZero(mi), g.dxl.setZero(n), g.dxu.setZero(n);
  // Row i of A or G: ∂ℓ/∂row = α_i a + β_i x.
  Vector &alpha_a = w.alpha_a, &beta_a = w.beta_a, &alpha_g = w.alpha_g, &beta_g = w.beta_g;
  alpha_a.setZero(ma), beta_a.setZero(ma), alpha_g.setZero(mi), beta_g.setZero(mi);
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
  rank_two_on_pattern(p.A, alpha_a, a, beta_a, m.x, g.dA);
  rank_two_on_pattern(p.G, alpha_g, a, beta_g, m.x, g.dG);
}

}  // namespace lcprelax
