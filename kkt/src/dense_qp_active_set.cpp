// DenseQpSolver's first method for strictly convex problems: the dual active-set method of
// Goldfarb & Idnani ("A numerically stable dual method for solving strictly convex
// quadratic programs", Math. Programming 27, 1983). Starting from the unconstrained minimum
// x = −P⁻¹q, it adds the equality rows, then repeatedly the most violated inequality side,
// dropping active sides whose multiplier would turn negative; every iterate is dual
// feasible, so the first primal feasible one is optimal. Factors: P = LLᵀ, J = L⁻ᵀQ and
// the upper triangular R with QᵀL⁻¹N = [R; 0] for the active normals N, both updated by
// Givens rotations when a side enters or leaves (O(n²) per change).
//
// Internal multipliers follow the interior point's convention (dense_qp_impl.hpp):
// Px + q = Aeᵀy' + Cᵀλ, λ ≥ 0. The result is exact up to roundoff; it is accepted only if
// the unscaled residual test of qp_settings.hpp passes (else the interior point runs).
#include "dense_qp_impl.hpp"

#include <algorithm>
#include <cmath>

namespace lcprelax {
namespace dense_qp_active_set_detail {

// Rotation (c, s) with c·a + s·b = hypot(a, b), −s·a + c·b = 0.
struct Givens {
  double c = 1.0, s = 0.0;
  static Givens zeroing(double a, double b) {
    const double h = std::hypot(a, b);
    if (h == 0.0) return {};
    return {a / h, b / h};
  }
};

// Columns j and k of M rotated: (M_j, M_k) ← (c M_j + s M_k, −s M_j + c M_k).
void rotate_columns(DenseMatrix& M, Index j, Index k, const Givens& g) {
  for (Index i = 0; i < M.rows(); ++i) {
    const double a = M(i, j), b = M(i, k);
    M(i, j) = g.c * a + g.s * b;
    M(i, k) = -g.s * a + g.c * b;
  }
}

}  // namespace dense_qp_active_set_detail

using namespace dense_qp_active_set_detail;

bool DenseQpSolver::Impl::run_active_set() {
  // P = LLᵀ (fails unless P is positive definite: the method needs strict convexity).
  if (!p_factor_ready) {
    if (!llt_P.compute(P)) return false;
    J0.setZero(n, n);  // L⁻ᵀ
    for (Index j = 0; j < n; ++j) {
      auto col = J0.col(j);
      col(j) = 1.0;
      llt_P.solve_upper(col);
    }
    p_factor_ready = true;
  }
  J = J0;
  R.setZero(n, n);
  as_index.clear();
  as_u.setZero(n);
  as_active.assign(static_cast<std::size_t>(mc), 0);
  Index q = 0;
  // Unconstrained minimum.
  x = -problem.q;
  llt_P.solve_in_place(x);

  // Normal of constraint `c` (≥ 0: side c; < 0: equality row −1 − c) into as_normal.
  auto normal = [&](Index c) {
    if (c < 0) {
      as_normal = Ae.row(-1 - c).transpose();
      return;
    }
    const Side& sd = sides[static_cast<std::size_t>(c)];
    if (sd.on_g_row) {
      as_normal = sd.sign * Gi.row(sd.gi_row).transpose();
    } else {
      as_normal.setZero();
      as_normal(sd.index) = sd.sign;
    }
  };
  auto slack = [&](Index c) { return c < 0 ? as_normal.dot(x) - be(-1 - c) : as_normal.dot(x) - d(c); };
  // d = Jᵀn, z = J₂d₂ (primal direction), r = R⁻¹d₁ (how the active multipliers change).
  auto directions = [&]() {
    as_d.noalias() = J.transpose() * as_normal;
    as_z.noalias() = J.rightCols(n - q) * as_d.tail(n - q);
    for (Index i = q - 1; i >= 0; --i) {
      double v = as_d(i);
      for (Index k = i + 1; k < q; ++k) v -= R(i, k) * as_r(k);
      as_r(i) = v / R(i, i);
    }
  };
  // Adds the constraint whose d = Jᵀn is in as_d: rotations zero d's tail into d(q).
  auto add = [&](Index c) {
    for (Index j = n - 1; j > q; --j) {
      const Givens g = Givens::zeroing(as_d(j - 1), as_d(j));
      if (g.s == 0.0) continue;
      as_d(j - 1) = g.c * as_d(j - 1) + g.s * as_d(j);
      as_d(j) = 0.0;
      rotate_columns(J, j - 1, j, g);
    }
    R.col(q).head(q + 1) = as_d.head(q + 1);
    as_index.push_back(c);
    ++q;
  };
  // Drops the active constraint at position l: R's columns shift left, rotations of rows
  // (and of J's columns) restore the triangle.
  auto drop = [&](Index l) {
    for (Index k = l; k + 1 < q; ++k) {
      R.col(k) = R.col(k + 1);
      as_u(k) = as_u(k + 1);
      as_index[static_cast<std::size_t>(k)] = as_index[static_cast<std::size_t>(k + 1)];
    }
    as_index.pop_back();
    R.col(q - 1).setZero();
    as_u(q - 1) = 0.0;
    --q;
    for (Index j = l; j < q; ++j) {
      const Givens g = Givens::zeroing(R(j, j), R(j + 1, j));
      if (g.s == 0.0) continue;
      for (Index k = j; k < q; ++k) {
        const double a = R(j, k), b = R(j + 1, k);
        R(j, k) = g.c * a + g.s * b;
        R(j + 1, k) = -g.s * a + g.c * b;
      }
      R(j + 1, j) = 0.0;
      rotate_columns(J, j, j + 1, g);
    }
  };
  const double tiny = 1e-14;
  const double scale_x = 1.0 + (n > 0 ? P.cwiseAbs().maxCoeff() : 0.0);
  // ‖c_k‖₁ of each side, for the feasibility tolerance 1e-13·(1 + |d_k| + ‖c_k‖₁‖x‖∞).
  for (Index k = 0; k < mc; ++k) {
    const Side& sd = sides[static_cast<std::size_t>(k)];
    side_norm1(k) = sd.on_g_row ? Gi.row(sd.gi_row).cwiseAbs().sum() : 1.0;
  }
  double x_norm = 0.0;

  // Equality rows: full steps of either sign; never dropped.
  for (Index r = 0; r < me; ++r) {
    if (q >= n) return false;
    normal(-1 - r);
    directions();
    const double zn = as_z.dot(as_normal);
    if (!(std::abs(zn) > tiny * scale_x * as_normal.squaredNorm())) return false;  // dependent rows
    const double t = -slack(-1 - r) / zn;
    x += t * as_z;
    as_u.head(q) -= t * as_r.head(q);
    add(-1 - r);
    as_u(q - 1) = t;
  }

  // Inequality sides: the most violated one enters.
  const int max_changes = static_cast<int>(10 * (mc + me) + 20);
  int changes = 0;
  for (;;) {
    x_norm = n > 0 ? x.cwiseAbs().maxCoeff() : 0.0;
    Index p = -1;
    double worst = 0.0;
    apply_C(x, cx);
    for (Index k = 0; k < mc; ++k) {
      if (as_active[static_cast<std::size_t>(k)]) continue;
      const double sk = cx(k) - d(k);
      const double tol = 1e-13 * (1.0 + std::abs(d(k)) + side_norm1(k) * x_norm);
      if (sk < -tol && sk < worst) worst = sk, p = k;
    }
    if (p < 0) break;  // primal feasible: optimal
    normal(p);
    double u_plus = 0.0;
    for (;;) {
      if (++changes > max_changes) return false;
      directions();
      // Partial step: the first active inequality whose multiplier reaches 0.
      double t1 = std::numeric_limits<double>::infinity();
      Index l = -1;
      for (Index k = 0; k < q; ++k)
        if (as_index[static_cast<std::size_t>(k)] >= 0 && as_r(k) > tiny && as_u(k) / as_r(k) < t1)
          t1 = as_u(k) / as_r(k), l = k;
      const double zn = as_z.dot(as_normal);
      const bool z_zero = !(std::abs(zn) > tiny * scale_x * as_normal.squaredNorm());
      const double t2 = z_zero ? std::numeric_limits<double>::infinity() : -slack(p) / zn;
      const double t = std::min(t1, t2);
      if (!std::isfinite(t)) return false;  // infeasible: QpSolver gives the certificate
      if (!z_zero) x += t * as_z;
      as_u.head(q) -= t * as_r.head(q);
      u_plus += t;
      if (t == t2) {
        add(p);
        as_u(q - 1) = u_plus;
        as_active[static_cast<std::size_t>(p)] = 1;
        break;
      }
      as_active[static_cast<std::size_t>(as_index[static_cast<std::size_t>(l)])] = 0;
      drop(l);
      normal(p);  // (unchanged; kept explicit)
    }
  }

  // Internal iterate: y' for the equality rows, λ and s for the sides.
  y.setZero(), lam.setZero();
  for (Index k = 0; k < q; ++k) {
    const Index c = as_index[static_cast<std::size_t>(k)];
    if (c < 0)
      y(-1 - c) = as_u(k);
    else
      lam(c) = std::max(as_u(k), 0.0);
  }
  apply_C(x, cx);
  s = (cx - d).cwiseMax(0.0);
  result.info.iterations = changes;
  return x.allFinite() && y.allFinite() && lam.allFinite();
}

}  // namespace lcprelax
