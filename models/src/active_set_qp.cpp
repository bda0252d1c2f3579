// The warm-started primal–dual active-set (semismooth Newton) QP solver (active_set_qp.hpp).
#include <lcprelax/models/active_set_qp.hpp>

#include <lcprelax/core/errors.hpp>
#include <lcprelax/sparse/cholmod_ldlt.hpp>
#include <lcprelax/sparse/triplets.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <string>

namespace lcprelax::detail {
namespace {

double dist(double v, double lo, double hi) { return v < lo ? lo - v : (v > hi ? v - hi : 0.0); }

// Clears a state whose side is infinite; an equality (lo == hi) is always active.
ActiveState sanitize(ActiveState s, double lo, double hi) {
  if (lo == hi) return -1;
  if (s < 0 && !std::isfinite(lo)) return 0;
  if (s > 0 && !std::isfinite(hi)) return 0;
  return s;
}

// New state from the value v of a row (or variable) and its multiplier m (active-set step).
ActiveState next_state(ActiveState s, double v, double m, double lo, double hi, double ptol, double stol) {
  if (lo == hi) return -1;
  if (s == 0) {
    if (v < lo - ptol) return -1;
    if (v > hi + ptol) return 1;
    return 0;
  }
  if (s < 0 && m > stol) return 0;  // lower bound needs ν ≤ 0
  if (s > 0 && m < -stol) return 0; // upper bound needs ν ≥ 0
  return s;
}

}  // namespace

ActiveSetResult solve_active_set_qp(const QpProblem& p, std::vector<ActiveState> rows,
                                    std::vector<ActiveState> bounds, const ActiveSetSettings& st,
                                    const Vector* x_feasible) {
  const Index n = p.num_variables(), me = p.num_equalities(), mi = p.num_inequalities();
  if (static_cast<Index>(rows.size()) != mi || static_cast<Index>(bounds.size()) != n)
    throw InputError("solve_active_set_qp: need one state per row of G and per variable");
  ActiveSetResult out;
  // Variables with a finite bound get a KKT row each.
  std::vector<Index> bounded;
  for (Index j = 0; j < n; ++j) {
    bounds[j] = sanitize(bounds[j], p.xl(j), p.xu(j));
    if (std::isfinite(p.xl(j)) || std::isfinite(p.xu(j))) bounded.push_back(j);
  }
  for (Index i = 0; i < mi; ++i) rows[i] = sanitize(rows[i], p.l(i), p.u(i));
  const Index nb = static_cast<Index>(bounded.size());
  const Index cz = n + me, cb = n + me + mi, N = cb + nb;

  double pmax = 1.0;
  for (Index j = 0; j < p.P.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(p.P, j); it; ++it)
      if (it.row() == j) pmax = std::max(pmax, std::abs(it.value()));
  const double dp = st.delta * pmax, dd = st.delta / pmax;

  // K's upper triangle with every constraint active; inactive columns are toggled below.
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(p.P.nonZeros() + p.A.nonZeros() + p.G.nonZeros() + 2 * N));
  append_triplets(t, p.P, 0, 0, 1.0);
  for (Index j = 0; j < n; ++j) t.emplace_back(j, j, dp);
  append_triplets(t, p.A, 0, n, 1.0, /*transpose=*/true);
  append_triplets(t, p.G, 0, cz, 1.0, /*transpose=*/true);
  for (Index k = 0; k < nb; ++k) t.emplace_back(bounded[k], cb + k, 1.0);
  for (Index c = n; c < N; ++c) t.emplace_back(c, c, -dd);
  SparseMatrix K = from_triplets(N, N, t);
  const Vector active_values = Eigen::Map<const Vector>(K.valuePtr(), K.nonZeros());

