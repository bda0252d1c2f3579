// Dense vs sparse KKT factorization in the interior-point QP (QpSettings::kkt_backend):
// where CHOLMOD's sparse path starts to win over the dense LDLᵀ (sparse/dense_ldlt.hpp),
// which sets QpSettings::dense_max_kkt, and what the dense path buys the learning losses.
//
//   BM_QpSolve/n/backend      random sparse convex QP of n variables (random_qp.hpp: n/4
//                             equalities, n/2 inequality rows, so a full KKT of ~1.75n
//                             rows; n = 4 … 292 sweeps KKT dimensions 7 … 511), set up once;
//                             each iteration is update(same problem) + solve() + backward(),
//                             the learning losses' per-sample work. backend 0 = cholmod,
//                             1 = dense. Counters: kkt_dim, iterations, factorizations,
//                             kkt_form (1 full, 2 eliminated), ok (1 if solved).
//   BM_QpSolveDenseData/n/b   the same work on a fully dense QP shaped like the contact and
//                             relaxed-LCP subproblems (n variables ≥ 0, n dense rows Gx ≥ h,
//                             no equalities: KKT 2n, or the n×n eliminated form).
//   BM_LearnBlock/method/b    the block losses (as bench_learn_block.cpp: 400 transitions,
//                             μ = 0.1, evaluated at μ = 0.3), 1 thread, relaxed (1) and
//                             convex (2), backend b; counter samples_per_s.
//   BM_LearnPolygon/method/b  the polygon losses (as bench_learn_polygon.cpp: 315 contact
//                             samples at 25%-perturbed parameters), 1 thread, relaxed (1)
//                             and convex (2), backend b; counter samples_per_s.
// Compare rows with the same arguments but backend 0 and 1 from ONE run (shared machine).
//
//   build-dense/bench/bench_qp_dense_vs_sparse --benchmark_min_time=0.3
#include "learn_problems.hpp"
#include "random_qp.hpp"

#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/learn/polygon_objective.hpp>
#include <lcprelax/models/block1d.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;
using namespace lcprelax::learn;

constexpr std::uint64_t kSeed = 11;

KktBackend backend_arg(std::int64_t b) { return b == 0 ? KktBackend::cholmod : KktBackend::dense; }

void BM_QpSolve(benchmark::State& state) {
  const Index n = static_cast<Index>(state.range(0));
  QpSettings s;
  s.kkt_backend = backend_arg(state.range(1));
  const bench::RandomQp rq = bench::make_random_qp(n, kSeed);
  QpSolver solver(s);
  solver.setup(rq.problem);
  QpInfo info = solver.solve().info;  // warm-up (and the counters)
  bool ok = info.status == QpStatus::solved;
  for (auto _ : state) {
    solver.update(rq.problem);
    const QpResult& r = solver.solve();
    ok = ok && r.info.status == QpStatus::solved;
    if (r.info.status != QpStatus::solved) continue;
    const QpGradient g = solver.backward(rq.dl_dx);
    benchmark::DoNotOptimize(g.dq.data());
  }
  const Index kkt_dim = rq.problem.num_variables() + rq.problem.num_equalities() + rq.problem.num_inequalities();
  state.counters["kkt_dim"] = kkt_dim;
  state.counters["iterations"] = info.iterations;
  state.counters["factorizations"] = info.factorizations;
  state.counters["kkt_form"] = static_cast<double>(info.kkt_form);
  state.counters["ok"] = ok ? 1 : 0;
  state.SetLabel(std::string(to_string(info.kkt_backend)) + " N=" + std::to_string(kkt_dim));
}
BENCHMARK(BM_QpSolve)
    ->ArgsProduct({{4, 6, 8, 12, 16, 24, 32, 40, 48, 56, 64, 80, 96, 128, 160, 192, 256, 292}, {0, 1}})
    ->ArgNames({"n", "dense"})
    ->Unit(benchmark::kMicrosecond);

// A dense QP shaped like the contact and relaxed-LCP subproblems: min ½xᵀPx + qᵀx s.t.
// Gx ≥ h (n rows), x ≥ 0, P = BᵀB/n + 0.1·I and G fully dense, h = Gx0 − |noise| for a
// random x0 ≥ 0 (so feasible), q ~ N(0, 1); the KKT is [P Gᵀ; G −W]
// (N = 2n) or, without equalities, the n×n eliminated form.
QpProblem dense_qp(Index n, std::uint64_t seed) {
  std::mt19937_64 rng(seed + static_cast<std::uint64_t>(n));
  std::normal_distribution<double> N(0.0, 1.0);
  QpProblem p(n);
  const DenseMatrix B = DenseMatrix::NullaryExpr(n, n, [&] { return N(rng); });
  const DenseMatrix P = B.transpose() * B / n + 0.1 * DenseMatrix::Identity(n, n);
  p.P = DenseMatrix(P.triangularView<Eigen::Upper>()).sparseView();
  p.q = Vector::NullaryExpr(n, [&] { return N(rng); });
  p.G = DenseMatrix(DenseMatrix::NullaryExpr(n, n, [&] { return N(rng); })).sparseView();
  const Vector x0 = Vector::NullaryExpr(n, [&] { return std::abs(N(rng)); });  // feasible point
  p.l = p.G * x0 - Vector::NullaryExpr(n, [&] { return std::abs(N(rng)); });
  p.u = Vector::Constant(n, std::numeric_limits<double>::infinity());
  p.xl = Vector::Zero(n);
  return p;
}

