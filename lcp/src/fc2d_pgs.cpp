// Projected Gauss–Seidel for fc2d and the Lemke crash basis (see fc2d_pgs.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/fc2d_pgs.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace lcprelax {
namespace {

struct Block {
  double nn = 0, nt = 0, tn = 0, tt = 0;
};

// The exact solution of u = W_cc r + ũ under Coulomb's law (cases of fc2d_pgs.hpp); false
// when no case holds.
bool solve_local(const Block& b, double un, double ut, double mu, double& rn, double& rt) {
  if (un >= 0) {
    rn = rt = 0.0;
    return true;
  }
  const double det = b.nn * b.tt - b.nt * b.tn;
  if (det > 0) {
    const double sn = -(b.tt * un - b.nt * ut) / det, st = -(-b.tn * un + b.nn * ut) / det;
    if (sn >= 0 && std::abs(st) <= mu * sn) {
      rn = sn;
      rt = st;
      return true;
    }
  }
  for (double s : {1.0, -1.0}) {
    const double den = b.nn - s * mu * b.nt;
    if (!(den > 0)) continue;
    const double n = -un / den, t = -s * mu * n;
    const double slide = b.tn * n + b.tt * t + ut;
    if (n >= 0 && s * slide >= 0) {
      rn = n;
      rt = t;
      return true;
    }
  }
  return false;
}

}  // namespace

Fc2dPgsResult fc2d_pgs(const SparseMatrix& W, const Vector& q, const Vector& mu, int max_sweeps, double tolerance) {
  const Index nc = mu.size();
  if (W.rows() != 2 * nc || W.cols() != 2 * nc || q.size() != 2 * nc)
    throw InputError("fc2d PGS: W must be 2nc×2nc and q of size 2nc for nc = " + std::to_string(nc) + " contacts");
  if (nc > 0 && mu.minCoeff() < 0) throw InputError("fc2d PGS: negative friction coefficient");
  std::vector<Block> blocks(static_cast<std::size_t>(nc));
  for (Index col = 0; col < W.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(W, col); it; ++it) {
      const Index c = col / 2;
      if (it.row() / 2 != c) continue;
      Block& b = blocks[static_cast<std::size_t>(c)];
      const bool rt = it.row() % 2, ct = col % 2;
      (rt ? (ct ? b.tt : b.tn) : (ct ? b.nt : b.nn)) = it.value();
    }
  Fc2dPgsResult out;
  out.r = Vector::Zero(2 * nc);
  out.u = q;
  auto add_column = [&](Index col, double delta) {
    if (delta == 0.0) return;
    for (SparseMatrix::InnerIterator it(W, col); it; ++it) out.u(it.row()) += it.value() * delta;
  };
  for (out.sweeps = 0; out.sweeps < max_sweeps;) {
    ++out.sweeps;
    out.change = 0.0;
    for (Index c = 0; c < nc; ++c) {
      const Block& b = blocks[static_cast<std::size_t>(c)];
      const double rn0 = out.r(2 * c), rt0 = out.r(2 * c + 1);
      const double un = out.u(2 * c) - b.nn * rn0 - b.nt * rt0, ut = out.u(2 * c + 1) - b.tn * rn0 - b.tt * rt0;
      double rn = rn0, rt = rt0;
      if (!solve_local(b, un, ut, mu(c), rn, rt)) continue;
      add_column(2 * c, rn - rn0);
      add_column(2 * c + 1, rt - rt0);
      out.r(2 * c) = rn;
      out.r(2 * c + 1) = rt;
      out.change = std::max({out.change, std::abs(rn - rn0), std::abs(rt - rt0)});
    }
    // Relative to ‖r‖∞ (resting contact has ‖q‖ ~ 1e-19, so no absolute floor).
    if (out.change <= tolerance * (nc ? out.r.lpNorm<Eigen::Infinity>() : 0.0)) break;
  }
  out.u = W * out.r + q;  // fresh, without the drift of the incremental updates
  return out;
}

Vector fc2d_lcp_point(const Vector& r, const Vector& u, const Vector& mu) {
  const Index nc = mu.size();
  if (r.size() != 2 * nc || u.size() != 2 * nc) throw InputError("fc2d LCP point: sizes of r, u and μ disagree");
  Vector z(4 * nc);
  for (Index c = 0; c < nc; ++c) {
    const double rn = std::max(r(2 * c), 0.0), rt = r(2 * c + 1);
    // On the cone's boundary (sliding, or r = 0: separated) w_λ = μr_n − |r_t| = 0 and λ =
    // |u_t| makes w± = λ ± u_t ≥ 0; strictly inside (sticking) λ = 0.
    const bool boundary = std::abs(rt) >= mu(c) * rn * (1.0 - 1e-9);
    z(4 * c) = rn;
    z(4 * c + 1) = std::max(rt, 0.0);
    z(4 * c + 2) = std::max(-rt, 0.0);
    z(4 * c + 3) = boundary ? std::abs(u(2 * c + 1)) : 0.0;
  }
  return z;
}

std::vector<bool> fc2d_basis_guess(const Vector& r, const Vector& u, const Vector& mu, const SparseMatrix& M_lcp,
                                   const Vector& q_lcp) {
  const Index nc = mu.size();
  if (r.size() != 2 * nc || u.size() != 2 * nc || M_lcp.rows() != 4 * nc || q_lcp.size() != 4 * nc)
    throw InputError("fc2d basis guess: sizes of r, u, μ and the LCP disagree");
  Vector z = fc2d_lcp_point(r, u, mu);
  for (Index c = 0; c < nc; ++c)  // λ of separated contacts left at 0 (the crash paths measured so)
    if (!(r(2 * c) > 0)) z(4 * c + 3) = 0.0;
  const Vector w = M_lcp * z + q_lcp;
  std::vector<bool> basis(static_cast<std::size_t>(4 * nc));
  for (Index i = 0; i < 4 * nc; ++i) basis[static_cast<std::size_t>(i)] = z(i) > w(i);
  return basis;
}

LcpResult solve_fc2d_lemke_crash(const SparseMatrix& W, const Vector& q, const Vector& mu, const Fc2dLcp& lcp,
                                 int sweeps, LemkeSettings settings, int* sweeps_done, Fc2dCrash start) {
  const Fc2dPgsResult pgs = fc2d_pgs(W, q, mu, sweeps, 1e-12);
  if (sweeps_done) *sweeps_done = pgs.sweeps;
  settings.crash_start = true;
  LemkeSolver lemke(settings);
  lemke.setup(lcp.M, lcp.q);
  const std::vector<bool> guess = fc2d_basis_guess(pgs.r, pgs.u, mu, lcp.M, lcp.q);
  if (start == Fc2dCrash::purified) lemke.warm_start_point(fc2d_lcp_point(pgs.r, pgs.u, mu), guess);
  else lemke.warm_start(guess);
  return lemke.solve();
}

}  // namespace lcprelax
