// Batched QP solves with OpenMP (see qp_batch.hpp). Each thread keeps one QpSolver as its
// workspace; a problem with the same pattern as the thread's previous one reuses its
// symbolic analysis through update(). Static scheduling with results stored by index
// makes the outputs independent of the thread count.
#include <lcprelax/kkt/qp_batch.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include <exception>
#include <optional>

#ifdef LCPRELAX_HAS_OPENMP
#include <omp.h>
#endif

namespace lcprelax {
namespace {

// Solves problems[k] with the thread's workspace; false (and result set) on bad input.
bool solve_one(std::optional<QpSolver>& ws, const QpProblem*& last, const QpProblem& problem,
               const QpSettings& settings, QpResult& result) {
  try {
    if (ws && last && problem.same_pattern(*last)) {
      ws->update(problem);
    } else {
      ws.emplace(settings);
      ws->setup(problem);
    }
    last = &problem;
    result = ws->solve();
    return true;
  } catch (const std::exception& e) {
    ws.reset();
    last = nullptr;
    result = QpResult{};
    result.info.status = QpStatus::invalid_input;
    result.info.message = e.what();
    return false;
  }
}

template <class Body>
void parallel_for(int count, int threads, Body body) {
#ifdef LCPRELAX_HAS_OPENMP
  const int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel num_threads(nt)
  {
    std::optional<QpSolver> ws;
    const QpProblem* last = nullptr;
#pragma omp for schedule(static)
    for (int k = 0; k < count; ++k) body(k, ws, last);
  }
#else
  (void)threads;
  std::optional<QpSolver> ws;
  const QpProblem* last = nullptr;
  for (int k = 0; k < count; ++k) body(k, ws, last);
#endif
}

}  // namespace

std::vector<QpResult> solve_qp_batch(const std::vector<QpProblem>& problems, const QpSettings& settings,
                                     int threads) {
  std::vector<QpResult> results(problems.size());
  if (uses_petsc(settings.kkt_backend)) threads = 1;  // PETSc is not thread-safe
  parallel_for(static_cast<int>(problems.size()), threads,
               [&](int k, std::optional<QpSolver>& ws, const QpProblem*& last) {
                 solve_one(ws, last, problems[k], settings, results[k]);
               });
  return results;
}

void solve_qp_batch_backward(const std::vector<QpProblem>& problems, const std::vector<Vector>& dl_dx,
                             std::vector<QpResult>& results, std::vector<QpGradient>& gradients,
                             const QpSettings& settings, int threads) {
  results.assign(problems.size(), QpResult{});
  gradients.assign(problems.size(), QpGradient{});
  if (uses_petsc(settings.kkt_backend)) threads = 1;  // PETSc is not thread-safe
  parallel_for(static_cast<int>(problems.size()), threads,
               [&](int k, std::optional<QpSolver>& ws, const QpProblem*& last) {
                 if (static_cast<size_t>(k) >= dl_dx.size()) {
                   results[k].info.status = QpStatus::invalid_input;
                   results[k].info.message = "no loss gradient given for this problem";
                   return;
                 }
                 if (!solve_one(ws, last, problems[k], settings, results[k])) return;
                 const QpStatus s = results[k].info.status;
                 if (s != QpStatus::solved && s != QpStatus::solved_inaccurate) return;
                 try {
                   gradients[k] = ws->backward(dl_dx[k]);
                   results[k].info.backward_seconds = ws->result().info.backward_seconds;
                 } catch (const std::exception& e) {
                   results[k].info.status = QpStatus::invalid_input;
                   results[k].info.message = e.what();
                 }
               });
}

}  // namespace lcprelax
