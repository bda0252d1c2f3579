// Learning curves of the block's parameterizations (issue 20; learn/block_param.hpp):
// held-out next-state error against the number of training transitions, 5 seeds each.
//
//   run_learning_curves [--sizes 10,30,100,300,1000] [--seeds 5] [--noise 0.02]
//     [--csv bench/results/learning_curves.csv] [--plot bench/results/plots/learning_curves.png]
//     > bench/results/learning_curves.txt
//
// Per parameterization P, training size N and seed s: N transitions from the true block
// (μ = 0.1, m = mg = 1; learn/block_dataset.hpp: half stick, half slip, 10% margin from the
// stick/slip boundary) with relative Gaussian noise σ on v_next (default 2% of its RMS);
// θ starts at the physical model with μ₀ = 3μ (every P contains it, and the truth) and is
// trained with each of --methods: the relaxed loss (learn/relaxed_lcp.hpp, defaults;
// nonconvex QPs shifted) and the hard loss (Lemke, learn/block_param_objective.hpp), by
// full-batch L-BFGS (at most --epochs iterations, the trainer's convergence test). The
// held-out set: --test noise-free transitions of the same generator (another seed per s).
// Reported per run:
//   test_error = sqrt(Σ(v̂⁺ − v⁺)² / Σ(v⁺)²) over the held-out set, v̂⁺ from Lemke on the
//                learned LCP (learn::block_param_predict), v⁺ the exact step;
//   mode_error = fraction of held-out transitions whose stick/slip mode (γ = 0 or not) the
//                learned LCP predicts wrongly; a prediction Lemke cannot make counts as a
//                wrong mode and is left out of test_error (column failed);
//   train_failed = sample evaluations that failed during training (e.g. a relaxed QP made
//                infeasible by an elementwise M at a line-search trial point; skipped);
//   stick_speed  = RMS of v̂⁺ over the held-out transitions that truly stick, in units of
//                μmg/m (how far from "stuck" a model that slides there predicts).
// The text summary gives per P and N the median and largest test_error and the mean
// mode_error over the seeds, then per P the smallest N whose median test_error ≤ 1% and the
// mode error at N = 1,000. Seconds are wall time on a shared machine (noisy).
#include <lcprelax/learn/block_param.hpp>
#include <lcprelax/learn/block_param_objective.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/scenes/line_plot.hpp>

#include <CLI/CLI.hpp>

#include "csv_table.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace lcprelax;
using namespace lcprelax::learn;