  // Pivots below 1e-3·min(δp, δd) (cancellation on dependent active rows) are replaced by
  // ±that (CHOLMOD dbound); the refinement and the final KKT check judge the result.
  sparse::CholmodLdlt ldlt(1e-3 * std::min(dp, dd), sparse::CholmodOrdering::amd);
  if (const sparse::FactorResult fr = ldlt.analyze(K); !fr.ok()) {
    out.message = "analyze: " + fr.message;
    return out;
  }
  const double q_scale = std::max(1.0, p.q.cwiseAbs().maxCoeff());
  Vector rhs(N), sol(N), res(N);
  DenseMatrix work(N, 1);
  out.iterations = 0;
  // One equality-constrained QP on the current working set: x, y, z, z_bounds.
  auto solve_eqp = [&]() -> bool {
    ++out.iterations;
    std::copy(active_values.data(), active_values.data() + K.nonZeros(), K.valuePtr());
    rhs.head(n) = -p.q;
    rhs.segment(n, me) = p.b;
    auto set_column = [&](Index c, ActiveState s, double lo, double hi) {
      const Index begin = K.outerIndexPtr()[c], end = K.outerIndexPtr()[c + 1];
      if (s == 0) {
        std::fill(K.valuePtr() + begin, K.valuePtr() + end - 1, 0.0);
        K.valuePtr()[end - 1] = -1.0;  // the diagonal is the last (largest) row of the column
        rhs(c) = 0.0;
      } else {
        rhs(c) = s < 0 ? lo : hi;
      }
    };
    for (Index i = 0; i < mi; ++i) set_column(cz + i, rows[i], p.l(i), p.u(i));
    for (Index k = 0; k < nb; ++k) set_column(cb + k, bounds[bounded[k]], p.xl(bounded[k]), p.xu(bounded[k]));
    if (const sparse::FactorResult fr = ldlt.factorize(K); !fr.ok()) {
      out.message = "factorize: " + fr.message;
      return false;
    }
    auto unregularized_product = [&](const Vector& v, Vector& r) {
      r.noalias() = K.selfadjointView<Eigen::Upper>() * v;
      r.head(n) -= dp * v.head(n);
      r.segment(n, me) += dd * v.segment(n, me);
      for (Index i = 0; i < mi; ++i)
        if (rows[i] != 0) r(cz + i) += dd * v(cz + i);
      for (Index k = 0; k < nb; ++k)
        if (bounds[bounded[k]] != 0) r(cb + k) += dd * v(cb + k);
    };
    work.col(0) = rhs;
    ldlt.solve(work);
    sol = work.col(0);
    for (int r = 0; r < st.refinement_steps; ++r) {
      unregularized_product(sol, res);
      res = rhs - res;
      if (res.cwiseAbs().maxCoeff() <= 1e-3 * st.eps_abs) break;
      work.col(0) = res;
      ldlt.solve(work);
      sol += work.col(0);
    }
    if (!sol.allFinite()) {
      out.message = "non-finite KKT solution";
      return false;
    }
    out.x = sol.head(n);
    out.y = sol.segment(n, me);
    out.z = sol.segment(cz, mi);
    out.z_bounds = Vector::Zero(n);
    for (Index k = 0; k < nb; ++k) out.z_bounds(bounded[k]) = sol(cb + k);
    return true;
  };
  auto violation = [&](const Vector& x, const Vector& g) {
    double v = 0.0;
    for (Index i = 0; i < mi; ++i) v = std::max(v, dist(g(i), p.l(i), p.u(i)));
    for (Index j = 0; j < n; ++j) v = std::max(v, dist(x(j), p.xl(j), p.xu(j)));
    return v;
  };
  auto finish = [&](const Vector& g) {
    double primal = me > 0 ? (p.A * out.x - p.b).cwiseAbs().maxCoeff() : 0.0;
    primal = std::max(primal, violation(out.x, g));
    Vector stat = p.P.selfadjointView<Eigen::Upper>() * out.x + p.q + out.z_bounds;
    if (me > 0) stat.noalias() += p.A.transpose() * out.y;
    if (mi > 0) stat.noalias() += p.G.transpose() * out.z;
    out.primal_residual = primal;
    out.dual_residual = n > 0 ? stat.cwiseAbs().maxCoeff() : 0.0;
    out.rows = rows;
    out.bounds = bounds;
    out.converged = primal <= st.eps_abs && out.dual_residual <= st.eps_abs * q_scale;
    if (!out.converged)
      out.message = "KKT residuals primal " + std::to_string(primal) + ", dual " + std::to_string(out.dual_residual) +
                    " exceed the tolerance";
    return out;
  };
  auto wrong_sign = [&](ActiveState s, double m, double lo, double hi, double stol) {
    return lo != hi && ((s < 0 && m > stol) || (s > 0 && m < -stol));
  };
  const std::vector<ActiveState> rows0 = rows, bounds0 = bounds;

