#pragma once
// The convex model's two interior-point solvers of one island, kept between time steps so
// that a step whose phase QPs have the previous step's sparsity pattern (same contacts on
// the same bodies, same formulation) reuses their ordering and symbolic analysis
// (QpSolver::update: new values, same pattern) instead of a fresh QpSolver::setup.
//
// update() rewrites the scaled problem and redoes the Ruiz equilibration as setup() does
// (kkt/qp_solver.hpp), and the fill-reducing ordering of a pattern is deterministic, so a
// reused solve takes the same iterations as a fresh one: the answers agree to roundoff
// (tests/convex_solver_cache_test.cpp checks v⁺ and λ along a pile trajectory). In the
// spirit of PIQP's and OSQP's setup → solve → update → solve lifecycle.
//
// The pattern test is QpSolver::can_update; a cache whose solvers cannot be updated is set
// up afresh (counted in `stats.setups`). A cache belongs to one island at a time and is not
// thread-safe; the simulator keeps one per island (simulator.cpp).
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

namespace lcprelax {

/// What the solves through one cache did (cumulative).
struct ConvexSolverStats {
  long setups = 0;   ///< phase solvers set up afresh (new pattern): a symbolic analysis each
  long updates = 0;  ///< phase solvers updated in place (pattern repeated)
  // Wall time (s, steady_clock), for profiles: building the phase QPs (Delassus or lifted
  // data, triplets, CSC), setup()/update() (scaling, KKT pattern; setup() adds the
  // ordering and symbolic analysis), solve() and, within it, the numeric factorizations
  // (QpInfo::factor_seconds).
  double assemble_seconds = 0.0, prepare_seconds = 0.0, solve_seconds = 0.0, factor_seconds = 0.0;
};

struct ConvexSolverCache {
  explicit ConvexSolverCache(const QpSettings& settings = {}) : phase1(settings), phase2(settings) {}
  QpSolver phase1;  ///< frictionless normal impulses (convex_phase1_qp)
  QpSolver phase2;  ///< friction bounded by κ (convex_phase2_qp)
  ConvexSolverStats stats;
};

}  // namespace lcprelax
