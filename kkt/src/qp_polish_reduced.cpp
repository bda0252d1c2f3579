// The reduced KKT system of solution polishing (qp_polish_reduced.hpp; method in
// qp_polish.hpp, step 2).
#include "qp_polish_reduced.hpp"
#include "qp_polish.hpp"
#include "vector_norms.hpp"

#include <lcprelax/sparse/cholmod_ldlt.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lcprelax::detail {

Reduced reduce(const StandardForm& f, const ActiveSet& a) {
  Reduced s;
  s.col.assign(f.n, -1);
  s.pos.assign(f.mg, -1);
  s.xb = Vector::Zero(f.n);
  for (Index j = 0; j < f.n; ++j) {
    if (a.bounds[j] == 0)
      s.col[j] = s.nF++;
    else
      s.xb(j) = a.bounds[j] < 0 ? f.xl(j) : f.xu(j);
  }
  for (Index k = 0; k < f.mg; ++k)
    if (a.rows[k] != 0) s.pos[k] = s.mA++;
  s.N = s.nF + f.me + s.mA;
  return s;
}

// res = r − K0 v of the reduced system, i.e. the dual residual −(P̃x̃ + q̃ + Ẽᵀỹ + G̃_Aᵀζ)
// on the free variables and the primal residuals b̃ − Ẽx̃, h − G̃_A x̃ (x̃ = xb + free
// part of v), accumulated in long double: the refinement then reaches the roundoff of
// the solution rather than that of the residual's terms.
namespace {

void reduced_residual(const StandardForm& f, const ActiveSet& a, const Reduced& s, const Vector& v, Vector& res,
                      std::vector<long double>& acc) {
  const Index n = f.n, me = f.me, nF = s.nF;
  acc.assign(static_cast<size_t>(n + me + f.mg), 0.0L);
  long double* dual = acc.data();
  long double* prim_e = dual + n;
  long double* prim_g = prim_e + me;
  const auto x = [&](Index j) { return s.col[j] >= 0 ? v(s.col[j]) : s.xb(j); };
  for (Index j = 0; j < n; ++j) {
    const long double xj = x(j);
    for (SparseMatrix::InnerIterator e(f.P, j); e; ++e) {
      const Index i = e.row();
      if (i > j) continue;
      dual[i] += static_cast<long double>(e.value()) * xj;
      if (i != j) dual[j] += static_cast<long double>(e.value()) * x(i);
    }
    for (SparseMatrix::InnerIterator e(f.E, j); e; ++e) {
      dual[j] += static_cast<long double>(e.value()) * v(nF + e.row());
      prim_e[e.row()] += static_cast<long double>(e.value()) * xj;
    }
    for (SparseMatrix::InnerIterator e(f.G, j); e; ++e) {
      const Index k = e.row();
      if (s.pos[k] < 0) continue;
      dual[j] += static_cast<long double>(e.value()) * v(nF + me + s.pos[k]);
      prim_g[k] += static_cast<long double>(e.value()) * xj;
    }
  }
  res.resize(s.N);
  for (Index j = 0; j < n; ++j)
    if (s.col[j] >= 0) res(s.col[j]) = static_cast<double>(-(dual[j] + f.q(j)));
  for (Index k = 0; k < me; ++k) res(nF + k) = static_cast<double>(f.be(k) - prim_e[k]);
  for (Index k = 0; k < f.mg; ++k)
    if (s.pos[k] >= 0) res(nF + me + s.pos[k]) = static_cast<double>((a.rows[k] < 0 ? f.gl(k) : f.gu(k)) - prim_g[k]);
}

}  // namespace

// Solves the reduced KKT system of qp_polish.hpp (step 2) from the scaled point `start`
// (the interior iterate's x̃, ỹ and signed row multipliers, or a polished point's). False
// when the factorization fails.
bool solve_reduced(const StandardForm& f, const ScaledPoint& start, const ActiveSet& a, ScaledPoint& out) {
  const Index n = f.n, me = f.me, mg = f.mg;
  const Reduced s = reduce(f, a);
  const Index nF = s.nF, N = s.N;
  // Upper triangle of K_δ: P̃_FF + δI (col keeps the order, so i ≤ j stays above the
  // diagonal), the constraint columns C_Fᵀ to the right of it, and −δI below.
  std::vector<Triplet> t;
  t.reserve(static_cast<size_t>(f.P.nonZeros() + f.E.nonZeros() + f.G.nonZeros() + N));
  for (Index j = 0; j < n; ++j) {
    const Index cj = s.col[j];
    if (cj < 0) continue;
    for (SparseMatrix::InnerIterator e(f.P, j); e; ++e)
      if (e.row() <= j && s.col[e.row()] >= 0) t.emplace_back(s.col[e.row()], cj, e.value());
    for (SparseMatrix::InnerIterator e(f.E, j); e; ++e) t.emplace_back(cj, nF + e.row(), e.value());
    for (SparseMatrix::InnerIterator e(f.G, j); e; ++e)
      if (s.pos[e.row()] >= 0) t.emplace_back(cj, nF + me + s.pos[e.row()], e.value());
  }
  for (Index i = 0; i < N; ++i) t.emplace_back(i, i, i < nF ? kPolishDelta : -kPolishDelta);
  SparseMatrix K(N, N);
  K.setFromTriplets(t.begin(), t.end());
  K.makeCompressed();
  sparse::CholmodLdlt ldlt;
  if (!ldlt.analyze(K).ok() || !ldlt.factorize(K).ok()) return false;

  // Refinement from the interior iterate; keeps the iterate of smallest residual.
  Vector v(N);
  for (Index j = 0; j < n; ++j)
    if (s.col[j] >= 0) v(s.col[j]) = start.x(j);
  for (Index k = 0; k < me; ++k) v(nF + k) = start.y(k);
  for (Index k = 0; k < mg; ++k)
    if (s.pos[k] >= 0) v(nF + me + s.pos[k]) = start.zg(k);
  std::vector<long double> acc;
  Vector res, d;
  reduced_residual(f, a, s, v, res, acc);
  double best = inf_norm(res);
  Vector best_v = v;
  int stalls = 0;
  for (int step = 0; step < kPolishRefinement && best > 0 && stalls < 3; ++step) {
    d = res;
    if (!ldlt.solve(d).ok() || !d.allFinite()) break;
    v += d;
    reduced_residual(f, a, s, v, res, acc);
    const double now = inf_norm(res);
    if (now < best) {
      stalls = now < 0.5 * best ? 0 : stalls + 1;
      best = now;
      best_v = v;
    } else {
      ++stalls;
    }
  }
  out.x = s.xb;
  for (Index j = 0; j < n; ++j)
    if (s.col[j] >= 0) out.x(j) = best_v(s.col[j]);
  out.y = best_v.segment(nF, me);
  out.zg.setZero(mg);
  for (Index k = 0; k < mg; ++k)
    if (s.pos[k] >= 0) out.zg(k) = best_v(nF + me + s.pos[k]);
  return true;
}

}  // namespace lcprelax::detail
