// KKT factorization backends of the interior-point QP (QpSettings::kkt_backend) side by
// side: CHOLMOD, MUMPS through PETSc in one process, and MUMPS distributed over the MPI
// ranks, on Maros–Meszaros problems and a random large sparse QP (random_qp.hpp).
//
//   run_kkt_backends [--data tests/data/maros_meszaros] [--problems CVXQP1_S,...]
//                    [--random-n 30000] [--backends cholmod,mumps,mumps_distributed]
//                    [--reps 1] [--time-limit 120] [--csv OUT] [--append]
//   (as root: OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1)
//   mpiexec -n 2 --oversubscribe
//     run_kkt_backends --backends mumps_distributed --csv OUT --append
//
// Every (problem, backend): a fresh QpSolver with library defaults except kkt_backend and
// time_limit, setup() + solve(), --reps times (the fastest run is kept; every rank runs
// every solve collectively, the distributed backend needs that). Times: wall clock of
// rank 0 between barriers (setup + solve), QpInfo's setup, solve and factorization
// seconds. One MpiSession for the whole run, so PETSc/MPI start-up is NOT in the times
// (it is in `lcprelax qp --kkt-backend mumps`'s run time). A backend that needs PETSc is
// skipped with a message in a build without it.
// Columns: problem, n, rows, backend, ranks, status, iterations, factorizations,
// objective (17 digits), total_s, setup_s, solve_s, factor_s, factor_ms_each
// (factor_s / factorizations), over_cholmod (total_s / CHOLMOD's total_s of the same
// problem in the same CSV file, if there). Exit 0 (whatever the solves' outcomes); 2 on
// bad arguments or an unreadable problem.
#include "csv_table.hpp"
#include "pile_timing.hpp"
#include "random_qp.hpp"

#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;

struct Problem {
  std::string name;
  QpProblem qp;
};

struct Row {
  std::string problem, backend, status;
  Index n = 0, rows = 0;
  int iterations = 0, factorizations = 0;
  double objective = std::numeric_limits<double>::quiet_NaN();
  double total = std::numeric_limits<double>::infinity(), setup = 0.0, solve = 0.0, factor = 0.0;
};

KktBackend parse_backend(const std::string& s) {
  for (KktBackend b : {KktBackend::cholmod, KktBackend::mumps, KktBackend::mumps_distributed})
    if (s == to_string(b)) return b;
  throw std::invalid_argument("--backends: unknown backend '" + s + "'");
}

