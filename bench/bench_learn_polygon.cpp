// Throughput of the polygon learning losses (learn/polygon_objective.hpp): samples per
// second of forward + gradient (evaluate_mean over the whole dataset, warm starts from the
// previous iteration as in training) for each method with 1 and 2 threads, and the cost
// split per sample (assembly with tangents, solve, backward/chain rule; summed over
// threads, so it is CPU time per sample, not wall time).
//
//   build/bench/bench_learn_polygon [--benchmark_filter=relaxed]
//
// Dataset: the CLI's ground truth (apps/cmd_learn_polygon.cpp), 8 throws of 60 steps,
// contact steps only (315 samples), evaluated at 25%-perturbed parameters.
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/learn/polygon_objective.hpp>

#include <benchmark/benchmark.h>

namespace {

using namespace lcprelax;
using namespace lcprelax::learn;

const PolygonDataset& dataset() {
  static const PolygonDataset data = [] {
    PolygonModel m;
    Polygon p;
    p.vertices = {Vec2(-0.30, -0.22), Vec2(0.34, -0.18), Vec2(0.26, 0.24), Vec2(-0.22, 0.20)};
    m.shape = recentred(p);
    m.mu = 0.4;
    m.mass = 1.5;
    m.inertia = 0.06;
    PolygonDataSettings s;
    s.trajectories = 8;
    s.steps = 60;
    s.seed = 7;
    return generate_polygon_dataset(m, s);
  }();
  return data;
}

void BM_PolygonLoss(benchmark::State& state) {
  const PolygonMethod method = static_cast<PolygonMethod>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const PolygonDataset& data = dataset();
  PolygonModel start;
  {
    PolygonModel truth;
    Polygon p;
    p.vertices = {Vec2(-0.30, -0.22), Vec2(0.34, -0.18), Vec2(0.26, 0.24), Vec2(-0.22, 0.20)};
    truth.shape = recentred(p);
    truth.mu = 0.4;
    truth.mass = 1.5;
    truth.inertia = 0.06;
    start = perturb_polygon_model(truth, PolygonLearnFlags{}, 0.25, 3);
  }
  const ParameterSet theta = make_polygon_parameters(start, PolygonLearnFlags{});
  PolygonLossSettings ls;
  ls.method = method;
  PolygonObjective objective(data, ls);
  std::vector<Index> all, none;
  split_samples(objective.num_samples(), 0.0, 1, all, none);
  evaluate_mean(objective, theta, all, threads);  // warm starts, as in training
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
