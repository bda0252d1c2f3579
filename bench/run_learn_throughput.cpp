// Learning throughput: samples per second of one loss + gradient evaluation over a whole
// dataset (learn::evaluate_mean, as one training step sees it), for the block and polygon
// losses (hard, relaxed, convex), at each OpenMP thread count of --threads in one run, and,
// when started under `mpiexec -n R`, data-parallel over the R ranks
// (evaluate_batch_distributed: samples sharded by rank, results all-gathered and summed in
// a fixed order).
//
//   run_learn_throughput [--threads 1,2] [--min-time 1] [--block-samples 400]
//                        [--polygon-trajectories 8] [--problems block,polygon]
//                        [--methods hard,relaxed,convex] [--csv OUT] [--append]
//   run_learn_throughput --check-mpi      # exit 0 iff built with PETSc/MPI (regenerate.sh)
//   OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  (as root)
//     mpiexec -n 2 --oversubscribe run_learn_throughput --threads 1 --csv OUT --append
//
// Data (learn_problems.hpp): block 400 transitions evaluated at μ = 0.3 (truth 0.1); the
// polygon's 8 throws (seed 7, 315 contact transitions) at its 25%-perturbed start (seed 3)
// — the data of bench_learn_block / bench_learn_polygon. One untimed evaluation first
// (workspaces, warm starts), then passes are repeated until --min-time seconds (the count
// is agreed over the ranks: every pass is collective). Time = wall clock of rank 0 between
// barriers. Columns: problem, method, ranks, threads, samples, passes, seconds_per_pass,
// samples_per_s, failed (per pass), loss (mean loss of the first, untimed pass of a fresh
// objective, 17 digits: equal across thread and rank counts when the reduction is
// order-fixed; the timed passes are warm-started by their predecessors), speedup_vs_1x1 (this row's samples/s
// over the 1-rank 1-thread row of the same problem and method, when that row is in the
// same CSV file; else empty). Rank 0 prints and writes; --append adds rows to an existing
// CSV without a header. Exit 0; 2 on bad arguments.
#include "learn_problems.hpp"
#include "csv_table.hpp"
#include "pile_timing.hpp"

#include <lcprelax/mpi/mpi_session.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;

struct Measurement {
  int passes = 0;
  double seconds_per_pass = 0.0;
  double failed = 0.0;
  double loss = 0.0;
};

// Times evaluate_mean passes (collective over the ranks when distributed).
Measurement time_passes(learn::Objective& objective, const learn::ParameterSet& theta,
                        const std::vector<Index>& samples, int threads, double min_time) {
  const bool distributed = mpi::mpi_size() > 1;
  // Untimed first pass (workspaces, warm starts); its loss, from a fresh objective, is the
  // one compared across thread and rank counts (later passes depend on how many passes
  // warm-started them).
  const double first_loss = learn::evaluate_mean(objective, theta, samples, threads, distributed).loss;
  mpi::mpi_barrier();
  double t0 = bench::now_seconds();
  learn::BatchResult r = learn::evaluate_mean(objective, theta, samples, threads, distributed);
  const std::vector<double> first = mpi::allgather({bench::now_seconds() - t0});
  const double slowest = *std::max_element(first.begin(), first.end());
  const int passes = std::max(1, std::min(10000, static_cast<int>(std::ceil(min_time / std::max(slowest, 1e-9)))));
  Measurement m;
  mpi::mpi_barrier();
  t0 = bench::now_seconds();
  int failed = 0;
  for (int k = 0; k < passes; ++k) {
    r = learn::evaluate_mean(objective, theta, samples, threads, distributed);
    failed += r.failed;
  }
  mpi::mpi_barrier();
  m.passes = passes;
  m.seconds_per_pass = (bench::now_seconds() - t0) / passes;
  m.failed = static_cast<double>(failed) / passes;
  m.loss = first_loss;
  return m;
}

// samples/s of the 1-rank 1-thread rows already in the CSV (for --append runs).
std::map<std::string, double> read_baselines(const std::string& csv) {
  std::map<std::string, double> base;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    const std::vector<std::string> f = bench::split_list(line);
    if (f.size() >= 8 && f[2] == "1" && f[3] == "1") base[f[0] + "/" + f[1]] = std::stod(f[7]);
  }
  return base;
}

}  // namespace