  // 1. Crash: primal–dual active-set steps (semismooth Newton, header comment) from the
  //    guess, up to crash_iterations; the first feasible iterate starts step 2 there (its
  //    working set holds with equality), and is the answer if its multipliers' signs hold.
  bool feasible = false;
  for (int c = 0; c < std::min(st.crash_iterations, st.max_iterations) && !feasible; ++c) {
    if (!solve_eqp()) return out;
    const Vector g = p.G * out.x;
    if (violation(out.x, g) <= st.eps_abs) {
      feasible = true;
      break;
    }
    const double stol = st.sign_tol * std::max(1.0, sol.tail(N - n).cwiseAbs().maxCoeff());
    for (Index i = 0; i < mi; ++i) rows[i] = next_state(rows[i], g(i), out.z(i), p.l(i), p.u(i), st.eps_abs, stol);
    for (Index j = 0; j < n; ++j)
      bounds[j] = next_state(bounds[j], out.x(j), out.z_bounds(j), p.xl(j), p.xu(j), st.eps_abs, stol);
  }
  Vector x;
  if (feasible) {
    x = out.x;
  } else {
    // From the caller's feasible point, with the guessed rows that are active there.
    if (!x_feasible || x_feasible->size() != n) {
      out.message = "crash found no feasible point and none was given";
      return out;
    }
    x = *x_feasible;
    const Vector g = p.G * x;
    if (violation(x, g) > st.eps_abs) {
      out.message = "the given start point is infeasible";
      return out;
    }
    auto at = [&](ActiveState s, double v, double lo, double hi) -> ActiveState {
      if (s < 0 && std::abs(v - lo) <= st.eps_abs) return -1;
      if (s > 0 && std::abs(v - hi) <= st.eps_abs) return 1;
      return 0;
    };
    for (Index i = 0; i < mi; ++i) rows[i] = at(rows0[i], g(i), p.l(i), p.u(i));
    for (Index j = 0; j < n; ++j) bounds[j] = at(bounds0[j], x(j), p.xl(j), p.xu(j));
    if (!solve_eqp()) return out;
  }

  // 2. Primal feasible active-set method (Nocedal & Wright 2006, Alg. 16.3) from x: step
  //    toward the working set's minimizer up to the first blocking row, which joins the
  //    working set; at the minimizer, every row whose multiplier has the wrong sign leaves
  //    it (all at once: the objective still decreases, the next minimizer being optimal on
  //    a larger set that contains x). The latest out.x/z are the working set's minimizer.
  while (true) {
    const Vector d = out.x - x;
    const Vector gx = p.G * x, gd = p.G * d;
    double alpha = 1.0;
    auto ratio = [&](ActiveState s, double v, double dv, double lo, double hi) {
      if (s != 0) return 1.0;
      if (dv < 0 && std::isfinite(lo)) return std::max(0.0, (lo - v) / dv);
      if (dv > 0 && std::isfinite(hi)) return std::max(0.0, (hi - v) / dv);
      return 1.0;
    };
    for (Index i = 0; i < mi; ++i) alpha = std::min(alpha, ratio(rows[i], gx(i), gd(i), p.l(i), p.u(i)));
    for (Index j = 0; j < n; ++j) alpha = std::min(alpha, ratio(bounds[j], x(j), d(j), p.xl(j), p.xu(j)));
    bool changed = false;
    if (alpha < 1.0) {
      x += alpha * d;
      const double cut = alpha * (1.0 + 1e-12) + 1e-15;
      for (Index i = 0; i < mi; ++i)
        if (rows[i] == 0 && ratio(0, gx(i), gd(i), p.l(i), p.u(i)) <= cut) rows[i] = gd(i) < 0 ? -1 : 1, changed = true;
      for (Index j = 0; j < n; ++j)
        if (bounds[j] == 0 && ratio(0, x(j) - alpha * d(j), d(j), p.xl(j), p.xu(j)) <= cut)
          bounds[j] = d(j) < 0 ? -1 : 1, changed = true;
    } else {
      x = out.x;
      const double stol = st.sign_tol * std::max(1.0, std::max(out.z.size() ? out.z.cwiseAbs().maxCoeff() : 0.0,
                                                                out.z_bounds.cwiseAbs().maxCoeff()));
      for (Index i = 0; i < mi; ++i)
        if (wrong_sign(rows[i], out.z(i), p.l(i), p.u(i), stol)) rows[i] = 0, changed = true;
      for (Index j = 0; j < n; ++j)
        if (wrong_sign(bounds[j], out.z_bounds(j), p.xl(j), p.xu(j), stol)) bounds[j] = 0, changed = true;
      if (!changed) return finish(p.G * out.x);
    }
    if (!changed) {  // a blocking row that is already in the set: numerical trouble
      out.message = "no progress (step " + std::to_string(alpha) + ")";
      return out;
    }
    if (out.iterations >= st.max_iterations) {
      out.message = "no optimal working set within " + std::to_string(st.max_iterations) + " iterations (crash " +
                    (feasible ? "feasible" : "infeasible") + ")";
      out.rows = rows;
      out.bounds = bounds;
      return out;
    }
    if (!solve_eqp()) return out;
  }
}

}  // namespace lcprelax::detail
