// Work-precision of learning: learned-parameter error against wall time, per learning
// method, from the trainer's per-epoch record (learn/trainer.hpp: θ and wall time since the
// start of training after every epoch).
//
//   run_learn_convergence [--block-epochs 150] [--polygon-epochs 150] [--threads 1]
//                         [--block-samples 200] [--polygon-data bench|cli]
//                         [--problems block,polygon] [--csv OUT]
//
// Block (learn_problems.hpp; the CLI's `lcprelax learn block` settings): truth μ = 0.1,
// noise-free transitions (seed 1), methods hard, relaxed and convex, each from μ = 10× and
// 0.3× the truth; Adam, learning rate 0.05, full batch. error = |μ − μ*|/μ*.
// Polygon: μ, mass, inertia and the 8 vertex coordinates learned with Adam (learning rate
// 0.02, full batch), methods relaxed, hard and convex. --polygon-data bench (default): the
// data of tests/learn_polygon_recovery_test.cpp and bench_learn_polygon (8 throws of 60
// steps, seed 7: 315 contact transitions, all for training), start = truth perturbed by
// 25% (seed 3); --polygon-data cli: `lcprelax learn polygon`'s defaults (400 transitions
// from throws with seed 1, 20% held out for validation, perturbation seed 1, learning-rate
// decay 0.003; the CLI trains 300 epochs: pass --polygon-epochs 300 to match it).
// error = largest polygon_relative_error over the learned parameters (mu_error: μ's alone).
// Rows: one per epoch plus epoch 0 (the start, seconds 0). Columns: problem, method, init
// (block: "10x"/"0.3x"; polygon: "perturbed"), epoch, seconds, loss (mean training loss of
// the epoch; empty at epoch 0), validation_loss, error, mu_error, failed. A summary per run
// (final error, seconds, time to reach error ≤ 1e-2 and ≤ 1e-3) is printed. Exit 0.
#include "learn_problems.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;

struct Point {
  int epoch = 0;
  double seconds = 0.0, loss = NAN, validation_loss = NAN, error = NAN, mu_error = NAN;
  int failed = 0;
};

struct Run {
  std::string problem, method, init;
  std::vector<Point> points;
};

learn::TrainSettings train_settings(int epochs, int threads, double learning_rate, double decay = 0.0) {
  learn::TrainSettings t;
  t.epochs = epochs;
  t.patience = 0;  // every method runs the same epochs: error against time over the whole run
  t.threads = threads;
  t.seed = 1;
  t.optimizer.kind = learn::OptimizerKind::adam;
  t.optimizer.learning_rate = learning_rate;
  t.optimizer.decay = decay;
  return t;
}

Run block_run(learn::BlockMethod method, double init_factor, const learn::BlockDataset& data, int epochs,
              int threads) {
  Run run{"block", learn::to_string(method), init_factor == 10.0 ? "10x" : "0.3x", {}};
  auto objective = learn::make_block_objective(method, data);
  learn::ParameterSet theta = learn::block_parameters(init_factor * bench::kBlockTrueMu, 1.0, 1.0);
  const Index mu = theta.index("mu");
  auto err = [&](const learn::ParameterSet& t) { return std::abs(t[mu].value - bench::kBlockTrueMu) / bench::kBlockTrueMu; };
  run.points.push_back({0, 0.0, NAN, NAN, err(theta), err(theta), 0});
  const learn::TrainResult r =
      learn::train(*objective, theta, bench::all_samples(data.size()), {}, train_settings(epochs, threads, 0.05));
  learn::ParameterSet at = theta;
  for (const learn::EpochRecord& e : r.history) {
    at.set_values(e.theta);
    run.points.push_back({e.epoch, e.seconds, e.loss, e.validation_loss, err(at), err(at), e.failed});
  }
  return run;
}

Run polygon_run(learn::PolygonMethod method, const learn::PolygonDataset& data, bool cli, int epochs, int threads) {
  Run run{"polygon", learn::to_string(method), cli ? "perturbed (cli data)" : "perturbed", {}};
  learn::PolygonLossSettings ls;
  ls.method = method;
  learn::PolygonObjective objective(data, learn::reference_polygon_model(), ls);
  const learn::ParameterSet truth = bench::polygon_true_parameters();
  learn::ParameterSet theta = bench::polygon_start(0.25, cli ? 1 : 3);
  std::vector<Index> training, validation;
  learn::split_samples(objective.num_samples(), cli ? 0.2 : 0.0, 1, training, validation);
  auto mu_err = [&](const learn::ParameterSet& t) { return learn::polygon_relative_error(t, truth, 0); };
  run.points.push_back({0, 0.0, NAN, NAN, bench::polygon_max_error(theta, truth), mu_err(theta), 0});
  const learn::TrainResult r = learn::train(objective, theta, training, validation, train_settings(epochs, threads, 0.02, cli ? 0.003 : 0.0));
  learn::ParameterSet at = theta;
  for (const learn::EpochRecord& e : r.history) {
    at.set_values(e.theta);
    run.points.push_back({e.epoch, e.seconds, e.loss, e.validation_loss, bench::polygon_max_error(at, truth),
                          mu_err(at), e.failed});
  }
  return run;
}

