// QpSolver::backward: the OptNet adjoint at the final iterate, solved with the last
// forward factorization (derivation in qp_solver.hpp). All algebra is done on the scaled
// internal form, then chained to the user's data through the (constant) scaling factors:
//   P̃ = c·Dx P Dx, q̃ = c·Dx∘q, Ẽ = diag(Ee) E diag(Dx), b̃ = Ee∘b, G̃ = diag(Eg) G diag(Dx),
//   g̃ = Eg∘(l, u), x̃l = xl/Dx;   x = Dx∘x̃, y = Ee∘ỹ/c, z = Eg∘ζ/c.
// The adjoint system uses the barrier terms (Db, Dg) of that factorization, i.e. of the
// iterate before the last step; active and inactive constraints are at W → 0 and W → ∞
// there, so the difference vanishes as the solve converges.
// Exception: a solve that stopped before its first factorization (a warm start that
// already met the tolerances: 0 iterations) has no factorization of its own; the solver's
// last one belongs to an earlier problem (or does not exist), and the warm iterate's
// barrier terms are not those of a converged interior point (the warm start keeps every
// s, z ≥ 1e-2), so factorizing there gives gradients off by percents (measured 6% on a
// one-variable box QP). backward() then solves the problem again from the cold start
// (result() is replaced by that solve; it agrees with the warm one to the tolerances) and
// uses its final factorization; reusing the last factorization instead would give the
// gradient of the previous problem and, with per-thread workspaces, results that depend
// on the thread schedule (tests/qp_backward_warm_start_test.cpp).
#include "qp_solver_impl.hpp"

#include <lcprelax/core/errors.hpp>

#include <chrono>
#include <stdexcept>

