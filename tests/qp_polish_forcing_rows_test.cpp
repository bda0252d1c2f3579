// Forcing rows in polishing (QpSettings::polish_forcing_rows, kkt/src/qp_polish.cpp). A row
// all of whose variables sit at an active bound has no unique multiplier; the interior
// point's grows along the central path, and where the row's right-hand side is roundoff
// its term ω·l keeps the duality gap above 1e-9. QBORE3D (Maros–Meszaros, tests/data) has
// such rows: l = u = ±4e-16…1.8e-15 with every variable at 0 and ω ~ 1e5…9e6. Measured:
// the interior point ends solved_inaccurate with gap 2.56e-9, entirely σ(z); polishing
// with the step shifts 186 row multipliers (10 passes at most) and ends solved with gap
// 9.1e-11, dual residual 1.7e-10 (roundoff of the shifted multipliers), primal 4.5e-12;
// without it the polished point keeps the gap and is rejected.
// Residuals are recomputed here from the data with qpbenchmark's definitions.
#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace lcprelax {
namespace {

struct Recomputed {
  double primal = 0, dual = 0, gap = 0;
};

double dist(double v, double lo, double hi) { return std::max({lo - v, v - hi, 0.0}); }
double support(double z, double lo, double hi) { return z > 0 ? hi * z : (z < 0 ? lo * z : 0.0); }

Recomputed recompute(const QpProblem& p, const QpResult& r) {
  Recomputed c;
  const Vector Px = p.P.selfadjointView<Eigen::Upper>() * r.x, Gx = p.G * r.x;
  for (Index i = 0; i < Gx.size(); ++i) c.primal = std::max(c.primal, dist(Gx(i), p.l(i), p.u(i)));
  for (Index j = 0; j < r.x.size(); ++j) c.primal = std::max(c.primal, dist(r.x(j), p.xl(j), p.xu(j)));
  c.dual = (Px + p.q + p.G.transpose() * r.z + r.z_bounds).lpNorm<Eigen::Infinity>();
  double gap = r.x.dot(Px) + p.q.dot(r.x);
  for (Index i = 0; i < r.z.size(); ++i) gap += support(r.z(i), p.l(i), p.u(i));
  for (Index j = 0; j < r.x.size(); ++j) gap += support(r.z_bounds(j), p.xl(j), p.xu(j));
  c.gap = std::fabs(gap);
  return c;
}

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

}  // namespace
}  // namespace lcprelax