// Wall time of the first epoch whose error is ≤ level (NaN if never).
double time_to(const Run& r, double level) {
  for (const Point& p : r.points)
    if (p.error <= level) return p.seconds;
  return NAN;
}

void print_summary(const Run& r) {
  const Point& last = r.points.back();
  int failed = 0;
  for (const Point& p : r.points) failed += p.failed;
  std::printf("%-8s %-8s %-10s epochs %4d  %8.3f s  error %10.3g -> %10.3g  t(err<=1e-2) %8.3g s  t(err<=1e-3) %8.3g s"
              "  failed %d\n",
              r.problem.c_str(), r.method.c_str(), r.init.c_str(), last.epoch, last.seconds, r.points.front().error,
              last.error, time_to(r, 1e-2), time_to(r, 1e-3), failed);
  std::fflush(stdout);
}

std::string cell(double v) {
  if (!std::isfinite(v)) return "";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"learned-parameter error against wall time for each learning method"};
  int block_epochs = 150, polygon_epochs = 150, threads = 1;
  Index block_samples = 200;
  std::string problems = "block,polygon", polygon_data = "bench", csv;
  app.add_option("--block-epochs", block_epochs, "epochs per block run")->capture_default_str();
  app.add_option("--polygon-epochs", polygon_epochs, "epochs per polygon run")->capture_default_str();
  app.add_option("--threads", threads, "OpenMP threads of the trainer")->capture_default_str();
  app.add_option("--block-samples", block_samples, "block transitions")->capture_default_str();
  app.add_option("--polygon-data", polygon_data, "bench or cli (see the file comment)")->capture_default_str();
  app.add_option("--problems", problems, "block,polygon")->capture_default_str();
  app.add_option("--csv", csv, "CSV output");
  CLI11_PARSE(app, argc, argv);
  if (block_epochs < 1 || polygon_epochs < 1 || threads < 1 || block_samples < 1 ||
      (polygon_data != "bench" && polygon_data != "cli")) {
    std::fprintf(stderr, "epochs, threads and sample counts must be positive; --polygon-data bench or cli\n");
    return 2;
  }

  std::vector<Run> runs;
  if (problems.find("block") != std::string::npos) {
    const learn::BlockDataset data = bench::block_dataset(block_samples);
    for (learn::BlockMethod m : {learn::BlockMethod::hard, learn::BlockMethod::relaxed, learn::BlockMethod::convex})
      for (double f : {10.0, 0.3}) {
        runs.push_back(block_run(m, f, data, block_epochs, threads));
        print_summary(runs.back());
      }
  }
  if (problems.find("polygon") != std::string::npos) {
    const bool cli = polygon_data == "cli";
    learn::PolygonDataset data = bench::polygon_dataset(8, 7);
    if (cli) {  // as `lcprelax learn polygon --samples 400 --seed 1`
      int trajectories = 10;
      data = bench::polygon_dataset(trajectories, 1);
      while (data.transitions.size() < 400) data = bench::polygon_dataset(trajectories *= 2, 1);
      data.transitions.resize(400);
    }
    for (learn::PolygonMethod m : {learn::PolygonMethod::relaxed, learn::PolygonMethod::hard,
                                   learn::PolygonMethod::convex}) {
      runs.push_back(polygon_run(m, data, cli, polygon_epochs, threads));
      print_summary(runs.back());
    }
  }

  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "problem,method,init,epoch,seconds,loss,validation_loss,error,mu_error,failed\n";
    for (const Run& r : runs)
      for (const Point& p : r.points)
        out << r.problem << ',' << r.method << ',' << r.init << ',' << p.epoch << ',' << cell(p.seconds) << ','
            << cell(p.loss) << ',' << cell(p.validation_loss) << ',' << cell(p.error) << ',' << cell(p.mu_error) << ','
            << p.failed << '\n';
    if (!out) {
      std::fprintf(stderr, "%s: write failed\n", csv.c_str());
      return 2;
    }
  }
  return 0;
}
