#pragma once
// Per-thread solvers of the polygon losses (polygon_losses.hpp, PolygonSolvers), internal.
//
// PolygonObjective keeps one set per thread, so that the hard and convex losses do not
// build a LemkeSolver or a QpSolver (nor redo QpSolver::setup's symbolic analysis) for
// every sample. Results do not depend on what a solver solved before: Lemke's setup()
// resets it, QpSolver::update() only keeps the ordering and analysis of the same pattern,
// and solve() restarts from the settings' regularization.
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/learn/polygon_losses.hpp>

namespace lcprelax::learn {

struct PolygonSolvers {
  explicit PolygonSolvers(const PolygonLossSettings& s) : lemke(s.lemke), phase1(s.qp), phase2(s.qp) {}
  LemkeSolver lemke;
  QpSolver phase1, phase2;
};

/// update() when the pattern is the solver's, else setup() (symbolic analysis).
inline void setup_or_update(QpSolver& solver, const QpProblem& problem) {
  if (solver.can_update(problem))
    solver.update(problem);
  else
    solver.setup(problem);
}

}  // namespace lcprelax::learn
