// Least-norm multipliers in polishing (QpSettings::polish_least_norm, kkt/src/
// qp_polish_least_norm.cpp). Where the optimal multipliers form an unbounded set (implicit
// equalities: inequality rows that no feasible point can leave), the interior point's follow
// the analytic centre and grow as μ → 0; the gap's terms Σ z·bound then cancel at a size
// whose roundoff exceeds 1e-9.
//
// Powell's cyclic family (CUTEr POWELL20 generalized to n even; Maros–Meszaros POWELL20 is
// n = 10000 and is built here exactly as in the collection's QPS file): min ½‖x‖² s.t. row k:
// x_{k+1 mod n} − x_k ≥ s_k, s_k = ∓(2⌊k/2⌋ + 1.5) (− for even k). The rows sum to 0 ≥ Σs = 0,
// so every row is active and z + α·1 is optimal for every α ≥ −min z. Measured (recomputed
// residuals, eps 1e-9), solved without / with the step:
//   n = 1000: yes / yes;  2000: yes / yes;  4000: no (gap 1.2e-6) / yes (gap 0);
//   6000: no / no (gap 1.6e-6, its evaluation floor u·Σ|terms| ~ 1e-5);  10000: no (gap
//   3.9e-5) / yes (gap 0);  20000: no / no (gap 6.7e-6).
// With the step the smallest z is 0 (the least-norm point of the ray's feasible part) and the
// largest falls; where the gap stays above 1e-9 it is at the evaluation floor of its terms
// (~n³ in size), not a property of the multipliers.
//
// Random cyclic family (make_cycles, CyclicFamilyTable; 20 seeds per cell), solved without /
// with the step: scale 1: 20/20 for every spread; scale 1e2: spread 0: 8 / 20, spread 2:
// 0 / 19, spread 4: 0 / 18; in all 68 → 117 of 120. Without the step these end
// solved_inaccurate with the gap at 1e-9…6e-8: the gap ≈ xᵀ(Px + q + Gᵀz + z_b), and the
// polished point's stationarity error (1e-11…8e-10, weighted by |x| ~ 1e3) is the floor of
// its reduced system's refinement set by the interior point's multipliers; re-solving the
// reduced system from the least-norm point brings it to ~1e-14 (one pass of step 3c alone,
// the least-norm multipliers without that re-solve, measured 76 of 120).
// (At scale 1e4 neither solves one: the gap's terms reach 1e8, its evaluation floor 1e-8.)
#include <lcprelax/kkt/qp_gradient.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include "qp_recomputed_residuals.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

using test_support::Recomputed;
using test_support::recompute;

QpProblem make_powell(Index n) {
  QpProblem p(n);
  std::vector<Triplet> pt, gt;
  for (Index j = 0; j < n; ++j) pt.emplace_back(j, j, 1.0);
  p.P = SparseMatrix(n, n);
  p.P.setFromTriplets(pt.begin(), pt.end());
  Vector l(n);
  for (Index k = 0; k < n; ++k) {
    gt.emplace_back(k, (k + 1) % n, 1.0);
    gt.emplace_back(k, k, -1.0);
    const double c = 2.0 * static_cast<double>(k / 2) + 1.5;
    l(k) = k % 2 == 0 ? -c : c;
  }
  p.G = SparseMatrix(n, n);
  p.G.setFromTriplets(gt.begin(), gt.end());
  p.l = l;
  p.u = Vector::Constant(n, std::numeric_limits<double>::infinity());
  return p;
}

QpResult solve(const QpProblem& p, bool least_norm) {
  QpSettings s;
  s.polish_least_norm = least_norm;
  QpSolver solver(s);
  solver.setup(p);
  return solver.solve();
}

// Solved as the solver reports it (its residuals ≤ eps), and the residuals recomputed here
// agree: primal and dual ≤ eps, the gap ≤ eps or within its evaluation floor (the terms are
// ~n³ here: the order of summation alone moves the gap by more than 1e-9 for n ≥ 1000).
bool solved_at(const QpProblem& p, const QpResult& r, double eps) {
  if (r.info.status != QpStatus::solved) return false;
  if (!(r.info.primal_residual <= eps && r.info.dual_residual <= eps && r.info.duality_gap <= eps)) return false;
  const Recomputed c = recompute(p, r);
  return c.primal <= eps && c.dual <= eps && c.gap <= std::max(eps, c.gap_floor);
}

