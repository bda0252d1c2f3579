// Hypersparse entering columns in sparse Lemke (LemkeSettings::sparse_columns) against the
// dense triangular solve per pivot, in one run:
//   - fc2d files (Siconos format) as LCPs (fc2d_to_lcp): default LemkeSettings (sparse method,
//     retries on), each solved `--repeat` times per variant, variants interleaved;
//   - a dropping pile of polygons with the lcp contact model (--pile-bodies, --pile-steps):
//     the same scene stepped by two Simulators that differ only in sparse_columns.
// Reports per variant: status, pivots, CPU seconds (process CPU time, so other load on the
// machine cancels out), and the ratio dense/sparse of CPU time.
//
//   run_lemke_columns [FILE.dat ...] [--repeat 3] [--pile-bodies 0] [--pile-steps 60] [--seed 1]
//                     [--pile-sparse-only]
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct Outcome {
  std::string status;
  long pivots = 0;
  double seconds = 0.0;
};

Outcome solve_file(const SparseMatrix& M, const Vector& q, bool sparse_columns) {
  LemkeSettings s;
  s.method = LemkeMethod::sparse;
  s.sparse_columns = sparse_columns;
  LemkeSolver solver(s);
  const double t0 = cpu_seconds();
  solver.setup(M, q);
  const LcpResult& r = solver.solve();
  return {to_string(r.info.status), r.info.pivots, cpu_seconds() - t0};
}

Outcome run_pile(int bodies, int steps, std::uint64_t seed, bool sparse_columns) {
  PileOptions o;
  o.bodies = bodies;
  o.seed = seed;
  o.model = ContactModel::lcp;
  Scene scene = make_pile_scene(o);
  scene.settings.threads = 1;
  scene.settings.lemke.sparse_columns = sparse_columns;
  Simulator sim(scene.world, scene.settings);
  Outcome out;
  long failed = 0;
  const double t0 = cpu_seconds();
  for (int k = 0; k < steps; ++k) {
    const StepStats st = sim.step();
    out.pivots += st.work;
    failed += st.failed_islands;
  }
  out.seconds = cpu_seconds() - t0;
  out.status = failed == 0 ? "no failed island" : std::to_string(failed) + " failed islands";
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("sparse Lemke: hypersparse entering columns vs dense column solves, in one run");
  std::vector<std::string> files;
  int repeat = 3, pile_bodies = 0, pile_steps = 60;
  std::uint64_t seed = 1;
  bool pile_sparse_only = false;
  app.add_option("files", files, "fc2d files (Siconos format)");
  app.add_flag("--pile-sparse-only", pile_sparse_only, "run the pile with hypersparse columns only (for profiling)");
  app.add_option("--repeat", repeat, "solves per file and variant")->check(CLI::Range(1, 1000));
  app.add_option("--pile-bodies", pile_bodies, "bodies of the dropping pile (0: none)")->check(CLI::Range(0, 100000));
  app.add_option("--pile-steps", pile_steps, "steps of the pile")->check(CLI::Range(1, 100000));
  app.add_option("--seed", seed, "pile seed");
  CLI11_PARSE(app, argc, argv);

  std::printf("%-40s %-8s %-18s %9s %10s %8s\n", "problem", "columns", "status", "pivots", "cpu_s", "ratio");
  for (const std::string& f : files) {
    const io::Fc2dData d = io::read_siconos_fc2d(f);
    const Fc2dLcp lcp = fc2d_to_lcp(d.W, d.q, d.mu);
    Outcome dense, sparse;
    for (int k = 0; k < repeat; ++k) {  // interleaved
      const Outcome a = solve_file(lcp.M, lcp.q, false), b = solve_file(lcp.M, lcp.q, true);
      dense.status = a.status, dense.pivots = a.pivots, dense.seconds += a.seconds / repeat;
      sparse.status = b.status, sparse.pivots = b.pivots, sparse.seconds += b.seconds / repeat;
    }
    const std::string name = std::filesystem::path(f).stem().string();
    std::printf("%-40s %-8s %-18s %9ld %10.4f %8s\n", name.c_str(), "dense", dense.status.c_str(), dense.pivots,
                dense.seconds, "");
    std::printf("%-40s %-8s %-18s %9ld %10.4f %8.2f\n", name.c_str(), "sparse", sparse.status.c_str(), sparse.pivots,
                sparse.seconds, dense.seconds / sparse.seconds);
  }
  if (pile_bodies > 0) {
    const std::string name = "pile " + std::to_string(pile_bodies) + " bodies, " + std::to_string(pile_steps) + " steps";
    const Outcome dense = pile_sparse_only ? Outcome{"not run", 0, 0.0} : run_pile(pile_bodies, pile_steps, seed, false);
    const Outcome sparse = run_pile(pile_bodies, pile_steps, seed, true);
    std::printf("%-40s %-8s %-18s %9ld %10.4f %8s\n", name.c_str(), "dense", dense.status.c_str(), dense.pivots,
                dense.seconds, "");
    std::printf("%-40s %-8s %-18s %9ld %10.4f %8.2f\n", name.c_str(), "sparse", sparse.status.c_str(), sparse.pivots,
                sparse.seconds, dense.seconds / sparse.seconds);
  }
  return 0;
}
