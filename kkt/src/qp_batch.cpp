// Batched QP solves with OpenMP (see qp_batch.hpp). Each thread keeps one QpSolver as its
// workspace; a problem with the same pattern as the thread's previous one reuses its
// symbolic analysis through update(). Static scheduling with results stored by index
// makes the outputs independent of the thread count.
#include <lcprelax/kkt/qp_batch.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include <lcprelax/core/errors.hpp>

#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#ifdef LCPRELAX_HAS_OPENMP
#include <omp.h>
#endif

namespace lcprelax {
namespace {

// Throws InputError "problems[k]: ..." for the first invalid problem or invalid settings,
// before any solve starts (an exception cannot leave an OpenMP region).
void validate_batch(const std::vector<QpProblem>& problems, const QpSettings& settings) {
  if (std::string e = settings.validation_error(); !e.empty()) throw InputError("QpSettings: " + e);
  for (std::size_t k = 0; k < problems.size(); ++k)
    if (std::string e = problems[k].validation_error(); !e.empty())
      throw InputError("problems[" + std::to_string(k) + "]: " + e);
}

// Solves problems[k] with the thread's workspace (update() where the pattern repeats).
void solve_one(std::optional<QpSolver>& ws, const QpProblem*& last, const QpProblem& problem,
               const QpSettings& settings, QpResult& result) {
  if (ws && last && problem.same_pattern(*last)) {
    ws->update(problem);
  } else {
    ws.emplace(settings);
    ws->setup(problem);
  }
  last = &problem;
  result = ws->solve();
}

// Runs body(k, workspace, last) for k < count; an exception thrown for problem k is kept
// and the one of the lowest k rethrown after the loop with its problem index (InputError
// stays InputError, anything else becomes std::runtime_error).
template <class Body>
void parallel_for(int count, int threads, Body body) {
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(count));
  auto guarded = [&](int k, std::optional<QpSolver>& ws, const QpProblem*& last) {
    try {
      body(k, ws, last);
    } catch (...) {
      errors[static_cast<std::size_t>(k)] = std::current_exception();
      ws.reset();
      last = nullptr;
    }
  };
#ifdef LCPRELAX_HAS_OPENMP
  const int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel num_threads(nt)
  {
    std::optional<QpSolver> ws;
    const QpProblem* last = nullptr;
#pragma omp for schedule(static)
    for (int k = 0; k < count; ++k) guarded(k, ws, last);
  }
#else
  (void)threads;
  std::optional<QpSolver> ws;
  const QpProblem* last = nullptr;
  for (int k = 0; k < count; ++k) guarded(k, ws, last);
#endif
  for (int k = 0; k < count; ++k) {
    if (!errors[static_cast<std::size_t>(k)]) continue;
    const std::string where = "problems[" + std::to_string(k) + "]: ";
    try {
      std::rethrow_exception(errors[static_cast<std::size_t>(k)]);
    } catch (const InputError& e) {
      throw InputError(where + e.what());
    } catch (const std::exception& e) {  // not bad input (e.g. a failed analysis): keep it apart
      throw std::runtime_error(where + e.what());
    }
  }
}

}  // namespace

std::vector<QpResult> solve_qp_batch(const std::vector<QpProblem>& problems, const QpSettings& settings,
                                     int threads) {
  validate_batch(problems, settings);
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
  validate_batch(problems, settings);
  if (dl_dx.size() != problems.size())
    throw InputError("solve_qp_batch_backward: " + std::to_string(dl_dx.size()) + " loss gradients for " +
                     std::to_string(problems.size()) + " problems");
  results.assign(problems.size(), QpResult{});
  gradients.assign(problems.size(), QpGradient{});
  if (uses_petsc(settings.kkt_backend)) threads = 1;  // PETSc is not thread-safe
  parallel_for(static_cast<int>(problems.size()), threads,
               [&](int k, std::optional<QpSolver>& ws, const QpProblem*& last) {
                 solve_one(ws, last, problems[k], settings, results[k]);
                 if (!has_solution(results[k].info.status)) return;
                 gradients[k] = ws->backward(dl_dx[k]);
                 results[k].info.backward_seconds = ws->result().info.backward_seconds;
               });
}

}  // namespace lcprelax
