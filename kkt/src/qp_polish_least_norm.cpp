// Step 3c of polishing (qp_polish.hpp): the least-norm multipliers of the polished point's
// active set. Conventions (qp_problem.hpp): Px + q + Aᵀy + Gᵀz + z_bounds = 0, z ≤ 0 at an
// active lower side and z ≥ 0 at an active upper one (the same for z_bounds).
//
// With x fixed, the multipliers w = (y, z_A, z_B) of the active sides satisfy M w = t,
// t = −(Px + q), M = [Aᵀ G_Aᵀ I_B] (n × k), and signs on the inequality sides. Where that set
// is unbounded (implicit equalities: a row active at both a lower and an upper side through
// other rows, degenerate vertices) the interior point's multipliers follow the analytic
// centre and grow without bound as μ → 0; the terms of the duality gap and of the dual
// residual then carry roundoff u·|w| far above the tolerance (QETAMACR: |z| ~ 1e10 where a
// vertex dual has 5e4). The least-norm element of the set is found by the active-set method
// for least-distance problems (Lawson & Hanson, "Solving Least Squares Problems", 1974,
// ch. 23): from the current feasible w0, the unconstrained minimizer w1 = argmin{‖w‖ : M w =
// t, w_Z = 0} (Z: components pinned at 0); the step w0 + τ(w1 − w0) with the largest τ ≤ 1
// that keeps every sign (‖w‖ decreases along it, since w1 is the minimizer on that affine
// set); the components that block are pinned and the next round starts there.
//
// w1 solves the quasi-definite system [δI M; Mᵀ −I] (u, w) = (t, 0) (w = Mᵀu, MMᵀu + δu = t),
// factorized by CHOLMOD LDLᵀ with δ = kLeastNormDelta·max|M|², refined on the unregularized
// system (the proximal point iteration: it converges to the least-norm solution when M w = t
// is consistent) with the residual accumulated in long double. Allocates.
#include "qp_polish.hpp"

