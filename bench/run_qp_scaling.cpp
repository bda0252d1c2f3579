// Cost of the interior-point QP against problem size, forward (setup + solve) and
// backward (adjoint with the final factorization), with least-squares log-log slopes.
//
//   run_qp_scaling [--sizes 100,300,1000,3000,10000,30000,100000] [--min-time 1]
//                  [--max-reps 50] [--seed 2024] [--csv OUT.csv]
//
// Problems: bench/random_qp.hpp (banded random sparse convex QPs, n/4 equalities, n/2
// inequality rows, boxes; the bench_qp_random problems for the same seed), library
// defaults except max_iter = 500 (as bench_qp_random). Per size:
// - forward: a fresh QpSolver, setup() + solve(), repeated until --min-time seconds of
//   forward time or --max-reps runs (at least once); the MINIMUM wall time and the
//   minimum process CPU time over the runs (the least disturbed run on a shared machine);
// - backward: backward(dl_dx) on the last solved solver, repeated the same way.
// Columns: n, rows, nnz_P, factor_nnz, kkt_form, status, iterations, factorizations,
// forward_s, forward_cpu_s, forward_reps, factor_s (QpInfo::factor_seconds of the fastest
// run), backward_s, backward_cpu_s, backward_reps, backward_over_forward (wall).
// At the end: slopes of log(time) against log(n) over all sizes and over n ≥ 10⁴, for
// wall and CPU time, forward and backward, and of factor_nnz. Exit 0; 1 if a solve failed.
#include "pile_timing.hpp"
#include "random_qp.hpp"

#include <lcprelax/kkt/qp_solver.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;
using bench::cpu_seconds;
using bench::now_seconds;

struct Row {
  Index n = 0, rows = 0, nnz_p = 0;
  long factor_nnz = 0;
  std::string form, status;
  int iterations = 0, factorizations = 0;
  double fwd = std::numeric_limits<double>::infinity(), fwd_cpu = fwd, factor = 0.0;
  int fwd_reps = 0;
  double bwd = std::numeric_limits<double>::infinity(), bwd_cpu = bwd;
  int bwd_reps = 0;
  bool ok = false;
};

bool usable(QpStatus s) { return has_solution(s); }

Row measure(Index n, std::uint64_t seed, double min_time, int max_reps) {
  const bench::RandomQp qp = bench::make_random_qp(n, seed);
  QpSettings settings;
  settings.max_iter = 500;
  Row r;
  r.n = n;
  r.rows = qp.problem.num_equalities() + qp.problem.num_inequalities();
  r.nnz_p = static_cast<Index>(qp.problem.P.nonZeros());
  std::unique_ptr<QpSolver> solver;
  double spent = 0.0;
  while (r.fwd_reps < 1 || (spent < min_time && r.fwd_reps < max_reps)) {
    solver = std::make_unique<QpSolver>(settings);
    const double t0 = now_seconds(), c0 = cpu_seconds();
    solver->setup(qp.problem);
    const QpInfo& info = solver->solve().info;
    const double wall = now_seconds() - t0, cpu = cpu_seconds() - c0;
    spent += wall;
    ++r.fwd_reps;
    if (wall < r.fwd) r.fwd = wall, r.factor = info.factor_seconds;
    r.fwd_cpu = std::min(r.fwd_cpu, cpu);
    r.status = to_string(info.status);
    r.iterations = info.iterations;
    r.factorizations = info.factorizations;
    r.factor_nnz = info.kkt_factor_nnz;
    r.form = to_string(info.kkt_form);
    r.ok = usable(info.status);
    if (!r.ok) return r;
  }
  spent = 0.0;
  while (r.bwd_reps < 1 || (spent < min_time && r.bwd_reps < 20 * max_reps)) {
    const double t0 = now_seconds(), c0 = cpu_seconds();
    const QpGradient g = solver->backward(qp.dl_dx);
    const double wall = now_seconds() - t0, cpu = cpu_seconds() - c0;
    if (g.dq.size() != n) r.status = "backward_failed", r.ok = false;
    spent += wall;
    ++r.bwd_reps;
    r.bwd = std::min(r.bwd, wall);
    r.bwd_cpu = std::min(r.bwd_cpu, cpu);
  }
  return r;
}

