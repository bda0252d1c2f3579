// Work-precision data: solution error against run
// time for the interior point at a sweep of tolerances, Lemke, the interior-point LCP,
// Clp's barrier, and the pile's trajectory error against a tightly solved reference.
//
//   run_work_precision [--qps-dir tests/data/maros_meszaros] [--lcp-dir tests/data/siconos/lcp]
//                      [--clp clp] [--pile-bodies 40] [--pile-steps 30 60 120] [--csv OUT.csv]
//
// CSV columns: experiment,solver,problem,tolerance,seconds,error,status
//   qp    error = |f − f_ref| / max(1, |f_ref|), f_ref the objective of lcprelax at
//         eps_abs = 1e-10 (1e-9 where that fails); seconds = best of 3 solves (setup
//         included); Clp: one barrier run at its default tolerance (wall time of the
//         process, import included), its objective scored the same way.
//   lcp   error = Siconos' LCP error ‖z − max(0, z − w)‖/‖q‖ (io/siconos_errors.hpp);
//         Lemke (exact pivoting, tolerance column 0) and the interior-point LCP
//         (lcp/lcp_ipm.hpp) at eps_abs 1e-4 … 1e-10 on the monotone Siconos LCPs.
//   pile  a 40-body pile (make_pile_scene, seed 1) after 30, 60 and 120 steps with the
//         convex model at eps_abs 1e-4 … 1e-10: error = largest position difference (m)
//         from the same run at eps_abs = 1e-11; seconds = total simulation time. A pile is
//         chaotic once bodies collide in numbers: differences of any size grow, so the
//         longer horizons measure that growth more than the tolerance. The LCP model (Lemke) has
//         no tolerance; its row gives its time and its difference from the convex
//         reference, which is a model difference (Stewart–Trinkle vs the two-phase
//         model), not a solver error: the status column says so.
#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/lcp/lcp_ipm.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>

#include "clp_runner.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;
namespace fs = std::filesystem;

struct Point {
  std::string experiment, solver, problem;
  double tolerance = 0.0, seconds = 0.0, error = 0.0;
  std::string status;
};

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<fs::path> files(const std::string& dir, const std::string& ext) {
  std::vector<fs::path> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ext) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

QpResult solve_qp(const QpProblem& p, double eps, double& best_seconds) {
  QpResult r;
  best_seconds = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    QpSettings s;
    s.eps_abs = eps;
    QpSolver solver(s);
    const auto t0 = std::chrono::steady_clock::now();
    solver.setup(p);
    r = solver.solve();
    best_seconds = std::min(best_seconds, since(t0));
    if (best_seconds > 1.0) break;  // large problems: one run is enough
  }
  return r;
}

void qp_points(const std::string& dir, const std::string& clp, std::vector<Point>& out) {
  for (const fs::path& path : files(dir, ".qps")) {
    const io::QpsModel model = io::read_qps(path.string());
    const QpProblem& p = model.problem;
    const std::string name = path.stem().string();
    double t = 0.0;
    QpResult ref = solve_qp(p, 1e-10, t);
    if (ref.info.status != QpStatus::solved) ref = solve_qp(p, 1e-9, t);
    if (ref.info.status != QpStatus::solved) {
      std::fprintf(stderr, "%s: no reference (%s), skipped\n", name.c_str(), to_string(ref.info.status));
      continue;
    }
    const double f_ref = p.objective(ref.x), scale = std::max(1.0, std::abs(f_ref));
    for (double eps : {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9}) {
      const QpResult r = solve_qp(p, eps, t);
      const double err = r.x.size() == p.num_variables() ? std::abs(p.objective(r.x) - f_ref) / scale : NAN;
      out.push_back({"qp", "lcprelax", name, eps, t, err, to_string(r.info.status)});
    }
    if (!clp.empty()) {
      const bench::ClpRun c = bench::run_clp_barrier(clp, path, fs::temp_directory_path() / "lcprelax_wp_clp", 60.0);
      out.push_back({"qp", "clp-barrier", name, 0.0, c.wall_seconds, std::abs(c.objective - f_ref) / scale, c.status});
    }
    std::fprintf(stderr, "qp %s done\n", name.c_str());
  }
}

