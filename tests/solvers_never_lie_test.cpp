// "Solvers never lie" (issue 19): over seeded random sparse QPs and LCPs of several sizes and
// conditionings, every result the interior-point QP, Lemke or the LCP interior point calls
// `solved` passes an independent residual check in long double, and no `solved` result has a
// non-finite number. The check is written here from the problem statement alone
// (qp_problem.hpp, lcp_types.hpp), not from the solvers' residual code:
//   QP  primal  max(|Ax − b|, dist(Gx, [l, u]), dist(x, [xl, xu]))          ≤ tol·(1 + data)
//       dual    |Px + q + Aᵀy + Gᵀz + z_bounds|                             ≤ tol·(1 + data)
//       signs   z_i > 0 only with u_i finite, z_i < 0 only with l_i finite (same for bounds)
//       complementarity  z_i⁺·(u_i − G_i x) and z_i⁻·(G_i x − l_i)         ≤ tol·(1 + data)
//   LCP z ≥ −tol, w = Mz + q ≥ −tol, |min(z_i, w_i)| ≤ tol·(1 + ‖q‖∞), w as returned ≈ Mz + q
// with tol = 1e-6 (the solvers stop at 1e-9 to 1e-8: three orders of slack for the
// unscaled, long-double recomputation) and "data" the largest magnitude of the terms summed.
// Ill-conditioned and nonconvex draws may end in any other status or an InputError
// (nonconvex P must never be solved). Run time: a few seconds.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/lcp/lcp_ipm.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

using Real = long double;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr Real kTol = 1e-6L;

// y = M·x in long double, with the largest |term| of each row in `scale`.
std::vector<Real> multiply(const SparseMatrix& M, const Vector& x, std::vector<Real>& scale, bool transpose = false) {
  std::vector<Real> y(static_cast<std::size_t>(transpose ? M.cols() : M.rows()), 0.0L);
  scale.assign(y.size(), 0.0L);
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
      const Index out = transpose ? j : it.row(), in = transpose ? it.row() : j;
      const Real term = static_cast<Real>(it.value()) * static_cast<Real>(x(in));
      y[static_cast<std::size_t>(out)] += term;
      scale[static_cast<std::size_t>(out)] = std::max(scale[static_cast<std::size_t>(out)], std::fabs(term));
    }
  return y;
}

// Distance of v from [lo, hi].
Real distance(Real v, double lo, double hi) {
  if (v < lo) return lo - v;
  if (v > hi) return v - hi;
  return 0.0L;
}

bool all_finite(const QpResult& r) {
  return r.x.allFinite() && r.y.allFinite() && r.z.allFinite() && r.z_bounds.allFinite() &&
         std::isfinite(r.info.objective);
}