void BM_QpSolveDenseData(benchmark::State& state) {
  const Index n = static_cast<Index>(state.range(0));
  QpSettings s;
  s.kkt_backend = backend_arg(state.range(1));
  const QpProblem p = dense_qp(n, kSeed);
  const Vector dl_dx = Vector::Ones(n);
  QpSolver solver(s);
  solver.setup(p);
  const QpInfo info = solver.solve().info;
  bool ok = info.status == QpStatus::solved;
  for (auto _ : state) {
    solver.update(p);
    const QpResult& r = solver.solve();
    ok = ok && r.info.status == QpStatus::solved;
    if (r.info.status != QpStatus::solved) continue;
    const QpGradient g = solver.backward(dl_dx);
    benchmark::DoNotOptimize(g.dq.data());
  }
  state.counters["kkt_dim"] = 2 * n;
  state.counters["iterations"] = info.iterations;
  state.counters["kkt_form"] = static_cast<double>(info.kkt_form);
  state.counters["ok"] = ok ? 1 : 0;
  state.SetLabel(std::string(to_string(info.kkt_backend)) + " N=" + std::to_string(2 * n));
}
BENCHMARK(BM_QpSolveDenseData)
    ->ArgsProduct({{2, 4, 8, 12, 16, 24, 32, 48, 64, 96, 128}, {0, 1}})
    ->ArgNames({"n", "dense"})
    ->Unit(benchmark::kMicrosecond);

const BlockDataset& block_data() {
  static const BlockDataset d = bench::block_dataset(400);
  return d;
}

void BM_LearnBlock(benchmark::State& state) {
  BlockLossSettings ls;
  ls.qp.kkt_backend = backend_arg(state.range(1));
  auto objective = make_block_objective(static_cast<BlockMethod>(state.range(0)), block_data(), ls);
  const ParameterSet theta = block_parameters(0.3, 1.0, 1.0);
  std::vector<Index> samples;
  for (Index i = 0; i < block_data().size(); ++i) samples.push_back(i);
  evaluate_mean(*objective, theta, samples, 1);  // workspaces and analyses
  int failed = 0;
  for (auto _ : state) {
    const BatchResult r = evaluate_mean(*objective, theta, samples, 1);
    failed += r.failed;
    benchmark::DoNotOptimize(r.loss);
  }
  const double n = static_cast<double>(samples.size()) * static_cast<double>(state.iterations());
  state.counters["samples_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
  state.counters["failed"] = failed;
  state.SetLabel(std::string(to_string(static_cast<BlockMethod>(state.range(0)))) + " " +
                 to_string(ls.qp.kkt_backend));
}
BENCHMARK(BM_LearnBlock)
    ->ArgsProduct({{static_cast<int>(BlockMethod::relaxed), static_cast<int>(BlockMethod::convex)}, {0, 1}})
    ->ArgNames({"method", "dense"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

const PolygonDataset& polygon_data() {
  static const PolygonDataset data = bench::polygon_dataset(8, 7);
  return data;
}

void BM_LearnPolygon(benchmark::State& state) {
  const ParameterSet theta = bench::polygon_start(0.25, 3);
  PolygonLossSettings ls;
  ls.method = static_cast<PolygonMethod>(state.range(0));
  ls.relaxed.qp.kkt_backend = ls.convex.qp.kkt_backend = backend_arg(state.range(1));
  PolygonObjective objective(polygon_data(), reference_polygon_model(), ls);
  std::vector<Index> all, none;
  split_samples(objective.num_samples(), 0.0, 1, all, none);
  evaluate_mean(objective, theta, all, 1);  // warm starts, as in training
  int failed = 0;
  for (auto _ : state) {
    const BatchResult r = evaluate_mean(objective, theta, all, 1);
    failed += r.failed;
    benchmark::DoNotOptimize(r.loss);
  }
  const double n = static_cast<double>(all.size()) * static_cast<double>(state.iterations());
  state.counters["samples_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
  state.counters["failed"] = failed;
  state.SetLabel(std::string(to_string(ls.method)) + " " + to_string(ls.relaxed.qp.kkt_backend));
}
BENCHMARK(BM_LearnPolygon)
    ->ArgsProduct({{static_cast<int>(PolygonMethod::relaxed), static_cast<int>(PolygonMethod::convex)}, {0, 1}})
    ->ArgNames({"method", "dense"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