void print_slopes(const std::vector<Row>& rows, Index from_n, const char* label) {
  std::vector<double> n, fwd, fwd_cpu, bwd, bwd_cpu, nnz;
  for (const Row& r : rows) {
    if (r.n < from_n || !r.ok) continue;
    n.push_back(static_cast<double>(r.n));
    fwd.push_back(r.fwd), fwd_cpu.push_back(r.fwd_cpu), bwd.push_back(r.bwd), bwd_cpu.push_back(r.bwd_cpu);
    nnz.push_back(static_cast<double>(r.factor_nnz));
  }
  std::printf("slope vs n (%s, %zu sizes): forward wall %.3f, forward CPU %.3f, backward wall %.3f, "
              "backward CPU %.3f, factor nnz %.3f\n",
              label, n.size(), bench::loglog_slope(n, fwd), bench::loglog_slope(n, fwd_cpu),
              bench::loglog_slope(n, bwd), bench::loglog_slope(n, bwd_cpu), bench::loglog_slope(n, nnz));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"QP forward/backward cost against size (random sparse QPs), log-log slopes"};
  std::vector<Index> sizes = {100, 300, 1000, 3000, 10000, 30000, 100000};
  double min_time = 1.0;
  int max_reps = 50;
  std::uint64_t seed = 2024;
  std::string csv;
  app.add_option("--sizes", sizes, "numbers of variables")->delimiter(',')->capture_default_str();
  app.add_option("--min-time", min_time, "seconds of repetitions per size and pass")->capture_default_str();
  app.add_option("--max-reps", max_reps, "most forward runs per size (backward: 20x)")->capture_default_str();
  app.add_option("--seed", seed, "random_qp.hpp seed")->capture_default_str();
  app.add_option("--csv", csv, "CSV output");
  CLI11_PARSE(app, argc, argv);
  for (Index n : sizes)
    if (n < 4) {
      std::fprintf(stderr, "--sizes: every n must be >= 4\n");
      return 2;
    }

  std::vector<Row> rows;
  bool failed = false;
  std::printf("%8s %7s %10s %5s %9s %10s %10s %5s %10s %10s %6s %9s  %s\n", "n", "rows", "factor_nnz", "iter",
              "form", "fwd_s", "fwd_cpu_s", "reps", "bwd_ms", "bwd_cpu_ms", "reps", "bwd/fwd", "status");
  for (Index n : sizes) {
    const Row r = measure(n, seed, min_time, max_reps);
    failed = failed || !r.ok;
    std::printf("%8d %7d %10ld %5d %9s %10.4g %10.4g %5d %10.4g %10.4g %6d %9.4f  %s\n", n, r.rows, r.factor_nnz,
                r.iterations, r.form.c_str(), r.fwd, r.fwd_cpu, r.fwd_reps, 1e3 * r.bwd, 1e3 * r.bwd_cpu, r.bwd_reps,
                r.bwd / r.fwd, r.status.c_str());
    std::fflush(stdout);
    rows.push_back(r);
  }
  print_slopes(rows, 0, "all sizes");
  print_slopes(rows, 10000, "n >= 10^4");

  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "n,rows,nnz_P,factor_nnz,kkt_form,status,iterations,factorizations,forward_s,forward_cpu_s,forward_reps,"
           "factor_s,backward_s,backward_cpu_s,backward_reps,backward_over_forward\n";
    out.precision(6);
    for (const Row& r : rows)
      out << r.n << ',' << r.rows << ',' << r.nnz_p << ',' << r.factor_nnz << ',' << r.form << ',' << r.status << ','
          << r.iterations << ',' << r.factorizations << ',' << r.fwd << ',' << r.fwd_cpu << ',' << r.fwd_reps << ','
          << r.factor << ',' << r.bwd << ',' << r.bwd_cpu << ',' << r.bwd_reps << ',' << r.bwd / r.fwd << '\n';
    if (!out) {
      std::fprintf(stderr, "%s: write failed\n", csv.c_str());
      return 2;
    }
  }
  return failed ? 1 : 0;
}