// The independent optimality check of the header comment; empty when it passes.
std::string qp_violation(const QpProblem& p, const QpResult& r) {
  if (!all_finite(r)) return "non-finite entry in a solved result";
  const Index n = p.num_variables();
  std::vector<Real> sc;
  // Primal feasibility.
  const std::vector<Real> ax = multiply(p.A, r.x, sc);
  for (Index i = 0; i < p.A.rows(); ++i)
    if (std::fabs(ax[i] - p.b(i)) > kTol * (1 + sc[i] + std::fabs(p.b(i)))) return "Ax != b at row " + std::to_string(i);
  std::vector<Real> gsc;
  const std::vector<Real> gx = multiply(p.G, r.x, gsc);
  for (Index i = 0; i < p.G.rows(); ++i)
    if (distance(gx[i], p.l(i), p.u(i)) > kTol * (1 + gsc[i])) return "Gx outside [l, u] at row " + std::to_string(i);
  for (Index j = 0; j < n; ++j)
    if (distance(r.x(j), p.xl(j), p.xu(j)) > kTol * (1 + std::fabs(r.x(j)))) return "x outside bounds at " + std::to_string(j);
  // Dual residual Px + q + Aᵀy + Gᵀz + z_bounds (P from its upper triangle).
  std::vector<Real> d(static_cast<std::size_t>(n), 0.0L), ds(static_cast<std::size_t>(n), 0.0L);
  auto add = [&](Index j, Real term) {
    d[j] += term;
    ds[j] = std::max(ds[j], std::fabs(term));
  };
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(p.P, j); it; ++it) {
      add(it.row(), static_cast<Real>(it.value()) * r.x(j));
      if (it.row() != j) add(j, static_cast<Real>(it.value()) * r.x(it.row()));
    }
  for (Index j = 0; j < n; ++j) add(j, p.q(j)), add(j, r.z_bounds(j));
  for (Index j = 0; j < p.A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(p.A, j); it; ++it) add(j, static_cast<Real>(it.value()) * r.y(it.row()));
  for (Index j = 0; j < p.G.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(p.G, j); it; ++it) add(j, static_cast<Real>(it.value()) * r.z(it.row()));
  for (Index j = 0; j < n; ++j)
    if (std::fabs(d[j]) > kTol * (1 + ds[j])) return "dual residual at " + std::to_string(j);
  // Signs and complementarity: rows, then bounds.
  auto side_check = [&](Real v, double lo, double hi, Real mult, Real scale) -> bool {
    const Real t = kTol * (1 + scale + std::fabs(mult));
    if (mult > t && hi == kInf) return false;
    if (mult < -t && lo == -kInf) return false;
    if (mult > 0 && hi != kInf && mult * (hi - v) > t) return false;
    if (mult < 0 && lo != -kInf && -mult * (v - lo) > t) return false;
    return true;
  };
  for (Index i = 0; i < p.G.rows(); ++i)
    if (!side_check(gx[i], p.l(i), p.u(i), r.z(i), gsc[i])) return "row multiplier sign/complementarity at " + std::to_string(i);
  for (Index j = 0; j < n; ++j)
    if (!side_check(r.x(j), p.xl(j), p.xu(j), r.z_bounds(j), std::fabs(r.x(j))))
      return "bound multiplier sign/complementarity at " + std::to_string(j);
  return {};
}

SparseMatrix random_sparse(std::mt19937& rng, Index rows, Index cols, int per_row, double spread) {
  std::uniform_int_distribution<Index> col(0, cols - 1);
  std::uniform_real_distribution<double> val(-1.0, 1.0), exponent(-spread, spread);
  std::vector<Triplet> t;
  for (Index i = 0; i < rows; ++i)
    for (int k = 0; k < per_row; ++k) t.emplace_back(i, col(rng), val(rng) * std::pow(10.0, exponent(rng)));
  SparseMatrix M(rows, cols);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

// A random QP: P = BᵀDB (rank(B) may be < n: PSD singular; rank 0: an LP), rows around a
// point x0 (feasible) or, for some seeds, shifted bounds (possibly infeasible), conditioning
// 10^±spread in the entries.
QpProblem random_qp(unsigned seed, Index n, double spread, bool nonconvex) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.05, 1.0);
  std::uniform_int_distribution<int> kind(0, 3);
  QpProblem p(n);
  const Index rank = seed % 5 == 0 && !nonconvex ? 0 : std::max<Index>(1, n - static_cast<Index>(seed % 3) * n / 3);
  const SparseMatrix B = random_sparse(rng, rank, n, 3, spread);
  SparseMatrix P = SparseMatrix(B.transpose()) * B;
  if (nonconvex) {  // [1 −.6 −.6; −.6 1 −.6; −.6 −.6 1] (eigenvalue −0.2; every 2×2 minor > 0)
    const Index k = static_cast<Index>(seed) % (n - 2);
    std::vector<Triplet> t;
    for (Index a = 0; a < 3; ++a)
      for (Index b = 0; b < 3; ++b) t.emplace_back(k + a, k + b, a == b ? 1.0 : -0.6);
    P.resize(n, n);
    P.setFromTriplets(t.begin(), t.end());
  }
  p.P = P.triangularView<Eigen::Upper>();
  const Vector x0 = Vector::NullaryExpr(n, [&](Index) { return u(rng); });
  p.q = Vector::NullaryExpr(n, [&](Index) { return u(rng) * std::pow(10.0, spread * u(rng)); });
  p.A = random_sparse(rng, n / 8, n, 3, spread);
  p.b = p.A * x0;
  p.G = random_sparse(rng, n / 2, n, 3, spread);
  const Vector gx = p.G * x0;
  const double shift = seed % 7 == 0 ? 2.0 : 0.0;  // may make the rows infeasible
  p.l = gx - Vector::NullaryExpr(gx.size(), [&](Index) { return pos(rng); }) + Vector::Constant(gx.size(), shift);
  p.u = gx + Vector::NullaryExpr(gx.size(), [&](Index) { return pos(rng); }) + Vector::Constant(gx.size(), shift);
  for (Index i = 0; i < gx.size(); ++i) {
    const int k = kind(rng);
    if (k == 1) p.l(i) = -kInf;
    if (k == 2) p.u(i) = kInf;
  }
  for (Index j = 0; j < n; ++j) {
    const int k = kind(rng);
    if (k >= 1 || rank == 0) p.xl(j) = x0(j) - pos(rng);  // an LP gets bounds (else unbounded)
    if (k >= 2 || rank == 0) p.xu(j) = x0(j) + pos(rng);
  }
  return p;
}

