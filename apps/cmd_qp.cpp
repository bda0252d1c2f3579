// `lcprelax qp FILE.qps [--eps E] [--max-iter N] [--time-limit S] [--verbose] [--solution OUT.json] [--json]`
// (docs/cli.md): reads a QPS file, solves it with the interior-point QP and reports status,
// objective, iterations, residuals, duality gap, the setup + solve wall time (s) and, unless
// solved, the solver's message: a brief report (cli_report.hpp) or, with --json, one JSON
// object whose fields docs/cli.md lists. A P that is not positive semidefinite is bad input (exit 2).
// With --solution (only with a solution: solved or solved_inaccurate), OUT.json holds `x`,
// `y_rows` (one multiplier per constraint row of the file, QpResult::z, since the reader
// puts every row in G) and `y_bounds` (QpResult::z_bounds), signed as in
// docs/conventions.md (Px + q + Cᵀy_rows + y_bounds = 0).
#include "cli_common.hpp"
#include "cli_report.hpp"

#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/sparse/dense_ldlt.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <iostream>
#include <memory>

namespace lcprelax::cli {
namespace {

struct QpOptions {
  std::string file;
  double eps = QpSettings{}.eps_abs;
  int max_iter = QpSettings{}.max_iter;
  std::string solution;
  std::string kkt_backend = "automatic";
  double time_limit = QpSettings{}.time_limit;
  bool verbose = false;
  bool json = false;
};

QpSettings settings_from(const QpOptions& o) {
  require_option(std::isfinite(o.eps) && o.eps > 0.0, "--eps", "must be a positive finite number");
  require_option(o.max_iter >= 1, "--max-iter", "must be at least 1");
  QpSettings s;
  s.eps_abs = o.eps;
  s.max_iter = o.max_iter;
  require_option(o.time_limit > 0.0, "--time-limit", "must be positive");
  s.time_limit = o.time_limit;
  s.verbose = o.verbose;
  if (o.kkt_backend == "automatic") s.kkt_backend = KktBackend::automatic;
  else if (o.kkt_backend == "cholmod") s.kkt_backend = KktBackend::cholmod;
  else if (o.kkt_backend == "dense") s.kkt_backend = KktBackend::dense;
  else if (o.kkt_backend == "mumps") s.kkt_backend = KktBackend::mumps;
  else if (o.kkt_backend == "mumps-distributed") s.kkt_backend = KktBackend::mumps_distributed;
  else throw InputError("--kkt-backend: must be automatic, cholmod, dense, mumps or mumps-distributed");
  const std::string error = s.validation_error();
  if (!error.empty()) throw InputError("invalid solver settings: " + error);
  return s;
}

Json report_json(const QpInfo& info, double seconds) {
  Json j;
  j["status"] = to_string(info.status);
  j["objective"] = number_or_null(info.objective);
  j["iterations"] = info.iterations;
  j["primal_residual"] = number_or_null(info.primal_residual);
  j["dual_residual"] = number_or_null(info.dual_residual);
  j["duality_gap"] = number_or_null(info.duality_gap);
  j["seconds"] = number_or_null(seconds);
  if (info.status != QpStatus::solved) j["message"] = info.message;
  return j;
}

Json solution_json(const QpResult& result) {
  Json j;
  j["x"] = array_or_nulls(result.x);
  j["y_rows"] = array_or_nulls(result.z);
  j["y_bounds"] = array_or_nulls(result.z_bounds);
  return j;
}

// The brief report (cli_report.hpp): status first, then the problem and the solve.
void print_report(const io::QpsModel& model, const QpInfo& info, double seconds) {
  const QpProblem& p = model.problem;
  BriefReport r;
  r.add("status", to_string(info.status));
  if (info.status != QpStatus::solved && !info.message.empty()) r.add("message", info.message);
  r.add("problem", model.name.empty() ? std::string("(unnamed)") : model.name);
  r.add("size", std::to_string(p.num_variables()) + " variables, " + std::to_string(p.num_inequalities()) +
                    " constraint rows");
  r.add("nonzeros", std::to_string(p.P.nonZeros()) + " in P (upper triangle), " + std::to_string(p.G.nonZeros()) +
                        " in the constraint rows");
  r.add("objective", info.objective, "", 12);
  r.add_count("iterations", info.iterations);
  r.add("primal residual", info.primal_residual, "", 3);
  r.add("dual residual", info.dual_residual, "", 3);
  r.add("duality gap", info.duality_gap, "", 3);
  r.add("time", seconds, "s (setup + solve)", 3);
  r.print();
}

int run_qp(const QpOptions& o) {
  const QpSettings settings = settings_from(o);
  require_writable_file("--solution", o.solution);
  const io::QpsModel model = io::read_qps(o.file);

  QpSolver solver(settings);
  const Stopwatch watch;
  solver.setup(model.problem);  // rejects invalid data (NaN, crossed bounds, nonconvex P) with InputError
  const QpResult& result = solver.solve();
  const double seconds = watch.seconds();

  // Written only with a usable solution (solved or solved_inaccurate), never a failed iterate.
  if (!o.solution.empty()) {
    if (has_solution(result.info.status)) write_json_file(o.solution, solution_json(result));
    else std::cerr << "lcprelax qp: " << to_string(result.info.status) << ": --solution " << o.solution << " not written\n";
  }
  if (o.json) {
    print_json(report_json(result.info, seconds));
  } else {
    print_report(model, result.info, seconds);
  }
  return result.info.status == QpStatus::solved ? kExitSuccess : kExitSolveFailed;
}

}  // namespace

Command add_qp_command(CLI::App& parent) {
  auto options = std::make_shared<QpOptions>();
  CLI::App* qp = parent.add_subcommand(
      "qp", "Solve a convex quadratic program read from a QPS file (the Maros–Meszaros format)");
  qp->add_option("file", options->file, "QPS file (free MPS with a QUADOBJ or QMATRIX section; docs/formats.md)")
      ->required();
  qp->add_option("--eps", options->eps,
                 "stop when the primal residual, the dual residual and the duality gap are all at most this "
                 "(absolute, unscaled)")
      ->capture_default_str();
  qp->add_option("--max-iter", options->max_iter, "most interior-point iterations")->capture_default_str();
  qp->add_option("--solution", options->solution,
                 "write the solution (x, y_rows, y_bounds) to this JSON file when solved or solved_inaccurate");
  qp->add_option("--kkt-backend", options->kkt_backend,
                 "how the linear systems are factorized: automatic (dense for small problems, at most " +
                     std::to_string(QpSettings{}.dense_max_kkt) +
                     " rows, else cholmod), cholmod (sparse), dense (at most " +
                     std::to_string(sparse::DenseLdlt::kMaxDimension) + " rows), mumps (needs PETSc) or "
                     "mumps-distributed (over the processes of mpiexec)")
      ->capture_default_str();
  qp->add_option("--time-limit", options->time_limit, "stop the solve after this many seconds (default: no limit)");
  qp->add_flag("--verbose", options->verbose, "print one line per interior-point iteration on stderr");
  add_json_flag(*qp, options->json);
  qp->footer(exit_codes_help("solved (status solved)", "not solved to --eps (status max_iterations, primal_infeasible, dual_infeasible, "
                             "time_limit, numerical_error or solved_inaccurate; message says why)"));
  return Command{qp, [options] { return run_qp(*options); }};
}

}  // namespace lcprelax::cli
