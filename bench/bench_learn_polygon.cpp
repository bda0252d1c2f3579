// Throughput of the polygon learning losses (learn/polygon_objective.hpp): samples per
// second of forward + gradient (evaluate_mean over the whole dataset; relaxed: proximal
// centres from the previous iteration as in training) for each method with 1 and 2 threads,
// and the cost split per sample (SceneObjectiveStats: contacts and island assembly, the step
// loss, the pullback to θ; summed over threads, so it is CPU time per sample, not wall time).
//
//   build/bench/bench_learn_polygon [--benchmark_filter=relaxed]
//
// Dataset: the CLI's ground truth (apps/cmd_learn_polygon.cpp), 8 throws of 60 steps,
// contact steps only (315 samples), evaluated at 25%-perturbed parameters.
#include "learn_problems.hpp"

#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/learn/polygon_objective.hpp>

#include <benchmark/benchmark.h>

namespace {

using namespace lcprelax;
using namespace lcprelax::learn;

const PolygonDataset& dataset() {
  static const PolygonDataset data = bench::polygon_dataset(8, 7);
  return data;
}

void BM_PolygonLoss(benchmark::State& state) {
  const PolygonMethod method = static_cast<PolygonMethod>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const PolygonDataset& data = dataset();
  const ParameterSet theta = bench::polygon_start(0.25, 3);
  PolygonLossSettings ls;
  ls.method = method;
  PolygonObjective objective(data, reference_polygon_model(), ls);
  std::vector<Index> all, none;
  split_samples(objective.num_samples(), 0.0, 1, all, none);
  evaluate_mean(objective, theta, all, threads);  // proximal centres, as in training
  objective.reset_times();
  int failed = 0;
  for (auto _ : state) {
    const BatchResult r = evaluate_mean(objective, theta, all, threads);
    failed += r.failed;
    benchmark::DoNotOptimize(r.loss);
  }
  const PolygonLossTimes t = objective.times();
  const double n = static_cast<double>(all.size()) * static_cast<double>(state.iterations());
  state.SetLabel(std::string(to_string(method)) + " threads=" + std::to_string(threads));
  state.counters["samples_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
  state.counters["assembly_us"] = 1e6 * t.assembly / n;
  state.counters["solve_us"] = 1e6 * t.solve / n;
  state.counters["backward_us"] = 1e6 * t.backward / n;
  state.counters["failed_per_pass"] = failed / static_cast<double>(state.iterations());
}

BENCHMARK(BM_PolygonLoss)
    ->ArgsProduct({{static_cast<int>(PolygonMethod::hard), static_cast<int>(PolygonMethod::relaxed),
                    static_cast<int>(PolygonMethod::convex)},
                   {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