TEST(SolversNeverLie, EverySolvedQpPassesTheLongDoubleCheck) {
  int solved = 0, refused = 0, total = 0, nonconvex_draws = 0;
  for (Index n : {4, 12, 40, 120, 300})
    for (double spread : {0.0, 1.5, 3.0})
      for (unsigned seed = 1; seed <= 12; ++seed) {
        const bool nonconvex = seed % 6 == 0;
        const QpProblem p = random_qp(seed * 131 + static_cast<unsigned>(n), n, spread, nonconvex);
        SCOPED_TRACE("n " + std::to_string(n) + ", spread " + std::to_string(spread) + ", seed " + std::to_string(seed));
        ++total;
        nonconvex_draws += nonconvex;
        QpSolver solver;
        try {
          solver.setup(p);
        } catch (const InputError& e) {
          ++refused;
          EXPECT_TRUE(nonconvex) << e.what();
          continue;
        }
        const QpResult& r = solver.solve();
        EXPECT_FALSE(nonconvex && has_solution(r.info.status)) << "a nonconvex QP was accepted and solved";
        if (r.info.status != QpStatus::solved) continue;
        ++solved;
        EXPECT_EQ(qp_violation(p, r), "");
      }
  EXPECT_GE(solved, (total - nonconvex_draws) / 2);  // the check is not vacuous (measured: 88 of 150)
  EXPECT_EQ(refused, nonconvex_draws);  // every nonconvex P refused at setup
  std::printf("QPs: %d drawn, %d solved and checked, %d refused as nonconvex\n", total, solved, refused);
}

// The independent LCP check of the header comment; empty when it passes.
std::string lcp_violation(const SparseMatrix& M, const Vector& q, const LcpResult& r) {
  if (!r.z.allFinite() || !r.w.allFinite()) return "non-finite z or w in a solved result";
  std::vector<Real> sc;
  const std::vector<Real> mz = multiply(M, r.z, sc);
  const Real qn = q.size() ? q.cwiseAbs().maxCoeff() : 0.0;
  for (Index i = 0; i < q.size(); ++i) {
    const Real w = mz[i] + q(i), t = kTol * (1 + qn + sc[i]);
    if (r.z(i) < -t) return "z < 0 at " + std::to_string(i);
    if (w < -t) return "w < 0 at " + std::to_string(i);
    if (std::min<Real>(r.z(i), w) > t) return "not complementary at " + std::to_string(i);
    if (std::fabs(w - r.w(i)) > t) return "returned w differs from Mz + q at " + std::to_string(i);
  }
  return {};
}