TEST(QpPolishLeastNorm, PowellFamilySolvedOnlyWithTheStep) {
  for (Index n : {Index(4000), Index(10000)}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const QpProblem p = make_powell(n);
    const QpResult with = solve(p, true);
    const QpResult without = solve(p, false);
    const Recomputed cw = recompute(p, with), co = recompute(p, without);
    std::printf("[ measured ] powell n %d: without %s gap %.2e z in [%.4e, %.4e] ‖z‖ %.4e | with %s gap %.2e z in [%.4e, "
                "%.4e] ‖z‖ %.4e\n",
                static_cast<int>(n), to_string(without.info.status), co.gap, without.z.minCoeff(), without.z.maxCoeff(),
                without.z.norm(), to_string(with.info.status), cw.gap, with.z.minCoeff(), with.z.maxCoeff(), with.z.norm());
    EXPECT_TRUE(solved_at(p, with, 1e-9)) << with.info.message;
    EXPECT_TRUE(with.info.polish_accepted);
    EXPECT_NE(without.info.status, QpStatus::solved) << "needs the step no more";
    // Same optimum; the multipliers (≤ 0: lower sides) of least norm have their largest at 0.
    EXPECT_NEAR(with.info.objective, without.info.objective, 1e-9 * std::fabs(without.info.objective));
    EXPECT_LE(with.z.maxCoeff(), 0.0);
    EXPECT_EQ(with.z.maxCoeff(), 0.0);
    EXPECT_LT(with.z.norm(), without.z.norm());
  }
}