#include <lcprelax/sparse/cholmod_ldlt.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace lcprelax::detail {
namespace {

// One unknown multiplier: kind 0 y_i (row i of A), 1 z_i (row i of G), 2 z_b,j; sign 0 free,
// −1 ≤ 0, +1 ≥ 0.
struct Unknown {
  int kind;
  Index index;
  signed char sign;
};

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// r = (t − M w, w − Mᵀu) in long double, over the unpinned unknowns (pinned w entries are 0);
// returns ‖r‖∞ and sets `stationarity` to ‖t − M w‖∞.
double least_norm_residual(const RowMajor& Ar, const RowMajor& Gr, const std::vector<Unknown>& unk,
                           const std::vector<char>& pinned, const std::vector<long double>& t, const Vector& v, Index n,
                           Vector& res, std::vector<long double>& acc, double& stationarity) {
  const Index k = static_cast<Index>(unk.size());
  acc.assign(t.begin(), t.end());
  res.resize(n + k);
  for (Index c = 0; c < k; ++c) {
    const Unknown& e = unk[c];
    const long double wc = pinned[c] ? 0.0L : static_cast<long double>(v(n + c));
    long double mtu = 0.0L;
    if (e.kind == 2) {
      acc[e.index] -= wc;
      mtu = v(e.index);
    } else {
      const RowMajor& R = e.kind == 0 ? Ar : Gr;
      for (RowMajor::InnerIterator it(R, e.index); it; ++it) {
        acc[it.col()] -= static_cast<long double>(it.value()) * wc;
        mtu += static_cast<long double>(it.value()) * v(it.col());
      }
    }
    res(n + c) = pinned[c] ? 0.0 : static_cast<double>(wc - mtu);
  }
  double worst = 0.0;
  for (Index j = 0; j < n; ++j) {
    res(j) = static_cast<double>(acc[j]);
    worst = std::max(worst, std::abs(res(j)));
  }
  stationarity = worst;
  for (Index c = 0; c < k; ++c) worst = std::max(worst, std::abs(res(n + c)));
  return worst;
}

// w1 of the header comment into w (size k); false when the factorization fails or the
// refinement does not bring ‖t − M w‖∞ below `tol` (inconsistent or too ill-conditioned).
bool least_norm_solve(const RowMajor& Ar, const RowMajor& Gr, const std::vector<Unknown>& unk,
                      const std::vector<char>& pinned, const std::vector<long double>& t, Index n, double tol, Vector& w) {
  const Index k = static_cast<Index>(unk.size());
  double mmax = 1.0;
  std::vector<Triplet> trip;
  for (Index c = 0; c < k; ++c) {
    if (pinned[c]) continue;
    const Unknown& e = unk[c];
    if (e.kind == 2) {
      trip.emplace_back(e.index, n + c, 1.0);
      continue;
    }
    for (RowMajor::InnerIterator it(e.kind == 0 ? Ar : Gr, e.index); it; ++it) {
      trip.emplace_back(it.col(), n + c, it.value());
      mmax = std::max(mmax, std::abs(it.value()));
    }
  }
  const double delta = kLeastNormDelta * mmax * mmax;
  for (Index j = 0; j < n; ++j) trip.emplace_back(j, j, delta);
  for (Index c = 0; c < k; ++c) trip.emplace_back(n + c, n + c, -1.0);
  SparseMatrix K(n + k, n + k);
  K.setFromTriplets(trip.begin(), trip.end());
  K.makeCompressed();
  sparse::CholmodLdlt ldlt;
  if (!ldlt.analyze(K).ok() || !ldlt.factorize(K).ok()) return false;
  Vector v = Vector::Zero(n + k), res, d;
  std::vector<long double> acc;
  double stat = 0.0, best_stat = 0.0;
  bool improved = false;
  double now = least_norm_residual(Ar, Gr, unk, pinned, t, v, n, res, acc, stat);
  double best = now;
  Vector best_v = v;
  for (int step = 0; step < kLeastNormRefinement && now > 0.0; ++step) {
    d = res;
    if (!ldlt.solve(d).ok() || !d.allFinite()) break;
    v += d;
    for (Index c = 0; c < k; ++c)
      if (pinned[c]) v(n + c) = 0.0;
    now = least_norm_residual(Ar, Gr, unk, pinned, t, v, n, res, acc, stat);
    if (now < best) {
      best = now;
      best_stat = stat;
      best_v = v;
      improved = true;
    } else if (now > 0.5 * best && step > 2) {
      break;
    }
  }
  if (!improved) return false;
  // Stationarity-only steps (right-hand side (t − M w, 0)): the second block's residual
  // w − Mᵀu carries the roundoff of the large u and would keep the first from falling further.
  v = best_v;
  least_norm_residual(Ar, Gr, unk, pinned, t, v, n, res, acc, stat);
  for (int step = 0; step < kLeastNormRefinement && stat > 0.0; ++step) {
    d = res;
    d.tail(k).setZero();
    if (!ldlt.solve(d).ok() || !d.allFinite()) break;
    v += d;
    for (Index c = 0; c < k; ++c)
      if (pinned[c]) v(n + c) = 0.0;
    least_norm_residual(Ar, Gr, unk, pinned, t, v, n, res, acc, stat);
    if (stat < best_stat) {
      const bool fast = stat < 0.5 * best_stat;
      best_stat = stat;
      best_v = v;
      if (!fast) break;
    } else {
      break;
    }
  }
  if (!(best_stat <= tol)) return false;
  w = best_v.tail(k);
  return true;
}

}  // namespace

