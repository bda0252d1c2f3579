#pragma once
// Batched QP solves (and backward passes) in parallel with OpenMP. Each thread owns its
// solver workspace; problems are processed in index order per thread and results stored
// by index, so the outputs do not depend on the number of threads. Every problem and the
// settings are validated before any solve: invalid data throw InputError naming the problem
// ("problems[3]: ..."). An exception raised while problem k is solved is rethrown after the
// batch with the same prefix (the lowest such k; InputError stays InputError, any other
// becomes std::runtime_error).
// Threads ≤ 0 means OpenMP's default; without OpenMP the batch runs serially.
#include <lcprelax/kkt/qp_gradient.hpp>
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/kkt/qp_result.hpp>
#include <lcprelax/kkt/qp_settings.hpp>

#include <vector>

namespace lcprelax {

std::vector<QpResult> solve_qp_batch(const std::vector<QpProblem>& problems,
                                     const QpSettings& settings = {}, int threads = 0);

/// Solves every problem and runs backward(dl_dx[k]) on it with the same workspace
/// (gradients[k] is left empty where the status has no solution, see has_solution). Throws
/// InputError when dl_dx.size() differs from problems.size().
void solve_qp_batch_backward(const std::vector<QpProblem>& problems, const std::vector<Vector>& dl_dx,
                             std::vector<QpResult>& results, std::vector<QpGradient>& gradients,
                             const QpSettings& settings = {}, int threads = 0);

}  // namespace lcprelax
