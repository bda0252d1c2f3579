// Forcing rows in polishing (QpSettings::polish_forcing_rows, kkt/src/qp_polish.cpp). A row
// all of whose variables sit at an active bound has no unique multiplier; the interior
// point's grows along the central path, and where the row's right-hand side is roundoff
// its term ω·l keeps the duality gap above 1e-9. QBORE3D (Maros–Meszaros, tests/data) has
// such rows: l = u = ±4e-16…1.8e-15 with every variable at 0 and ω ~ 1e5…9e6. Measured:
// the interior point ends solved_inaccurate with gap 2.56e-9, entirely σ(z); polishing
// with the step shifts 186 row multipliers (10 passes at most) and ends solved with gap
// 9.1e-11, dual residual 1.7e-10 (roundoff of the shifted multipliers), primal 4.5e-12;
// without it the polished point keeps the gap and is rejected.
// Generated family (make_forcing_family, FamilyTable): min ½xᵀDx + qᵀx, 0 ≤ x ≤ 5, D on every
// other variable, 40 core rows l ≤ Gx ≤ u (4 random entries, l ∈ [−2, −1], u ∈ [1, 2]) and 12
// forcing rows Σ_{j∈S} g_j x_j = ε over 3–6 random variables whose q_j ∈ [−1.5, −0.5] (they
// would leave the bound but for the row), |ε| ∈ [0.5, 2]·ε_scale with a random sign, every
// entry scaled by 10^(spread·U(−½, ½)); n = 80, seeds 1…30 per (ε_scale, spread). Measured,
// solved at 1e-9 without / with the step:
//   without: ε_scale 1e-15: spread 0: 30, spread 2: 30, spread 4: 27 (of 30);
//            ε_scale 1e-13: 29, 21, 1;   ε_scale 1e-11: 4, 0, 0
//   with:    30 everywhere but ε_scale 1e-11, spread 4: 15;   in all 142 → 255 of 270.
//   (those without least-norm multipliers; with that step alone, no forcing-row step: 254 —
//   29 at ε_scale 1e-13, spread 4 and 15 at 1e-11, spread 4; both steps: 259, 19 of 30 at
//   1e-11, spread 4. QBORE3D needs the forcing-row step with or without the least-norm one.)
// (The 15 left at ε 1e-11, spread 4 are not looked into.)
// Residuals are recomputed here from the data with qpbenchmark's definitions.
#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include "qp_recomputed_residuals.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

using test_support::Recomputed;
using test_support::recompute;

QpResult solve_qbore3d(const QpProblem& p, bool forcing_rows) {
  QpSettings s;
  s.polish_forcing_rows = forcing_rows;
  QpSolver solver(s);
  solver.setup(p);
  return solver.solve();
}

TEST(QpPolishForcingRows, QBore3dIsSolvedOnlyWithTheStep) {
  const io::QpsModel model = io::read_qps(std::string(LCPRELAX_TEST_DATA_DIR) + "/maros_meszaros/QBORE3D.qps");
  const QpProblem& p = model.problem;

  const QpResult with = solve_qbore3d(p, true);
  EXPECT_EQ(with.info.status, QpStatus::solved) << with.info.message;
  EXPECT_TRUE(with.info.polish_accepted);
  const Recomputed c = recompute(p, with);
  EXPECT_LE(c.primal, 1e-9);
  EXPECT_LE(c.dual, 1e-9);
  EXPECT_LE(c.gap, 1e-9);
  // Same optimum as the interior point's (objective 3100.20 of the collection's report).
  EXPECT_NEAR(with.info.objective, 3100.2008, 1e-3);

  const QpResult without = solve_qbore3d(p, false);
  EXPECT_NE(without.info.status, QpStatus::solved) << "QBORE3D no longer needs the forcing-row step";
  EXPECT_GT(recompute(p, without).gap, 1e-9);
  EXPECT_NEAR(without.info.objective, with.info.objective, 1e-6 * std::fabs(with.info.objective));
}

