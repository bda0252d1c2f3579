// Solves min ½x² − x (x* = 1) through the installed package; exits 0 iff solved correctly.
#include <lcprelax/kkt/qp_solver.hpp>

#include <cmath>
#include <cstdio>

int main() {
  lcprelax::QpProblem problem(1);
  problem.P.insert(0, 0) = 1.0;
  problem.q(0) = -1.0;
  lcprelax::QpSolver solver;
  solver.setup(problem);
  const lcprelax::QpResult& result = solver.solve();
  std::printf("consumer: status %s, x = %.12g\n", lcprelax::to_string(result.info.status), result.x(0));
  return result.info.status == lcprelax::QpStatus::solved && std::abs(result.x(0) - 1.0) < 1e-8 ? 0 : 1;
}