namespace lcprelax {
namespace {

// Splits the signed adjoint d̃ of a quantity into its upper and lower one-sided parts in
// proportion to z/s of each side (exact: d̃_side = (z/s)(±v + g) and d̃ = D(v + g)).
void split_sides(const detail::Side& side, const Vector& dsigned, const Vector& D, Vector& out) {
  for (Index k = 0; k < side.size(); ++k) {
    const Index q = side.idx[k];
    const double share = D(q) > 0 ? (side.z(k) / side.s(k)) / D(q) : 0.0;
    out(q) = (side.upper ? 1.0 : -1.0) * dsigned(q) * share;
  }
}

}  // namespace

QpGradient QpSolver::backward(const Vector& dl_dx, const Vector& dl_dy, const Vector& dl_dz) {
  Impl& m = *impl_;
  const auto t0 = std::chrono::steady_clock::now();
  if (!has_solution(m.result.info.status))
    throw std::logic_error(std::string("QpSolver::backward needs a solved problem, status is ") +
                           to_string(m.result.info.status));
  const QpProblem& p = m.problem;
  const detail::StandardForm& f = m.form;
  const Index n = f.n;
  if (dl_dx.size() != n || (dl_dy.size() != 0 && dl_dy.size() != p.num_equalities()) ||
      (dl_dz.size() != 0 && dl_dz.size() != p.num_inequalities()))
    throw InputError("QpSolver::backward: gradient sizes do not match the problem");
  if (!dl_dx.allFinite() || !dl_dy.allFinite() || !dl_dz.allFinite())
    throw InputError("QpSolver::backward: non-finite loss gradient");

  // Loss gradients with respect to the scaled unknowns (x̃, ỹ, ζ).
  const Vector gx = f.Dx.cwiseProduct(dl_dx);
  Vector gy = Vector::Zero(f.me), gz = Vector::Zero(f.mg);
  for (Index k = 0; k < f.me; ++k) {
    const Index s = f.eq_index[k];
    if (f.eq_source[k] == detail::EqSource::a_row && dl_dy.size()) gy(k) = f.Ee(k) / f.c * dl_dy(s);
    if (f.eq_source[k] == detail::EqSource::g_row && dl_dz.size()) gy(k) = f.Ee(k) / f.c * dl_dz(s);
  }
  if (dl_dz.size())
    for (Index k = 0; k < f.mg; ++k) gz(k) = f.Eg(k) / f.c * dl_dz(f.g_index[k]);

  if (m.result.info.factorizations == 0) {  // see the header comment
    m.has_warm_start = false;
    const QpResult& cold = solve();
    if (!has_solution(cold.info.status))
      throw std::runtime_error(std::string("QpSolver::backward: the cold re-solve after a 0-iteration warm start "
                                           "failed: ") + to_string(cold.info.status));
  }

  // One refined solve with the final factorization: K0 (d_x, d_y, d̃_ζ) = −(g_x, g_y, g_ζ).
  Vector dx, dy, dz;
  m.kkt.solve(f, -gx, -gy, -gz, dx, dy, dz, m.settings.max_refinement);
  if (f.me == 0) dy = Vector::Zero(0);

  // Scaled multipliers and the one-sided adjoints of bounds and rows.
  const Vector& xt = m.it.x;
  Vector zg, zb;
  m.it.signed_multipliers(f.mg, n, zg, zb);
  const Vector db_signed = m.Db.cwiseProduct(dx);
  Vector Dg_now, Db_now;  // the shares of each side use the final iterate's z/s
  m.it.barrier_terms(f.mg, n, Dg_now, Db_now);
  Vector dgu = Vector::Zero(f.mg), dgl = Vector::Zero(f.mg), dbu = Vector::Zero(n), dbl = Vector::Zero(n);
  split_sides(m.it.g_upper, dz, Dg_now, dgu);
  split_sides(m.it.g_lower, dz, Dg_now, dgl);
  split_sides(m.it.b_upper, db_signed, Db_now, dbu);
  split_sides(m.it.b_lower, db_signed, Db_now, dbl);

  QpGradient g;
  g.adjoint_residual = m.kkt.last_relative_residual();
  g.dq = f.c * f.Dx.cwiseProduct(dx);
  g.dP = p.P;
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(g.dP, j); it; ++it) {
      const Index i = it.row();
      const double v = i == j ? dx(i) * xt(i) : dx(i) * xt(j) + xt(i) * dx(j);
      it.valueRef() = f.c * f.Dx(i) * f.Dx(j) * v;
    }
  std::vector<Index> eq_of_a(p.num_equalities(), -1), kept_of_g(p.num_inequalities(), -1);
  for (Index k = 0; k < f.me; ++k)
    if (f.eq_source[k] == detail::EqSource::a_row) eq_of_a[f.eq_index[k]] = k;
  for (Index k = 0; k < f.mg; ++k) kept_of_g[f.g_index[k]] = k;
  g.dA = p.A;
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(g.dA, j); it; ++it) {
      const Index k = eq_of_a[it.row()];
      it.valueRef() = f.Ee(k) * f.Dx(j) * (dy(k) * xt(j) + m.it.y(k) * dx(j));
    }
  g.dG = p.G;
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(g.dG, j); it; ++it) {
      const Index i = it.row();
      double v = 0.0;
      if (const Index k = f.g_eq_row[i]; k >= 0) v = f.Ee(k) * f.Dx(j) * (dy(k) * xt(j) + m.it.y(k) * dx(j));
      else if (const Index k2 = kept_of_g[i]; k2 >= 0) v = f.Eg(k2) * f.Dx(j) * (dz(k2) * xt(j) + zg(k2) * dx(j));
      it.valueRef() = v;
    }
  g.db = Vector::Zero(p.num_equalities());
  g.dl = Vector::Zero(p.num_inequalities());
  g.du = Vector::Zero(p.num_inequalities());
  g.dxl = Vector::Zero(n);
  g.dxu = Vector::Zero(n);
  for (Index k = 0; k < f.me; ++k) {
    const Index s = f.eq_index[k];
    const double v = -f.Ee(k) * dy(k);  // ∂ℓ/∂(right-hand side)
    switch (f.eq_source[k]) {
      case detail::EqSource::a_row: g.db(s) = v; break;
      case detail::EqSource::g_row: (m.result.z(s) >= 0 ? g.du(s) : g.dl(s)) = v; break;
      case detail::EqSource::fixed_variable: (m.result.z_bounds(s) >= 0 ? g.dxu(s) : g.dxl(s)) = v; break;
    }
  }
  for (Index k = 0; k < f.mg; ++k) {
    const Index s = f.g_index[k];
    g.du(s) = -f.Eg(k) * dgu(k);
    g.dl(s) = f.Eg(k) * dgl(k);
  }
  for (Index j = 0; j < n; ++j) {
    if (f.fixed_eq_row[j] >= 0) continue;
    g.dxu(j) = -dbu(j) / f.Dx(j);
    g.dxl(j) = dbl(j) / f.Dx(j);
  }
  m.result.info.backward_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return g;
}

}  // namespace lcprelax