QpProblem make_forcing_family(unsigned seed, double eps_scale, double spread) {
  constexpr Index n = 80, core_rows = 40, forcing = 12;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto scaled = [&](double v) { return v * std::pow(10.0, spread * (unit(rng) - 0.5)); };
  QpProblem p(n);
  std::vector<Triplet> pt, gt;
  for (Index j = 0; j < n; j += 2) pt.emplace_back(j, j, 0.5 + unit(rng));
  p.P = SparseMatrix(n, n);
  p.P.setFromTriplets(pt.begin(), pt.end());
  for (Index j = 0; j < n; ++j) p.q(j) = unit(rng) - 0.3;
  const Index m = core_rows + forcing;
  Vector l(m), u(m);
  for (Index i = 0; i < core_rows; ++i) {
    for (int k = 0; k < 4; ++k) {
      const Index j = static_cast<Index>(rng() % n);
      gt.emplace_back(i, j, scaled(2.0 * unit(rng) - 0.5));
    }
    l(i) = -1.0 - unit(rng);
    u(i) = 1.0 + unit(rng);
  }
  for (Index r = 0; r < forcing; ++r) {
    const Index i = core_rows + r;
    const int size = 3 + static_cast<int>(rng() % 4);
    for (int k = 0; k < size; ++k) {
      const Index j = static_cast<Index>(rng() % n);
      gt.emplace_back(i, j, scaled(0.5 + 1.5 * unit(rng)));
      p.q(j) = -0.5 - unit(rng);
    }
    const double magnitude = (0.5 + 1.5 * unit(rng)) * eps_scale;
    l(i) = u(i) = rng() % 2 ? magnitude : -magnitude;
  }
  p.G = SparseMatrix(m, n);
  p.G.setFromTriplets(gt.begin(), gt.end());  // repeated (i, j) are summed
  p.l = l;
  p.u = u;
  p.xl = Vector::Zero(n);
  p.xu = Vector::Constant(n, 5.0);
  return p;
}

// Variants: 0 neither step, 1 forcing rows only, 2 least-norm multipliers only
// (QpSettings::polish_least_norm, the general step: a forcing row's multiplier is one
// direction of an unbounded multiplier set), 3 both (the defaults).
TEST(QpPolishForcingRows, FamilyTable) {
  int total[4] = {0, 0, 0, 0};
  for (double eps_scale : {1e-15, 1e-13, 1e-11})
    for (double spread : {0.0, 2.0, 4.0}) {
      int solved[4] = {0, 0, 0, 0};
      for (unsigned seed = 1; seed <= 30; ++seed) {
        const QpProblem p = make_forcing_family(seed, eps_scale, spread);
        for (int variant = 0; variant < 4; ++variant) {
          QpSettings s;
          s.polish_forcing_rows = variant & 1;
          s.polish_least_norm = variant & 2;
          QpSolver solver(s);
          solver.setup(p);
          const QpResult& r = solver.solve();
          if (r.info.status != QpStatus::solved) continue;
          const Recomputed c = recompute(p, r);
          EXPECT_LE(std::max({c.primal, c.dual, c.gap}), 2e-9) << "seed " << seed << " reported solved";
          ++solved[variant];
        }
      }
      std::printf("[ measured ] eps_scale %.0e spread %.0f: solved with neither %d, forcing rows %d, least norm %d, "
                  "both %d of 30\n",
                  eps_scale, spread, solved[0], solved[1], solved[2], solved[3]);
      EXPECT_GE(solved[1], solved[0]);
      EXPECT_GE(solved[3], solved[0]);
      for (int v = 0; v < 4; ++v) total[v] += solved[v];
    }
  std::printf("[ measured ] in all: neither %d, forcing rows %d, least norm %d, both %d of 270\n", total[0], total[1],
              total[2], total[3]);
  EXPECT_GE(total[1], 250);
  EXPECT_GE(total[1] - total[0], 100);
  EXPECT_GE(total[2] - total[0], 100);
  EXPECT_GE(total[3], 255);
}

}  // namespace
}  // namespace lcprelax