Row run(const Problem& p, KktBackend backend, int reps, double time_limit) {
  Row r;
  r.problem = p.name;
  r.backend = to_string(backend);
  r.n = p.qp.num_variables();
  r.rows = p.qp.num_equalities() + p.qp.num_inequalities();
  QpSettings s;
  s.kkt_backend = backend;
  s.time_limit = time_limit;
  for (int k = 0; k < reps; ++k) {
    QpSolver solver(s);
    mpi::mpi_barrier();
    const double t0 = bench::now_seconds();
    try {
      solver.setup(p.qp);
      const QpInfo& info = solver.solve().info;
      mpi::mpi_barrier();
      const double wall = bench::now_seconds() - t0;
      if (wall < r.total) {
        r.total = wall, r.setup = info.setup_seconds, r.solve = info.solve_seconds, r.factor = info.factor_seconds;
        r.status = to_string(info.status);
        r.iterations = info.iterations;
        r.factorizations = info.factorizations;
        r.objective = info.objective;
      }
    } catch (const std::exception& e) {
      r.status = std::string("error: ") + e.what();
      for (char& c : r.status)
        if (c == ',' || c == '\n') c = ';';
      return r;
    }
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  mpi::MpiSession session(&argc, &argv);
  CLI::App app{"KKT backends of the QP: CHOLMOD vs MUMPS (1 process, distributed)"};
  std::string data = "tests/data/maros_meszaros", csv;
  std::string problems = "CVXQP1_S,PRIMAL1,MOSARQP1,CONT-050,STCQP1,LISWET1,AUG2D";
  std::string backends = "cholmod,mumps,mumps_distributed";
  Index random_n = 30000;
  int reps = 1;
  double time_limit = 120.0;
  bool append = false;
  app.add_option("--data", data, "directory of the .qps files")->capture_default_str();
  app.add_option("--problems", problems, "Maros–Meszaros problem names")->capture_default_str();
  app.add_option("--random-n", random_n, "variables of the random QP (0: none)")->capture_default_str();
  app.add_option("--backends", backends, "cholmod, mumps, mumps_distributed")->capture_default_str();
  app.add_option("--reps", reps, "runs per problem and backend (fastest kept)")->capture_default_str();
  app.add_option("--time-limit", time_limit, "QpSettings::time_limit (s)")->capture_default_str();
  app.add_option("--csv", csv, "CSV output (rank 0)");
  app.add_flag("--append", append, "append rows to an existing CSV");
  CLI11_PARSE(app, argc, argv);
  const int rank = mpi::mpi_rank(), ranks = mpi::mpi_size();

  std::vector<KktBackend> chosen;
  std::vector<Problem> set;
  try {
    for (const std::string& b : bench::split_list(backends)) {
      const KktBackend k = parse_backend(b);
      if (k != KktBackend::cholmod && !mpi::petsc_available()) {
        if (rank == 0) std::fprintf(stderr, "built without PETSc: backend %s skipped\n", b.c_str());
        continue;
      }
      chosen.push_back(k);
    }
    if (reps < 1) throw std::invalid_argument("--reps must be >= 1");
    for (const std::string& name : bench::split_list(problems))
      set.push_back({name, io::read_qps(data + "/" + name + ".qps").problem});
    if (random_n > 0) set.push_back({"random_" + std::to_string(random_n), bench::make_random_qp(random_n, 2024).problem});
  } catch (const std::exception& e) {
    if (rank == 0) std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }

  std::vector<Row> rows;
  if (rank == 0)
    std::printf("%-12s %7s %7s %-18s %5s %-18s %5s %6s %10s %10s %10s  %s\n", "problem", "n", "rows", "backend", "ranks",
                "status", "iter", "facts", "total_s", "factor_s", "ms/fact", "objective");
  for (const Problem& p : set)
    for (KktBackend b : chosen) {
      const Row r = run(p, b, reps, time_limit);
      if (rank == 0)
        std::printf("%-12s %7d %7d %-18s %5d %-18s %5d %6d %10.4g %10.4g %10.4g  %.10g\n", r.problem.c_str(), r.n,
                    r.rows, r.backend.c_str(), ranks, r.status.c_str(), r.iterations, r.factorizations, r.total,
                    r.factor, r.factorizations > 0 ? 1e3 * r.factor / r.factorizations : 0.0, r.objective);
      std::fflush(stdout);
      rows.push_back(r);
    }

  if (rank == 0 && !csv.empty()) {
    const bool header = !append || !std::filesystem::exists(csv);
    std::map<std::string, double> cholmod;  // problem → CHOLMOD total_s (this run or the file)
    if (!header) {
      std::ifstream in(csv);
      std::string line;
      std::getline(in, line);
      while (std::getline(in, line)) {
        const std::vector<std::string> f = bench::split_list(line);
        if (f.size() > 9 && f[3] == "cholmod") cholmod[f[0]] = std::stod(f[9]);
      }
    }
    for (const Row& r : rows)
      if (r.backend == "cholmod") cholmod[r.problem] = r.total;
    std::ofstream out(csv, header ? std::ios::trunc : std::ios::app);
    if (header)
      out << "problem,n,rows,backend,ranks,status,iterations,factorizations,objective,total_s,setup_s,solve_s,"
             "factor_s,factor_ms_each,over_cholmod\n";
    for (const Row& r : rows) {
      char objective[64];
      std::snprintf(objective, sizeof objective, "%.17g", r.objective);
      out << r.problem << ',' << r.n << ',' << r.rows << ',' << r.backend << ',' << ranks << ',' << r.status << ','
          << r.iterations << ',' << r.factorizations << ',' << objective << ',' << r.total << ',' << r.setup << ','
          << r.solve << ',' << r.factor << ',';
      if (r.factorizations > 0) out << 1e3 * r.factor / r.factorizations;
      out << ',';
      const auto c = cholmod.find(r.problem);
      if (c != cholmod.end() && std::isfinite(r.total)) out << r.total / c->second;
      out << '\n';
    }
    if (!out) {
      std::fprintf(stderr, "%s: write failed\n", csv.c_str());
      return 2;
    }
  }
  return 0;
}