// Random LCPs: monotone (M = BᵀB + skew, PSD symmetric part) and P-matrices (diagonally
// dominant), scaled by 10^±spread per row and column.
SparseMatrix random_lcp_matrix(std::mt19937& rng, Index n, double spread, bool monotone) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SparseMatrix M;
  if (monotone) {
    const SparseMatrix B = random_sparse(rng, n, n, 2, 0.0);
    const SparseMatrix S = random_sparse(rng, n, n, 2, 0.0);
    M = SparseMatrix(B.transpose()) * B + S - SparseMatrix(S.transpose());
  } else {
    M = random_sparse(rng, n, n, 3, 0.0);
    Vector rows = Vector::Zero(n);
    for (Index j = 0; j < n; ++j)
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) rows(it.row()) += std::abs(it.value());
    for (Index i = 0; i < n; ++i) M.coeffRef(i, i) += rows(i) + 0.5;
  }
  const Vector d = Vector::NullaryExpr(n, [&](Index) { return std::pow(10.0, spread * u(rng)); });
  SparseMatrix out = d.asDiagonal() * M * d.asDiagonal();  // congruence: monotone stays monotone
  out.makeCompressed();
  return out;
}

TEST(SolversNeverLie, EverySolvedLcpPassesTheLongDoubleCheck) {
  int solved = 0, total = 0;
  for (Index n : {3, 10, 40, 100, 250})
    for (double spread : {0.0, 1.0, 2.0})
      for (unsigned seed = 1; seed <= 8; ++seed) {
        std::mt19937 rng(seed * 7919 + static_cast<unsigned>(n));
        const bool monotone = seed % 2 == 0;
        const SparseMatrix M = random_lcp_matrix(rng, n, spread, monotone);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        const Vector q = Vector::NullaryExpr(n, [&](Index) { return u(rng) * std::pow(10.0, spread * u(rng)); });
        SCOPED_TRACE("n " + std::to_string(n) + ", spread " + std::to_string(spread) + ", seed " + std::to_string(seed));
        LemkeSolver lemke;
        lemke.setup(M, q);
        const LcpResult& r = lemke.solve();
        ++total;
        if (r.info.status == LcpStatus::solved) {
          ++solved;
          EXPECT_EQ(lcp_violation(M, q, r), "") << "Lemke";
        }
        if (!monotone) continue;
        const LcpResult ri = solve_lcp_ipm(M, q);
        ++total;
        if (ri.info.status == LcpStatus::solved) {
          ++solved;
          EXPECT_EQ(lcp_violation(M, q, ri), "") << "interior point";
        }
      }
  EXPECT_GE(solved, total * 3 / 4);
  std::printf("LCP solves: %d, %d solved and checked\n", total, solved);
}

// Data at the overflow threshold: whatever the status, `solved` only with finite numbers.
TEST(SolversNeverLie, HugeDataIsNeverSolvedWithNonFiniteNumbers) {
  for (double big : {1e300, 1e306, 1e308}) {
    SparseMatrix M(2, 2);
    M.setIdentity();
    const Vector q = (Vector(2) << big, -big).finished();
    LemkeSolver lemke;
    lemke.setup(M, q);
    const LcpResult& r = lemke.solve();
    if (r.info.status == LcpStatus::solved) {
      EXPECT_EQ(lcp_violation(M, q, r), "") << big;
    }
    try {
      const LcpResult ri = solve_lcp_ipm(M, q);
      if (ri.info.status == LcpStatus::solved) {
        EXPECT_EQ(lcp_violation(M, q, ri), "") << big;
      }
    } catch (const InputError&) {
    }
    QpProblem p(2);
    p.P = M;
    p.q = q;
    p.xl = Vector::Constant(2, -big);
    p.xu = Vector::Constant(2, big);
    try {
      QpSolver s;
      s.setup(p);
      const QpResult& rq = s.solve();
      if (rq.info.status == QpStatus::solved) {
        EXPECT_EQ(qp_violation(p, rq), "") << big;
      }
    } catch (const InputError&) {
    }
  }
}

}  // namespace
}  // namespace lcprelax