namespace {

struct RunResult {
  double test_error = 0.0, mode_error = 0.0, train_loss = 0.0, seconds = 0.0;
  double stick_speed = 0.0;  // RMS of v̂⁺ over the truly sticking held-out transitions, / (μmg/m)
  int failed = 0, epochs = 0, train_failed = 0;
  bool converged = false;
};

std::vector<Index> iota(Index n) {
  std::vector<Index> v(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = i;
  return v;
}

RunResult run(BlockParam param, BlockMethod method, const BlockDataset& train_data, const BlockDataset& test, const Block1d& truth,
              double init_mu, int epochs, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  BlockLossSettings s;
  s.relaxed.nonconvex = NonconvexPolicy::shift;
  auto objective = make_block_param_objective(param, method, train_data, s);
  ParameterSet theta = block_param_parameters(param, init_mu, train_data.mass, train_data.mg);
  TrainSettings t;
  t.epochs = epochs;
  t.threads = threads;
  t.optimizer.kind = OptimizerKind::lbfgs;
  t.optimizer.learning_rate = 1.0;
  const std::vector<Index> all = iota(train_data.size());
  const TrainResult tr = train(*objective, theta, all, {}, t);
  RunResult r;
  r.epochs = static_cast<int>(tr.history.size());
  r.converged = tr.converged;
  r.train_failed = tr.failed;
  r.train_loss = evaluate_mean(*objective, theta, all, threads).loss;
  LemkeSolver solver;
  double err2 = 0.0, ref2 = 0.0;
  int wrong = 0, sticking = 0;
  double stick2 = 0.0;
  for (const BlockTransition& x : test.samples) {
    const double exact = block1d_next_velocity(truth, x.v, x.u, block1d_exact_impulse(truth, x.v, x.u));
    const bool stick = std::abs(x.v + x.u / truth.mass) <= truth.mu * truth.mg / truth.mass;
    const BlockPrediction p = block_param_predict(param, theta, test.mass, test.mg, x.v, x.u, solver);
    if (!p.ok) {
      ++r.failed;
      ++wrong;
      continue;
    }
    err2 += (p.v_next - exact) * (p.v_next - exact);
    ref2 += exact * exact;
    if (p.stick != stick) ++wrong;
    if (stick) {
      ++sticking;
      stick2 += p.v_next * p.v_next;
    }
  }
  r.test_error = std::sqrt(err2 / ref2);
  r.mode_error = static_cast<double>(wrong) / static_cast<double>(test.size());
  r.stick_speed = sticking > 0 ? std::sqrt(stick2 / sticking) / (truth.mu * truth.mg / truth.mass) : 0.0;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("learning curves of the block's parameterizations (issue 20)");
  std::vector<int> sizes = {10, 30, 100, 300, 1000};
  std::vector<std::string> params = {"physical", "residual", "pair", "elementwise"};
  std::vector<std::string> methods = {"relaxed", "hard"};
  int seeds = 5, test_size = 2000, epochs = 200, threads = 1;
  double noise = 0.02, true_mu = 0.1, init_mu = 0.3;
  std::string csv_path, plot;
  app.add_option("--sizes", sizes, "training set sizes")->delimiter(',');
  app.add_option("--params", params, "parameterizations")->delimiter(',');
  app.add_option("--methods", methods, "training losses (relaxed, hard)")->delimiter(',');
  app.add_option("--seeds", seeds, "seeds per size");
  app.add_option("--test", test_size, "held-out transitions");
  app.add_option("--epochs", epochs, "L-BFGS iteration cap");
  app.add_option("--threads", threads, "OpenMP threads");
  app.add_option("--noise", noise, "relative noise on the training v_next");
  app.add_option("--true-mu", true_mu, "true friction coefficient");
  app.add_option("--init-mu", init_mu, "initial friction coefficient");
  app.add_option("--csv", csv_path, "CSV of every run (none without this option)");
  app.add_option("--plot", plot, "plot of the median test error (.png/.svg)");
  CLI11_PARSE(app, argc, argv);

  const Block1d truth{1.0, 1.0, true_mu};
  std::ofstream csv;
  if (!bench::open_optional_csv(csv_path, csv)) return 2;
  csv << "param,method,samples,seed,epochs,converged,train_loss,test_error,mode_error,failed,train_failed,stick_speed,seconds\n";
  std::printf("Learning curves, 1-D block (true mu %g, initial mu %g, noise %g relative, %d held-out, L-BFGS <= %d "
              "iterations)\n",
              true_mu, init_mu, noise, test_size, epochs);
  std::printf("%-20s %7s %12s %12s %12s %8s %9s\n", "param", "N", "median_err", "max_err", "mode_err", "failed",
              "seconds");
  struct Cell {
    std::vector<double> err, mode;
    int failed = 0;
    double seconds = 0.0;
  };
  std::map<std::string, std::map<int, Cell>> cells;
  std::vector<std::string> rows;
  for (const std::string& method_name : methods)
  for (const std::string& param_name : params) {
    const BlockParam param = parse_block_param(param_name);
    const BlockMethod method = parse_block_method(method_name);
    const std::string name = param_name + "/" + method_name;
    rows.push_back(name);
    for (int n : sizes) {
      Cell& c = cells[name][n];
      for (int s = 1; s <= seeds; ++s) {
        BlockDataSettings g;
        g.truth = truth;
        g.samples = n;
        g.seed = static_cast<std::uint64_t>(1000 * s + n);
        g.noise = noise;
        const BlockDataset train_data = generate_block_dataset(g);
        g.samples = test_size;
        g.seed = static_cast<std::uint64_t>(777777 + s);
        g.noise = 0.0;
        const BlockDataset test = generate_block_dataset(g);
        const RunResult r = run(param, method, train_data, test, truth, init_mu, epochs, threads);
        csv << param_name << ',' << method_name << ',' << n << ',' << s << ',' << r.epochs << ',' << (r.converged ? 1 : 0) << ','
            << r.train_loss << ',' << r.test_error << ',' << r.mode_error << ',' << r.failed << ',' << r.train_failed << ',' << r.stick_speed << ',' << r.seconds << '\n';
        csv.flush();
        c.err.push_back(r.test_error);
        c.mode.push_back(r.mode_error);
        c.failed += r.failed;
        c.seconds += r.seconds;
      }
      double mode = 0.0;
      for (double m : c.mode) mode += m / static_cast<double>(c.mode.size());
      std::printf("%-20s %7d %12.4g %12.4g %12.4g %8d %9.2f\n", name.c_str(), n, bench::median(c.err),
                  *std::max_element(c.err.begin(), c.err.end()), mode, c.failed, c.seconds);
      std::fflush(stdout);
    }
  }
  std::printf("\nSummary: smallest N (of the sizes run) with median test error <= 1%%; mean mode error at N = 1000\n");
  std::printf("%-20s %14s %18s\n", "param/method", "N_for_1pct", "mode_err_at_1000");
  for (const std::string& name : rows) {
    std::string reach = "> " + std::to_string(sizes.back());
    for (int n : sizes)
      if (bench::median(cells[name][n].err) <= 0.01) {
        reach = std::to_string(n);
        break;
      }
    std::string mode = "n/a";
    if (cells[name].count(1000)) {
      double m = 0.0;
      for (double x : cells[name][1000].mode) m += x / static_cast<double>(cells[name][1000].mode.size());
      std::ostringstream o;
      o << m;
      mode = o.str();
    }
    std::printf("%-20s %14s %18s\n", name.c_str(), reach.c_str(), mode.c_str());
  }
  if (!plot.empty() && line_plot_available()) {
    std::vector<LineSeries> series;
    for (const std::string& name : rows) {
      LineSeries l{name, {}, {}};
      l.markers = true;
      for (int n : sizes) {
        l.x.push_back(n);
        l.y.push_back(bench::median(cells[name][n].err));
      }
      series.push_back(l);
    }
    LinePlotOptions o;
    o.title = "Block: held-out next-state error (median of seeds)";
    o.x_label = "training transitions";
    o.y_label = "relative RMS error of v+";
    o.log_x = o.log_y = true;
    write_line_plot(plot, series, o);
    std::vector<LineSeries> modes;
    for (const std::string& name : rows) {
      LineSeries l{name, {}, {}};
      l.markers = true;
      for (int n : sizes) {
        double m = 0.0;
        for (double x : cells[name][n].mode) m += x / static_cast<double>(cells[name][n].mode.size());
        l.x.push_back(n);
        l.y.push_back(m);
      }
      modes.push_back(l);
    }
    o.title = "Block: held-out stick/slip mode error (mean of seeds)";
    o.y_label = "fraction of wrong modes";
    o.log_y = false;
    const std::string mode_plot = plot.substr(0, plot.rfind('.')) + "_mode" + plot.substr(plot.rfind('.'));
    write_line_plot(mode_plot, modes, o);
  }
  return 0;
}
