// Forward (setup + solve) and backward (adjoint) time of the interior-point QP solver on
// random sparse convex QPs (random_qp.hpp) of n = 100 … 100,000 variables.
//
//   BM_QpForward/n   one fresh QpSolver per iteration: setup(problem) + solve().
//                    Counters: iterations, factor_nnz (nnz of the final KKT factor),
//                    factorizations, kkt_form (0 automatic, 1 full, 2 eliminated), n_rows.
//   BM_QpBackward/n  backward(dl_dx) on a solver that already solved the problem once
//                    (zero new numeric factorizations by contract).
//                    Counters: bwd_over_fwd = backward time / best forward time seen for
//                    this n (target ≤ 0.2 from n ≥ 10,000), fwd_ms, target_met (1 or 0).
//
// Problems, solved solvers and forward times are cached per n, so Google Benchmark's
// repeated calls of a benchmark function do not regenerate or re-solve a 100,000-variable
// problem. Run BM_QpForward before BM_QpBackward (the default order) for the ratio to use
// the benchmark's own forward measurement; otherwise the one warm-up solve is used.
#include "random_qp.hpp"

#include <lcprelax/kkt/qp_solver.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <memory>
#include <string>

namespace {

using lcprelax::Index;
using lcprelax::QpSettings;
using lcprelax::QpSolver;
using lcprelax::QpStatus;
using lcprelax::bench::RandomQp;

constexpr std::uint64_t kSeed = 2024;
constexpr double kTargetRatio = 0.2;  // target: backward ≤ 0.2 × forward for n ≥ 10⁴

QpSettings bench_settings() {
  QpSettings s;  // library defaults: eps_abs = 1e-9, eps_rel = 0
  s.max_iter = 500;
  return s;
}

bool usable(QpStatus s) { return has_solution(s); }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Case {
  RandomQp qp;
  double best_forward_seconds = std::numeric_limits<double>::infinity();
  std::unique_ptr<QpSolver> solved;  // for the backward benchmark, created on demand
  QpStatus solved_status = QpStatus::unsolved;
};

Case& get_case(Index n) {
  static std::map<Index, std::unique_ptr<Case>> cases;
  auto& slot = cases[n];
  if (!slot) {
    slot = std::make_unique<Case>();
    slot->qp = lcprelax::bench::make_random_qp(n, kSeed);
  }
  return *slot;
}

QpSolver& solved_solver(Case& c) {
  if (!c.solved) {
    c.solved = std::make_unique<QpSolver>(bench_settings());
    const auto t0 = std::chrono::steady_clock::now();
    c.solved->setup(c.qp.problem);
    c.solved_status = c.solved->solve().info.status;
    c.best_forward_seconds = std::min(c.best_forward_seconds, seconds_since(t0));
  }
  return *c.solved;
}

void set_common_counters(benchmark::State& state, const RandomQp& qp) {
  state.counters["n"] = static_cast<double>(qp.problem.num_variables());
  state.counters["n_rows"] = static_cast<double>(qp.problem.num_equalities() + qp.problem.num_inequalities());
  state.counters["nnz_P"] = static_cast<double>(qp.problem.P.nonZeros());
}

void BM_QpForward(benchmark::State& state) {
  const Index n = static_cast<Index>(state.range(0));
  Case& c = get_case(n);
  lcprelax::QpInfo info;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    QpSolver solver(bench_settings());
    solver.setup(c.qp.problem);
    info = solver.solve().info;
    benchmark::DoNotOptimize(info.objective);
    c.best_forward_seconds = std::min(c.best_forward_seconds, seconds_since(t0));
  }
  if (!usable(info.status)) {
    state.SkipWithError(("solve failed: " + std::string(lcprelax::to_string(info.status)) + " " + info.message).c_str());
    return;
  }
  set_common_counters(state, c.qp);
  state.counters["iterations"] = info.iterations;
  state.counters["factor_nnz"] = static_cast<double>(info.kkt_factor_nnz);
  state.counters["factorizations"] = info.factorizations;
  state.counters["kkt_form"] = static_cast<double>(static_cast<int>(info.kkt_form));
  state.counters["inaccurate"] = info.status == QpStatus::solved_inaccurate ? 1.0 : 0.0;
  state.SetLabel(lcprelax::to_string(info.kkt_form));
}

void BM_QpBackward(benchmark::State& state) {
  const Index n = static_cast<Index>(state.range(0));
  Case& c = get_case(n);
  QpSolver& solver = solved_solver(c);
  if (!usable(c.solved_status)) {
    state.SkipWithError(("forward solve failed: " + std::string(lcprelax::to_string(c.solved_status))).c_str());
    for (auto _ : state) {
    }
    return;
  }
  double total = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    lcprelax::QpGradient g = solver.backward(c.qp.dl_dx);
    benchmark::DoNotOptimize(g.dq.data());
    total += seconds_since(t0);
  }
  const double backward = total / static_cast<double>(std::max<benchmark::IterationCount>(state.iterations(), 1));
  const double ratio = backward / c.best_forward_seconds;
  const lcprelax::QpInfo& info = solver.result().info;
  set_common_counters(state, c.qp);
  state.counters["iterations"] = info.iterations;
  state.counters["factor_nnz"] = static_cast<double>(info.kkt_factor_nnz);
  state.counters["fwd_ms"] = 1e3 * c.best_forward_seconds;
  state.counters["bwd_over_fwd"] = ratio;
  state.counters["target_met"] = ratio <= kTargetRatio ? 1.0 : 0.0;
}

// Small sizes run for the default minimum time; large ones a fixed, small number of times
// so that the 100,000-variable case finishes in a few solves.
BENCHMARK(BM_QpForward)->Unit(benchmark::kMillisecond)->Arg(100)->Arg(1000);
BENCHMARK(BM_QpForward)->Unit(benchmark::kMillisecond)->Arg(10000)->Iterations(3);
BENCHMARK(BM_QpForward)->Unit(benchmark::kMillisecond)->Arg(100000)->Iterations(1);
BENCHMARK(BM_QpBackward)->Unit(benchmark::kMillisecond)->Arg(100)->Arg(1000)->Arg(10000);
BENCHMARK(BM_QpBackward)->Unit(benchmark::kMillisecond)->Arg(100000)->Iterations(5);

}  // namespace

BENCHMARK_MAIN();