void lcp_points(const std::string& dir, std::vector<Point>& out) {
  for (const fs::path& path : files(dir, ".dat")) {
    const io::LcpData d = io::read_siconos_lcp(path.string());
    const std::string name = path.stem().string();
    LemkeSolver lemke;
    lemke.setup(d.M, d.q);
    const auto t0 = std::chrono::steady_clock::now();
    const LcpResult& r = lemke.solve();
    const double t = since(t0);
    out.push_back({"lcp", "lemke", name, 0.0, t, r.z.size() ? io::lcp_error(d.M, d.q, r.z) : NAN, to_string(r.info.status)});
    for (double eps : {1e-4, 1e-6, 1e-8, 1e-10}) {
      QpSettings s;
      s.eps_abs = eps;
      const auto t1 = std::chrono::steady_clock::now();
      const LcpResult ri = solve_lcp_ipm(d.M, d.q, s);
      const double ti = since(t1);
      out.push_back({"lcp", "ipm", name, eps, ti, ri.z.size() ? io::lcp_error(d.M, d.q, ri.z) : NAN,
                     to_string(ri.info.status)});
    }
  }
}

std::vector<Vec3> simulate(const Scene& scene, const SimulatorSettings& settings, int steps, double& seconds) {
  Simulator sim = make_simulator(scene, settings);
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) sim.step();
  seconds = since(t0);
  std::vector<Vec3> poses;
  for (const RigidBody& b : sim.world().bodies) poses.push_back(b.pose);
  return poses;
}

double max_position_difference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i].head<2>() - b[i].head<2>()).norm());
  return d;
}

void pile_points(int bodies, int steps, std::vector<Point>& out) {
  PileOptions o;
  o.bodies = bodies;
  o.model = ContactModel::convex;
  const Scene scene = make_pile_scene(o);
  SimulatorSettings ref_settings;
  ref_settings.threads = 1;
  ref_settings.qp.eps_abs = 1e-11;
  double t = 0.0;
  const std::vector<Vec3> ref = simulate(scene, ref_settings, steps, t);
  const std::string name = std::to_string(bodies) + " bodies x " + std::to_string(steps) + " steps";
  out.push_back({"pile", "convex-ipm", name, 1e-11, t, 0.0, "reference"});
  for (double eps : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
    SimulatorSettings s = ref_settings;
    s.qp.eps_abs = eps;
    const std::vector<Vec3> poses = simulate(scene, s, steps, t);
    out.push_back({"pile", "convex-ipm", name, eps, t, max_position_difference(poses, ref), "ok"});
  }
  Scene lcp_scene = scene;
  lcp_scene.settings.model = ContactModel::lcp;
  const std::vector<Vec3> lcp = simulate(lcp_scene, ref_settings, steps, t);
  out.push_back({"pile", "lcp-lemke", name, 0.0, t, max_position_difference(lcp, ref),
                 "model difference to the convex reference"});
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"work-precision data: error against run time"};
  std::string qps_dir = "tests/data/maros_meszaros", lcp_dir = "tests/data/siconos/lcp", clp = "clp",
              csv = "work_precision.csv";
  int pile_bodies = 40;
  std::vector<int> pile_steps = {30, 60, 120};
  app.add_option("--qps-dir", qps_dir, "directory of QPS files (empty: skip)");
  app.add_option("--lcp-dir", lcp_dir, "directory of Siconos LCP files (empty: skip)");
  app.add_option("--clp", clp, "Clp executable (empty: skip Clp)");
  app.add_option("--pile-bodies", pile_bodies, "bodies of the pile experiment (0: skip)");
  app.add_option("--pile-steps", pile_steps, "horizons (steps) of the pile experiment");
  app.add_option("--csv", csv, "output CSV");
  CLI11_PARSE(app, argc, argv);

  std::vector<Point> points;
  if (!qps_dir.empty()) qp_points(qps_dir, clp, points);
  if (!lcp_dir.empty()) lcp_points(lcp_dir, points);
  if (pile_bodies > 0)
    for (int steps : pile_steps) pile_points(pile_bodies, steps, points);

  std::ofstream out(csv);
  if (!out) {
    std::fprintf(stderr, "cannot write %s\n", csv.c_str());
    return 2;
  }
  out << "experiment,solver,problem,tolerance,seconds,error,status\n";
  out.precision(6);
  for (const Point& p : points)
    out << p.experiment << ',' << p.solver << ',' << p.problem << ',' << p.tolerance << ',' << p.seconds << ','
        << p.error << ",\"" << p.status << "\"\n";
  std::printf("%zu points written to %s\n", points.size(), csv.c_str());
  return 0;
}