bool least_norm_multipliers(const StandardForm& f, const QpProblem& p, const std::vector<signed char>& rows,
                            const std::vector<signed char>& bounds, double tol_d, QpResult& cand) {
  const Index n = f.n;
  std::vector<Unknown> unk;
  for (Index i = 0; i < p.num_equalities(); ++i) unk.push_back({0, i, 0});
  for (Index i = 0; i < p.num_inequalities(); ++i)
    if (f.g_eq_row[i] >= 0) unk.push_back({1, i, 0});
  for (Index k = 0; k < f.mg; ++k)
    if (rows[k] != 0) unk.push_back({1, f.g_index[k], rows[k]});
  for (Index j = 0; j < n; ++j) {
    if (f.fixed_eq_row[j] >= 0) unk.push_back({2, j, 0});
    else if (bounds[j] != 0) unk.push_back({2, j, bounds[j]});
  }
  const Index k = static_cast<Index>(unk.size());
  if (k == 0) return false;
  const RowMajor Ar = p.A, Gr = p.G;
  // t = −(Px + q), in long double.
  std::vector<long double> t(static_cast<size_t>(n), 0.0L);
  for (Index j = 0; j < n; ++j) {
    for (SparseMatrix::InnerIterator e(p.P, j); e; ++e) {
      const Index i = e.row();
      if (i > j) continue;
      t[i] -= static_cast<long double>(e.value()) * cand.x(j);
      if (i != j) t[j] -= static_cast<long double>(e.value()) * cand.x(i);
    }
    t[j] -= p.q(j);
  }
  auto value = [&](const Unknown& e) -> double& {
    return e.kind == 0 ? cand.y(e.index) : e.kind == 1 ? cand.z(e.index) : cand.z_bounds(e.index);
  };
  Vector w0(k);
  for (Index c = 0; c < k; ++c) w0(c) = value(unk[c]);
  const double norm0 = w0.lpNorm<Eigen::Infinity>();
  std::vector<char> pinned(static_cast<size_t>(k), 0);
  // The solves may leave a stationarity error up to that of w0 (x's own roundoff) or tol_d.
  double stat0 = 0.0;
  {
    Vector v0 = Vector::Zero(n + k), res;
    v0.tail(k) = w0;
    std::vector<long double> acc;
    least_norm_residual(Ar, Gr, unk, pinned, t, v0, n, res, acc, stat0);
  }
  const double tol = std::max(tol_d, kLeastNormStationarity * stat0);
  Vector w1;
  bool moved = false;
  for (int round = 0; round < kLeastNormRounds; ++round) {
    if (!least_norm_solve(Ar, Gr, unk, pinned, t, n, tol, w1)) break;
    // Largest τ ≤ 1 keeping every sign; the blocking components get pinned.
    double tau = 1.0;
    for (Index c = 0; c < k; ++c) {
      const signed char s = unk[c].sign;
      if (s == 0 || pinned[c]) continue;
      const double a = s * w0(c), b = s * w1(c);  // a ≥ 0 must stay ≥ 0
      if (b < 0.0) tau = std::min(tau, std::max(a, 0.0) / (std::max(a, 0.0) - b));
    }
    const Vector step = w1 - w0;
    if (tau > 0.0) {
      w0 += tau * step;
      moved = true;
    }
    if (tau >= 1.0) break;
    bool pinned_any = false;
    for (Index c = 0; c < k; ++c) {
      const signed char s = unk[c].sign;
      if (s == 0 || pinned[c]) continue;
      if (s * w0(c) <= 0.0 && s * step(c) < 0.0) {
        w0(c) = 0.0;
        pinned[c] = 1;
        pinned_any = true;
      }
    }
    if (!pinned_any) break;
  }
  if (moved) {
    // A final correction of least norm restores stationarity where the blend kept a part of
    // the interior point's error: M Δ = t − M w0 over the unknowns not at 0 (those stay).
    std::vector<char> zero(static_cast<size_t>(k), 0);
    for (Index c = 0; c < k; ++c) zero[c] = pinned[c] || (unk[c].sign != 0 && w0(c) == 0.0);
    Vector v0 = Vector::Zero(n + k), res, delta;
    v0.tail(k) = w0;
    std::vector<long double> acc;
    double stat = 0.0;
    least_norm_residual(Ar, Gr, unk, zero, t, v0, n, res, acc, stat);
    const std::vector<long double> r(res.data(), res.data() + n);
    if (stat > 0.0 && least_norm_solve(Ar, Gr, unk, zero, r, n, 0.5 * stat, delta))
      for (Index c = 0; c < k; ++c) {
        if (zero[c]) continue;
        const double v = w0(c) + delta(c);
        w0(c) = (unk[c].sign != 0 && unk[c].sign * v < 0.0) ? 0.0 : v;
      }
  }
  if (!moved || !(w0.lpNorm<Eigen::Infinity>() < norm0)) return false;
  for (Index c = 0; c < k; ++c) {
    const signed char s = unk[c].sign;
    value(unk[c]) = (s != 0 && s * w0(c) < 0.0) ? 0.0 : w0(c);
  }
  return true;
}

}  // namespace lcprelax::detail
