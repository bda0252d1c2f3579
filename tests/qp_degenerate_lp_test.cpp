// Degenerate LPs of the Maros–Meszaros kind, generated: the ingredients of the interior
// point that make them solve to 1e-9 (absolute, residuals recomputed here from the data).
//
// Family (make_lp): min qᵀx s.t. Gx ≥ l, 0 ≤ x ≤ U, built around a vertex x0 with half of
// its variables at 0 and others at U (primal degenerate: 60% of the rows tight at x0 as
// well), and q = Gᵀw − z_b from nonnegative multipliers w on half of the tight rows and z_b
// on 70% of the active bounds (dual degenerate: the optimal multiplier set is not a point).
// Row entries span 10^spread (badly scaled).
// Ingredients (kkt/src/ipm_iterate.hpp, kkt/src/qp_bound_multipliers.cpp):
//   - exact_bound_steps: bound-multiplier steps from the dual-residual equation, assigned
//     (not corrected by a difference) to the active side;
//   - clean_bound_multipliers: exact componentwise multipliers of the variables at a bound
//     in the unscaled candidate.
// Measured on this family (FamilyTable: n = 40 and 80, U ∈ {10, 1e2, 1e3},
// spread 0…3, seeds 1…12, 288 problems): solved 268 with both, 269 with the cleanup only,
// 268 with the exact steps only, 268 with neither. With polishing (which shrinks forcing
// rows' multipliers and accepts any solved polished point) the family does not separate
// the two ingredients; the single cases below still need them; on the
// Maros–Meszaros set they are what moved QSCFXM1, Q25FV47, QGROW7 and LASER to solved. The
// cases below solve with the defaults and did not solve with the named ingredient switched
// off (statuses in each test's comment).
#include <lcprelax/kkt/qp_solver.hpp>

#include "degenerate_qp_family.hpp"

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

constexpr double kEps = 1e-9;

QpProblem make_lp(unsigned seed, Index n, Index m, double big, double spread) {
  return testing::make_degenerate_qp(seed, n, m, big, spread, false);
}

// max(primal, dual, gap) recomputed from the data (definitions of qp_settings.hpp; A empty).
double worst_residual(const QpProblem& p, const QpResult& r) {
  const Vector Gx = p.G * r.x;
  double primal = 0.0;
  for (Index i = 0; i < Gx.size(); ++i) primal = std::max({primal, p.l(i) - Gx(i), Gx(i) - p.u(i)});
  for (Index j = 0; j < r.x.size(); ++j) primal = std::max({primal, p.xl(j) - r.x(j), r.x(j) - p.xu(j)});
  const Vector rd = p.q + p.G.transpose() * r.z + r.z_bounds;
  long double gap = 0.0L;
  for (Index j = 0; j < r.x.size(); ++j) gap += static_cast<long double>(p.q(j)) * r.x(j);
  for (Index i = 0; i < r.z.size(); ++i) gap += testing::support_term(r.z(i), p.l(i), p.u(i));
  for (Index j = 0; j < r.x.size(); ++j) gap += testing::support_term(r.z_bounds(j), p.xl(j), p.xu(j));
  return std::max({primal, rd.lpNorm<Eigen::Infinity>(), static_cast<double>(std::fabs(gap))});
}

void expect_solved(unsigned seed, Index n, double big, double spread) {
  const QpProblem p = make_lp(seed, n, n * 4 / 5, big, spread);
  QpSolver solver;  // defaults: both ingredients on
  solver.setup(p);
  const QpResult& r = solver.solve();
  SCOPED_TRACE("seed " + std::to_string(seed) + ", n " + std::to_string(n) + ": " + r.info.message);
  ASSERT_EQ(r.info.status, QpStatus::solved);
  EXPECT_LE(r.info.primal_residual, kEps);
  EXPECT_LE(r.info.dual_residual, kEps);
  EXPECT_LE(r.info.duality_gap, kEps);
  EXPECT_LE(worst_residual(p, r), 2 * kEps);  // recomputed (roundoff of a different sum order)
  EXPECT_TRUE(r.x.allFinite() && r.z.allFinite() && r.z_bounds.allFinite());
}

// n = 80, U = 10, spread 3, seed 9: solved_inaccurate with exact_bound_steps = false.
TEST(QpDegenerateLp, ExactBoundStepsSolveBadlyScaledLp) { expect_solved(9, 80, 1e1, 3.0); }

// n = 80, U = 1e3, spread 0, seed 1 and U = 1e2, spread 0, seed 9: solved_inaccurate with
// clean_bound_multipliers = false.
TEST(QpDegenerateLp, CleanBoundMultipliersSolveLargeBounds) {
  expect_solved(1, 80, 1e3, 0.0);
  expect_solved(9, 80, 1e2, 0.0);
}

// n = 80, U = 1e3, spread 1, seed 9: numerical_error without either ingredient or with the
// exact steps only, solved_inaccurate with the cleanup only.
TEST(QpDegenerateLp, BothIngredientsNeeded) { expect_solved(9, 80, 1e3, 1.0); }

// The measurement quoted in the header: on the whole family the defaults solve at least 265
// of the 288 and no fewer than with neither ingredient.
TEST(QpDegenerateLp, FamilyTable) {
  int solved[4] = {0, 0, 0, 0}, total = 0;
  for (double big : {1e1, 1e2, 1e3})
    for (double spread : {0.0, 1.0, 2.0, 3.0})
      for (unsigned seed = 1; seed <= 12; ++seed)
        for (Index n : {40, 80}) {
          const QpProblem p = make_lp(seed, n, n * 4 / 5, big, spread);
          ++total;
          for (int mask = 0; mask < 4; ++mask) {
            QpSettings s;
            s.exact_bound_steps = mask & 1;
            s.clean_bound_multipliers = mask & 2;
            s.centrality_correctors = 0;  // this table measures the two ingredients above
            QpSolver solver(s);
            solver.setup(p);
            const QpResult& r = solver.solve();
            solved[mask] += r.info.status == QpStatus::solved;
          }
        }
  std::printf("solved of %d: none %d, exact only %d, clean only %d, both %d\n", total, solved[0], solved[1], solved[2],
              solved[3]);
  EXPECT_GE(solved[3], 265);
  EXPECT_GE(solved[3], solved[0]);
}

}  // namespace
}  // namespace lcprelax