int main(int argc, char** argv) {
  mpi::MpiSession session(&argc, &argv);
  CLI::App app{"learning throughput: samples/s per method, threads and MPI ranks"};
  std::vector<int> thread_counts = {1, 2};
  double min_time = 1.0;
  Index block_samples = 400;
  int polygon_trajectories = 8;
  std::string problems = "block,polygon", methods = "hard,relaxed,convex", csv;
  bool append = false, check_mpi = false;
  app.add_flag("--check-mpi", check_mpi, "only exit 0 if this build has PETSc/MPI, else 1 (for scripts)");
  app.add_option("--threads", thread_counts, "OpenMP thread counts")->delimiter(',')->capture_default_str();
  app.add_option("--min-time", min_time, "seconds of timed passes per row")->capture_default_str();
  app.add_option("--block-samples", block_samples, "block transitions")->capture_default_str();
  app.add_option("--polygon-trajectories", polygon_trajectories, "polygon throws of 60 steps")->capture_default_str();
  app.add_option("--problems", problems, "block,polygon")->capture_default_str();
  app.add_option("--methods", methods, "hard,relaxed,convex")->capture_default_str();
  app.add_option("--csv", csv, "CSV output (rank 0)");
  app.add_flag("--append", append, "append rows to an existing CSV");
  CLI11_PARSE(app, argc, argv);
  if (check_mpi) return mpi::petsc_available() ? 0 : 1;
  for (int t : thread_counts)
    if (t < 1) {
      std::fprintf(stderr, "--threads: every count must be >= 1\n");
      return 2;
    }
  const int rank = mpi::mpi_rank(), ranks = mpi::mpi_size();

  struct Out {
    std::string problem, method;
    int threads;
    Index samples;
    Measurement m;
  };
  std::vector<Out> rows;
  const learn::BlockDataset block = bench::block_dataset(block_samples);
  const learn::PolygonDataset polygon = bench::polygon_dataset(polygon_trajectories, 7);
  const learn::ParameterSet polygon_theta = bench::polygon_start(0.25, 3);
  if (rank == 0)
    std::printf("%-8s %-8s %5s %7s %7s %6s %12s %12s %7s  %s\n", "problem", "method", "ranks", "threads", "samples",
                "passes", "ms/pass", "samples/s", "failed", "loss");
  for (const std::string& problem : bench::split_list(problems)) {
    for (const std::string& method : bench::split_list(methods)) {
      for (int threads : thread_counts) {
        Out o{problem, method, threads, 0, {}};
        if (problem == "block") {
          auto objective = learn::make_block_objective(learn::parse_block_method(method), block);
          o.samples = block.size();
          o.m = time_passes(*objective, learn::block_parameters(0.3, 1.0, 1.0), bench::all_samples(o.samples),
                            threads, min_time);
        } else if (problem == "polygon") {
          learn::PolygonLossSettings ls;
          ls.method = learn::parse_polygon_method(method);
          learn::PolygonObjective objective(polygon, learn::reference_polygon_model(), ls);
          o.samples = objective.num_samples();
          o.m = time_passes(objective, polygon_theta, bench::all_samples(o.samples), threads, min_time);
        } else {
          if (rank == 0) std::fprintf(stderr, "--problems: unknown '%s'\n", problem.c_str());
          return 2;
        }
        if (rank == 0)
          std::printf("%-8s %-8s %5d %7d %7d %6d %12.4g %12.4g %7g  %.17g\n", problem.c_str(), method.c_str(), ranks,
                      threads, static_cast<int>(o.samples), o.m.passes, 1e3 * o.m.seconds_per_pass,
                      o.samples / o.m.seconds_per_pass, o.m.failed, o.m.loss);
        std::fflush(stdout);
        rows.push_back(o);
      }
    }
  }

  if (rank == 0 && !csv.empty()) {
    const bool header = !append || !std::filesystem::exists(csv);
    std::map<std::string, double> base = header ? std::map<std::string, double>{} : read_baselines(csv);
    for (const Out& o : rows)
      if (ranks == 1 && o.threads == 1) base[o.problem + "/" + o.method] = o.samples / o.m.seconds_per_pass;
    std::ofstream out(csv, header ? std::ios::trunc : std::ios::app);
    if (header)
      out << "problem,method,ranks,threads,samples,passes,seconds_per_pass,samples_per_s,failed,loss,speedup_vs_1x1\n";
    for (const Out& o : rows) {
      const double rate = o.samples / o.m.seconds_per_pass;
      const auto b = base.find(o.problem + "/" + o.method);
      char loss[64];
      std::snprintf(loss, sizeof loss, "%.17g", o.m.loss);
      out << o.problem << ',' << o.method << ',' << ranks << ',' << o.threads << ',' << o.samples << ','
          << o.m.passes << ',' << o.m.seconds_per_pass << ',' << rate << ',' << o.m.failed << ',' << loss << ',';
      if (b != base.end()) out << rate / b->second;
      out << '\n';
    }
    if (!out) {
      std::fprintf(stderr, "%s: write failed\n", csv.c_str());
      return 2;
    }
  }
  return 0;
}
