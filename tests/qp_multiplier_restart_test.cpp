// The multiplier-scaled third run (QpSettings::multiplier_restart_growth, kkt/src/qp_solve.cpp):
// after the first and the conservative second run both fail, one more cold start with its
// multipliers multiplied by the growth of the first run's largest multiplier.
//
// Family (make_concave_fit): LISWET-like convex fits (Li & Swetits' problems of the
// Maros–Meszaros collection) to concave data, min ½‖x − c‖² subject to
// x_i − 2x_{i+1} + x_{i+2} ≥ 0, c_j = 1 + a·t_j^p + 0.1·sin(j + 1), t_j = j/(n − 1). The fit is
// nearly affine, every row is active and the optimal multipliers are ~n² times the data's
// residual, orders of magnitude above Mehrotra's starting multipliers (~0.1).
// Measured (n ∈ {2000, 5000, 10000}; a ∈ {0.1, 1, −1} × p ∈ {2, 3, 0.5}, and a = 0: 30
// problems): with neither the third run nor the conservative run's drop of the inequality
// block's δ (QpSettings::conservative_row_reg_drop = 1e-8) 8 end numerical_error; the
// third run solves 5 of them (a = −1, p = 3 at every n; a = −1, p = 2 and a = 0.1, p = 0.5
// at n = 10000) in 68–173 iterations of all three runs, the drop the three with a = 0
// (noise only, tests/qp_row_regularization_test.cpp); the 22 solved by the first run take
// the same iterations (the third run is reached only after two failed runs).
#include "liswet_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace lcprelax {
namespace {

using testing_support::expect_liswet_solved;

// c_j = 1 + a·t_j^p + 0.1·sin(j + 1) (the header comment's family).
QpProblem make_concave_fit(Index n, double a, double p_exp) {
  return testing_support::make_liswet_fit(n, [&](double t, Index j) {
    return 1.0 + a * std::pow(t, p_exp) + 0.1 * std::sin(static_cast<double>(j + 1));
  });
}

TEST(QpMultiplierRestart, ConcaveFitSolvedByTheScaledRun) {
  for (Index n : {2000, 5000}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const QpProblem p = make_concave_fit(n, -1.0, 3.0);
    QpSolver solver;
    solver.setup(p);
    const QpResult& r = solver.solve();
    expect_liswet_solved(p, r);
    EXPECT_NE(r.info.message.find("multiplier-scaled third run"), std::string::npos) << r.info.message;
    // The optimal multipliers are far above the cold start's (~0.1).
    EXPECT_GT(-r.z.minCoeff(), 1e3);

    QpSettings without;
    without.multiplier_restart_growth = 0.0;
    QpSolver plain(without);
    plain.setup(p);
    const QpResult& f = plain.solve();
    EXPECT_FALSE(has_solution(f.info.status)) << to_string(f.info.status);
    EXPECT_GT(f.info.duality_gap, 1e-3);
  }
}

TEST(QpMultiplierRestart, SolvedProblemsDoNotReachIt) {
  // A fit that the first run solves: identical result with or without the third run.
  const QpProblem p = make_concave_fit(2000, 1.0, 2.0);
  QpSolver solver;
  solver.setup(p);
  const QpResult& r = solver.solve();
  expect_liswet_solved(p, r);
  QpSettings without;
  without.multiplier_restart_growth = 0.0;
  QpSolver plain(without);
  plain.setup(p);
  const QpResult& f = plain.solve();
  EXPECT_EQ(r.info.iterations, f.info.iterations);
  EXPECT_EQ(r.x, f.x);
}

TEST(QpMultiplierRestart, SettingValidated) {
  QpSettings s;
  s.multiplier_restart_growth = -1.0;
  EXPECT_NE(s.validation_error().find("multiplier_restart_growth"), std::string::npos);
  s.multiplier_restart_growth = 0.0;
  EXPECT_TRUE(s.validation_error().empty());
}

}  // namespace
}  // namespace lcprelax
