// Block learning throughput (learn/block_losses.hpp): samples per second of one forward +
// gradient evaluation, for each method with 1 and 2 threads, the cost split (assembly /
// solve / backward, from BlockObjective::timings, summed over threads), and a dense
// per-sample reference path with Eigen side by side:
//   hard:    the 3×3 LCP by enumeration of the 8 complementary bases (Eigen PartialPivLU),
//            gradient by one transposed solve with the accepted basis;
//   relaxed: the default relaxed QP (3 variables, rows Mλ + q ≥ 0, λ ≥ 0) by enumeration
//            of the 64 active sets (Eigen FullPivLU of each KKT matrix), envelope gradient;
//   convex:  the 1-variable QP in closed form (clamp) with its one-sided derivative.
// Data: 400 transitions, μ = 0.1, m = m·g = 1, evaluated at μ = 0.3.
//   build-block/bench/bench_learn_block --benchmark_min_time=0.5
#include "learn_problems.hpp"

#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/models/block1d.hpp>

#include <benchmark/benchmark.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace lcprelax::learn {
namespace {

const BlockDataset& data() {
  static const BlockDataset d = bench::block_dataset(400);
  return d;
}

std::vector<Index> all() {
  std::vector<Index> v;
  for (Index i = 0; i < data().size(); ++i) v.push_back(i);
  return v;
}

void BM_BlockLoss(benchmark::State& state) {
  const auto method = static_cast<BlockMethod>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  auto objective = make_block_objective(method, data());
  const ParameterSet theta = block_parameters(0.3, 1.0, 1.0);
  const std::vector<Index> samples = all();
  evaluate_mean(*objective, theta, samples, threads);  // workspaces and analyses
  objective->reset_timings();
  for (auto _ : state) benchmark::DoNotOptimize(evaluate_mean(*objective, theta, samples, threads).loss);
  state.SetItemsProcessed(state.iterations() * static_cast<long>(samples.size()));
  const BlockLossTimings t = objective->timings();
  const double total = t.assembly + t.solve + t.backward;
  state.counters["assembly_frac"] = t.assembly / total;
  state.counters["solve_frac"] = t.solve / total;
  state.counters["backward_frac"] = t.backward / total;
  state.counters["us_per_sample_cpu"] = 1e6 * total / std::max(1L, t.evaluations);
  state.SetLabel(std::string(to_string(method)) + ", " + std::to_string(threads) + " thread(s)");
}
BENCHMARK(BM_BlockLoss)
    ->ArgsProduct({{0, 1, 2}, {1, 2}})
    ->ArgNames({"method", "threads"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Dense hard reference: enumerate bases of w − Mz = q (columns e_i for w_i, −M_:i for z_i).
double dense_hard(const BlockTransition& t, double mu, double& grad) {
  const Block1dLcp lcp = block1d_lcp(Block1d{1.0, 1.0, mu}, t.v, t.u);
  const Eigen::Matrix3d M = DenseMatrix(lcp.M);
  const Eigen::Vector3d q = lcp.q;
  for (int mask = 0; mask < 8; ++mask) {
    Eigen::Matrix3d B;
    for (int i = 0; i < 3; ++i) B.col(i) = (mask >> i & 1) ? Eigen::Vector3d(-M.col(i)) : Eigen::Vector3d::Unit(i);
    Eigen::PartialPivLU<Eigen::Matrix3d> lu(B);
    if (std::abs(lu.determinant()) < 1e-12) continue;
    const Eigen::Vector3d x = lu.solve(q);
    if (x.minCoeff() < -1e-12) continue;
    Eigen::Vector3d z = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i)
      if (mask >> i & 1) z(i) = x(i);
    const double res = t.v + t.u + z(0) - z(1) - t.v_next;
    Eigen::Vector3d g = Eigen::Vector3d::Zero();  // ∂ℓ/∂x_B
    if (mask & 1) g(0) = 2 * res;
    if (mask & 2) g(1) = -2 * res;
    grad = B.transpose().partialPivLu().solve(g)(2);  // ∂ℓ/∂q₃ = ∂ℓ/∂μ (mg = 1)
    return res * res;
  }
  return std::nan("");
}

// Dense relaxed reference: min ½xᵀHx + hᵀx s.t. Cx ≥ d (C = [M; I], d = [−q; 0]).
double dense_relaxed(const BlockTransition& t, double mu, double& grad) {
  const Block1dLcp lcp = block1d_lcp(Block1d{1.0, 1.0, mu}, t.v, t.u);
  const Eigen::Matrix3d M = DenseMatrix(lcp.M);
  const Eigen::Vector3d P(1.0, -1.0, 0.0);
  const double r0 = t.v + t.u - t.v_next;
  const Eigen::Matrix3d H = 2.0 * P * P.transpose() + M + M.transpose() + 1e-3 * Eigen::Matrix3d::Identity();
  const Eigen::Vector3d h = 2.0 * r0 * P + lcp.q;
  Eigen::Matrix<double, 6, 3> C;
  C << M, Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 6, 1> d;
  d << -lcp.q, Eigen::Vector3d::Zero();
  for (int mask = 0; mask < 64; ++mask) {
    const int k = __builtin_popcount(static_cast<unsigned>(mask));
    if (k > 3) continue;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 + k, 3 + k);
    Eigen::VectorXd rhs(3 + k);
    K.topLeftCorner(3, 3) = H;
    rhs.head(3) = -h;
    for (int i = 0, a = 0; i < 6; ++i)
      if (mask >> i & 1) {
        K.block(0, 3 + a, 3, 1) = -C.row(i).transpose();
        K.block(3 + a, 0, 1, 3) = C.row(i);
        rhs(3 + a++) = d(i);
      }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    if (!lu.isInvertible()) continue;
    const Eigen::VectorXd s = lu.solve(rhs);
    const Eigen::Vector3d x = s.head(3);
    if (k > 0 && s.tail(k).minCoeff() < -1e-10) continue;
    if ((C * x - d).minCoeff() < -1e-10) continue;
    double mult3 = 0.0;  // multiplier of row 3 (μ − λ⁺ − λ⁻ ≥ 0)
    for (int i = 0, a = 0; i < 6; ++i)
      if (mask >> i & 1) {
        if (i == 2) mult3 = s(3 + a);
        ++a;
      }
    grad = x(2) - mult3;  // ∂c/∂q₃ = a2 λ₃ + z₃, z = −multiplier
    return 0.5 * x.dot(H * x) + h.dot(x) + r0 * r0;
  }
  return std::nan("");
}

double dense_convex(const BlockTransition& t, double mu, double& grad) {
  const double vs = t.v + t.u, lambda = std::clamp(-vs, -mu, mu);
  const double res = vs + lambda - t.v_next;
  grad = std::abs(-vs) > mu ? 2 * res * (-vs > 0 ? 1.0 : -1.0) : 0.0;
  return res * res;
}

void BM_DenseReference(benchmark::State& state) {
  const auto method = static_cast<BlockMethod>(state.range(0));
  auto f = method == BlockMethod::hard ? dense_hard : method == BlockMethod::relaxed ? dense_relaxed : dense_convex;
  double check = 0.0, gcheck = 0.0;
  for (auto _ : state) {
    double loss = 0.0, grad = 0.0;
    for (const BlockTransition& t : data().samples) {
      double g = 0.0;
      loss += f(t, 0.3, g);
      grad += g;
    }
    check = loss / data().size();
    gcheck = grad / data().size();
    benchmark::DoNotOptimize(loss);
  }
  state.SetItemsProcessed(state.iterations() * data().size());
  auto objective = make_block_objective(method, data());
  const BatchResult r = evaluate_mean(*objective, block_parameters(0.3, 1.0, 1.0), all(), 1);
  state.counters["loss_rel_diff"] = std::abs(check - r.loss) / std::abs(r.loss);
  state.counters["grad_abs_diff"] = std::abs(gcheck - r.gradient(0));
  state.SetLabel(std::string("dense ") + to_string(method) + ", 1 thread");
}
BENCHMARK(BM_DenseReference)->DenseRange(0, 2)->ArgName("method")->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lcprelax::learn

BENCHMARK_MAIN();