TEST(QpPolishLeastNorm, BackwardAtTheLeastNormPointMatchesFiniteDifferences) {
  // Every row active: x = x_p + α·1 with α = −(1ᵀx_p + 1ᵀq)/n, so ∂(cᵀx)/∂q_j = −(1ᵀc)/n
  // exactly; backward() at the polished (least-norm) point against that and against
  // central differences of re-solves.
  constexpr Index n = 4000;
  QpProblem p = make_powell(n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Vector c(n);
  for (Index j = 0; j < n; ++j) c(j) = unit(rng);
  QpSolver solver;
  solver.setup(p);
  const QpResult r = solver.solve();
  ASSERT_EQ(r.info.status, QpStatus::solved) << r.info.message;
  ASSERT_TRUE(r.info.polish_accepted);
  const QpGradient g = solver.backward(c);
  const double exact = -c.sum() / static_cast<double>(n);
  // x is affine in q (every row stays active), so a large step costs no truncation error and
  // keeps the re-solves' own error (~1e-9 in x) small against the difference.
  const double h = 1.0;
  for (Index j : {Index(0), Index(1234), Index(n - 1)}) {
    QpProblem pp = p, pm = p;
    pp.q(j) += h;
    pm.q(j) -= h;
    QpSolver sp, sm;
    sp.setup(pp);
    sm.setup(pm);
    const double fd = (c.dot(sp.solve().x) - c.dot(sm.solve().x)) / (2.0 * h);
    std::printf("[ measured ] dq_%d: backward %.10e  central difference %.10e  exact %.10e\n", static_cast<int>(j),
                g.dq(j), fd, exact);
    EXPECT_NEAR(g.dq(j), exact, 1e-8 * std::fabs(exact));
    EXPECT_NEAR(fd, exact, 1e-5 * std::fabs(exact));
  }
}

TEST(QpPolishLeastNorm, SmallPowellUnchanged) {
  // Solved by the interior point itself: no polish, identical results with and without.
  const QpProblem p = make_powell(1000);
  const QpResult with = solve(p, true), without = solve(p, false);
  const Recomputed c = recompute(p, with);
  std::printf("[ measured ] powell n 1000: %s, recomputed %.2e %.2e %.2e (gap floor %.2e)\n",
              to_string(with.info.status), c.primal, c.dual, c.gap, c.gap_floor);
  EXPECT_TRUE(solved_at(p, with, 1e-9));
  EXPECT_FALSE(with.info.polish_attempted);
  EXPECT_EQ(with.x, without.x);
  EXPECT_EQ(with.z, without.z);
}

// Random cyclic family: n = 60, ½xᵀDx + qᵀx (D ∈ [0.5, 1.5], q ∈ [−1, 1]·scale), |x| ≤ 10·scale,
// 20 random two-sided rows that are not tight, and 6 cycles of 4–8 distinct variables whose
// edge rows g_e (x_b − x_a) ≥ g_e (x*_b − x*_a) (x* ∈ [−1, 1]·scale, g_e = 10^(spread·U(−½, ½)))
// sum, weighted by 1/g_e, to 0 ≥ 0: every edge row is active, the multipliers unbounded along
// (1/g_e) on each cycle.
QpProblem make_cycles(unsigned seed, double scale, double spread) {
  constexpr Index n = 60, loose = 20, cycles = 6;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  QpProblem p(n);
  std::vector<Triplet> pt, gt;
  for (Index j = 0; j < n; ++j) pt.emplace_back(j, j, 0.5 + unit(rng));
  p.P = SparseMatrix(n, n);
  p.P.setFromTriplets(pt.begin(), pt.end());
  for (Index j = 0; j < n; ++j) p.q(j) = (2.0 * unit(rng) - 1.0) * scale;
  Vector xs(n);
  for (Index j = 0; j < n; ++j) xs(j) = (2.0 * unit(rng) - 1.0) * scale;
  std::vector<double> l, u;
  Index row = 0;
  for (Index i = 0; i < loose; ++i, ++row) {
    double lo = 0.0;
    for (int k = 0; k < 3; ++k) {
      const Index j = static_cast<Index>(rng() % n);
      const double g = 2.0 * unit(rng) - 1.0;
      gt.emplace_back(row, j, g);
      lo -= std::fabs(g) * 10.0 * scale;
    }
    l.push_back(lo - scale);
    u.push_back(-lo + scale);
  }
  std::vector<Index> perm(n);
  for (Index j = 0; j < n; ++j) perm[j] = j;
  for (Index c = 0; c < cycles; ++c) {
    std::shuffle(perm.begin(), perm.end(), rng);
    const int len = 4 + static_cast<int>(rng() % 5);
    for (int e = 0; e < len; ++e, ++row) {
      const Index a = perm[e], b = perm[(e + 1) % len];
      const double g = std::pow(10.0, spread * (unit(rng) - 0.5));
      gt.emplace_back(row, b, g);
      gt.emplace_back(row, a, -g);
      l.push_back(g * (xs(b) - xs(a)));
      u.push_back(std::numeric_limits<double>::infinity());
    }
  }
  p.G = SparseMatrix(row, n);
  p.G.setFromTriplets(gt.begin(), gt.end());
  p.l = Eigen::Map<const Vector>(l.data(), row);
  p.u = Eigen::Map<const Vector>(u.data(), row);
  p.xl = Vector::Constant(n, -10.0 * scale);
  p.xu = Vector::Constant(n, 10.0 * scale);
  return p;
}

TEST(QpPolishLeastNorm, CyclicFamilyTable) {
  int total[2] = {0, 0};
  for (double scale : {1.0, 1e2})
    for (double spread : {0.0, 2.0, 4.0}) {
      int solved[2] = {0, 0};
      for (unsigned seed = 1; seed <= 20; ++seed) {
        const QpProblem p = make_cycles(seed, scale, spread);
        for (int with = 0; with < 2; ++with) {
          const QpResult r = solve(p, with == 1);
          if (r.info.status == QpStatus::solved) {
            EXPECT_TRUE(solved_at(p, r, 1e-9)) << "seed " << seed;
          }
          solved[with] += solved_at(p, r, 1e-9);
        }
      }
      std::printf("[ measured ] cycles scale %.0e spread %.0f: solved without %d, with %d of 20\n", scale, spread,
                  solved[0], solved[1]);
      EXPECT_GE(solved[1], solved[0]);
      total[0] += solved[0];
      total[1] += solved[1];
    }
  std::printf("[ measured ] cycles: solved without %d, with %d of 120\n", total[0], total[1]);
  EXPECT_GE(total[1], 110);
}

}  // namespace
}  // namespace lcprelax
