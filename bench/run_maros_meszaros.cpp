// Maros–Meszaros report: lcprelax's interior-point QP and COIN-OR Clp's barrier side by
// side on every .qps file of a directory, at high accuracy (1e-9).
//
//   run_maros_meszaros DIR [--out results.csv] [--time-limit SEC] [--eps 1e-9]
//                          [--clp PATH_TO_CLP | --no-clp] [--only NAME,NAME,...] [--verbose]
//
// --only runs the named problems (file stems) of DIR; --verbose prints the solver's
// per-iteration log on stderr and, per problem, the roundoff floors of the dual residual and
// of the gap (u·Σ|terms| of xᵀPx, qᵀx, bᵀy, σ(z), σ(z_bounds)) with the largest multipliers; --no-exact-bound-steps and --no-clean-bound-multipliers
// switch off the QpSettings of those names, --no-primal-reg-drop sets
// QpSettings::primal_reg_drop = 0 (ablation), --primal-reg-drop V sets it to V;
// --kkt-backend NAME (automatic, cholmod, dense, mumps) sets QpSettings::kkt_backend.
//
// Success (qpbenchmark's "high accuracy" when eps = 1e-9):
// - lcprelax: status solved and the primal residual, dual residual and duality gap it
//   reports are all ≤ eps (they are also recomputed here: lcp_check_* columns);
// - Clp: status "optimal", its primal residual (computed here from its full-precision
//   solution) ≤ eps, and, when lcprelax succeeded too, the objectives agree:
//   |f_clp − f_lcp| ≤ 1e-6·max(1, |f_clp|, |f_lcp|). clp_success_strict also requires
//   Clp's dual residual and duality gap (its duals mapped by z = −π, z_bounds = −d; see
//   clp_runner.hpp) ≤ eps, the criterion lcprelax is held to.
// Times: lcprelax setup()+solve() (file reading excluded); Clp its own reported solve
// time (import excluded; the wall time of the process is in clp_wall_seconds). The shifted
// geometric mean sgm = exp(mean(log(t_i + 10))) − 10 counts a failure at the time limit.
#include "clp_runner.hpp"
#include "qp_check.hpp"

#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <unordered_map>
#include <vector>

namespace fs = std::filesystem;
using lcprelax::Index;
using lcprelax::Vector;

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kShift = 10.0;     // seconds, shifted geometric mean
constexpr double kObjRelTol = 1e-6;  // objective agreement between the two solvers

struct Options {
  fs::path dir;
  std::string out = "maros_meszaros_results.csv";
  double time_limit = 60.0;
  double eps = 1e-9;
  std::string clp = "clp";
  bool use_clp = true;
  bool verbose = false;
  bool exact_bound_steps = true, clean_bound_multipliers = true, primal_reg_drop = true;
  double primal_reg_drop_value = -1.0;  ///< < 0: QpSettings' default
  lcprelax::KktBackend kkt_backend = lcprelax::KktBackend::automatic;
  std::vector<std::string> only;  ///< file stems to run (empty: all)
};

struct Row {
  std::string problem;
  Index n = 0, m = 0;
  std::string lcp_status = "not_run", message;
  int lcp_iterations = 0;
  double lcp_seconds = kNan, lcp_objective = kNan, lcp_primal = kNan, lcp_dual = kNan, lcp_gap = kNan;
  lcprelax::bench::QpResiduals lcp_check{kNan, kNan, kNan, kNan};
  bool lcp_success = false;
  std::string clp_status = "not_run", clp_duals = "none";
  double clp_seconds = kNan, clp_wall = kNan, clp_objective = kNan;
  lcprelax::bench::QpResiduals clp_res{kNan, kNan, kNan, kNan};
  bool clp_objective_match = false, clp_success = false, clp_success_strict = false;
};

[[noreturn]] void usage(const std::string& error) {
  std::cerr << "error: " << error << "\nusage: run_maros_meszaros DIR [--out results.csv] [--time-limit SEC] "
            << "[--eps 1e-9] [--clp PATH_TO_CLP | --no-clp] [--only NAME,NAME,...] [--verbose]\n"
            << "       [--no-exact-bound-steps] [--no-clean-bound-multipliers] [--no-primal-reg-drop]\n"
            << "       [--primal-reg-drop V] [--kkt-backend automatic|cholmod|dense|mumps]\n";
  std::exit(2);
}

Options parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    try {
      if (a == "--out") o.out = value();
      else if (a == "--time-limit") o.time_limit = std::stod(value());
      else if (a == "--eps") o.eps = std::stod(value());
      else if (a == "--clp") o.clp = value();
      else if (a == "--no-clp") o.use_clp = false;
      else if (a == "--verbose") o.verbose = true;
      else if (a == "--no-exact-bound-steps") o.exact_bound_steps = false;
      else if (a == "--no-primal-reg-drop") o.primal_reg_drop = false;
      else if (a == "--no-clean-bound-multipliers") o.clean_bound_multipliers = false;
      else if (a == "--primal-reg-drop") o.primal_reg_drop_value = std::stod(value());
      else if (a == "--kkt-backend") {
        const std::string b = value();
        if (b == "automatic") o.kkt_backend = lcprelax::KktBackend::automatic;
        else if (b == "cholmod") o.kkt_backend = lcprelax::KktBackend::cholmod;
        else if (b == "dense") o.kkt_backend = lcprelax::KktBackend::dense;
        else if (b == "mumps") o.kkt_backend = lcprelax::KktBackend::mumps;
        else usage("unknown --kkt-backend " + b);
      }
      else if (a == "--only") {
        std::string list = value();
        for (std::size_t pos = 0; pos <= list.size();) {
          const std::size_t comma = std::min(list.find(',', pos), list.size());
          if (comma > pos) o.only.push_back(list.substr(pos, comma - pos));
          pos = comma + 1;
        }
      }
      else if (!a.empty() && a[0] == '-') usage("unknown option " + a);
      else if (o.dir.empty()) o.dir = a;
      else usage("more than one directory given");
    } catch (const std::logic_error&) {
      usage("bad number for " + a);
    }
  }
  if (o.dir.empty()) usage("no directory given");
  if (!(o.time_limit > 0.0) || !(o.eps > 0.0)) usage("--time-limit and --eps must be positive");
  return o;
}

void solve_lcprelax(const lcprelax::io::QpsModel& model, const Options& opt, Row& row) {
  lcprelax::QpSettings settings;
  settings.eps_abs = opt.eps;
  settings.time_limit = opt.time_limit;
  settings.verbose = opt.verbose;
  settings.exact_bound_steps = opt.exact_bound_steps;
  settings.clean_bound_multipliers = opt.clean_bound_multipliers;
  if (opt.primal_reg_drop_value >= 0.0) settings.primal_reg_drop = opt.primal_reg_drop_value;
  if (!opt.primal_reg_drop) settings.primal_reg_drop = 0.0;
  settings.kkt_backend = opt.kkt_backend;
  try {
    lcprelax::QpSolver solver(settings);
    const auto t0 = std::chrono::steady_clock::now();
    solver.setup(model.problem);
    const lcprelax::QpResult& r = solver.solve();
    row.lcp_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const lcprelax::QpInfo& info = r.info;
    row.lcp_status = lcprelax::to_string(info.status);
    row.lcp_iterations = info.iterations;
    row.lcp_objective = info.objective;
    row.lcp_primal = info.primal_residual;
    row.lcp_dual = info.dual_residual;
    row.lcp_gap = info.duality_gap;
    if (r.x.size() == model.problem.num_variables()) {
      row.lcp_check = lcprelax::bench::qp_residuals(model.problem, r.x, r.y, r.z, r.z_bounds);
      if (opt.verbose) {
        // Roundoff floor of the dual residual's evaluation in double: the largest row sum of
        // |terms| of Px + q + Aᵀy + Gᵀz + z_bounds times the unit roundoff 2⁻⁵³.
        const lcprelax::QpProblem& p = model.problem;
        Vector mag = p.q.cwiseAbs() + r.z_bounds.cwiseAbs();
        const lcprelax::SparseMatrix Pabs = p.P.cwiseAbs();
        mag += Pabs.selfadjointView<Eigen::Upper>() * r.x.cwiseAbs();
        if (p.A.rows()) mag += p.A.cwiseAbs().transpose() * r.y.cwiseAbs();
        if (p.G.rows()) mag += p.G.cwiseAbs().transpose() * r.z.cwiseAbs();
        std::fprintf(stderr, "dual residual evaluation floor: max_j sum|terms| = %.3e -> u*that = %.3e\n",
                     mag.maxCoeff(), mag.maxCoeff() * std::ldexp(1.0, -53));
        // The gap's terms: their sizes bound its evaluation error (u·Σ|terms|).
        const Vector px = p.P.selfadjointView<Eigen::Upper>() * r.x;
        const double xpx = r.x.dot(px), qx = p.q.dot(r.x), by = p.A.rows() ? p.b.dot(r.y) : 0.0;
        double sz = 0.0, szb = 0.0, ignored = 0.0;
        for (Index i = 0; i < r.z.size(); ++i) sz += lcprelax::bench::detail::support_term(r.z[i], p.l[i], p.u[i], ignored);
        for (Index j = 0; j < r.x.size(); ++j)
          szb += lcprelax::bench::detail::support_term(r.z_bounds[j], p.xl[j], p.xu[j], ignored);
        std::fprintf(stderr,
                     "gap terms: xPx %.3e qx %.3e by %.3e sigma(z) %.3e sigma(zb) %.3e -> u*sum %.3e; "
                     "max|y| %.2e max|z| %.2e max|zb| %.2e\n",
                     xpx, qx, by, sz, szb,
                     (std::abs(xpx) + std::abs(qx) + std::abs(by) + std::abs(sz) + std::abs(szb)) * std::ldexp(1.0, -53),
                     r.y.size() ? r.y.cwiseAbs().maxCoeff() : 0.0, r.z.size() ? r.z.cwiseAbs().maxCoeff() : 0.0,
                     r.z_bounds.cwiseAbs().maxCoeff());
      }
    }
    row.lcp_success = info.status == lcprelax::QpStatus::solved && row.lcp_primal <= opt.eps &&
                      row.lcp_dual <= opt.eps && row.lcp_gap <= opt.eps;
    if (!row.lcp_success && info.status != lcprelax::QpStatus::solved) row.message = info.message;
  } catch (const std::exception& e) {
    row.lcp_status = "exception";
    row.message = e.what();
  }
}

/// Maps Clp's solution to lcprelax's variable/row order by name (by position when Clp's
/// names are missing and the sizes agree). Returns "by_name", "by_position" or "unmapped".
std::string map_clp_solution(const lcprelax::io::QpsModel& model, const lcprelax::bench::ClpRun& run, Vector& x,
                             Vector& z, Vector& zb) {
  const Index n = model.problem.num_variables(), mi = model.problem.num_inequalities();
  x = Vector::Zero(n);
  zb = Vector::Zero(n);
  z = Vector::Zero(mi);
  const bool named = run.column_names.size() == run.x.size() && run.row_names.size() == run.row_dual.size();
  if (!named) {
    if (static_cast<Index>(run.x.size()) != n || static_cast<Index>(run.row_dual.size()) != mi) return "unmapped";
    for (Index j = 0; j < n; ++j) x[j] = run.x[j], zb[j] = -run.reduced_cost[j];
    for (Index i = 0; i < mi; ++i) z[i] = -run.row_dual[i];
    return "by_position";
  }
  std::unordered_map<std::string, Index> cols, rows;
  for (Index j = 0; j < n; ++j) cols.emplace(model.variable_names[j], j);
  for (Index i = 0; i < mi; ++i) rows.emplace(model.row_names[i], i);
  std::vector<char> col_seen(n, 0), row_seen(mi, 0);
  for (std::size_t k = 0; k < run.x.size(); ++k) {
    const auto it = cols.find(run.column_names[k]);
    if (it == cols.end()) return "unmapped";
    x[it->second] = run.x[k];
    zb[it->second] = -run.reduced_cost[k];
    col_seen[it->second] = 1;
  }
  for (std::size_t k = 0; k < run.row_dual.size(); ++k) {
    const auto it = rows.find(run.row_names[k]);
    if (it == rows.end()) continue;  // e.g. a free row Clp kept and lcprelax dropped
    z[it->second] = -run.row_dual[k];
    row_seen[it->second] = 1;
  }
  const bool complete = std::all_of(col_seen.begin(), col_seen.end(), [](char c) { return c != 0; }) &&
                        std::all_of(row_seen.begin(), row_seen.end(), [](char c) { return c != 0; });
  return complete ? "by_name" : "unmapped";
}

void solve_clp(const fs::path& file, const lcprelax::io::QpsModel* model, const Options& opt,
               const fs::path& work_dir, Row& row) {
  const lcprelax::bench::ClpRun run = lcprelax::bench::run_clp_barrier(opt.clp, file, work_dir, opt.time_limit);
  row.clp_status = run.status;
  row.clp_wall = run.wall_seconds;
  row.clp_seconds = std::isfinite(run.solve_seconds) ? run.solve_seconds : run.wall_seconds;
  row.clp_objective = run.objective;
  if (!run.message.empty()) row.message += (row.message.empty() ? "" : "; ") + ("clp: " + run.message);
  if (model != nullptr && !run.x.empty()) {
    Vector x, z, zb;
    row.clp_duals = map_clp_solution(*model, run, x, z, zb);
    if (row.clp_duals != "unmapped") row.clp_res = lcprelax::bench::qp_residuals(model->problem, x, Vector(), z, zb);
  }
  const double scale = std::max({1.0, std::abs(row.clp_objective), std::abs(row.lcp_objective)});
  row.clp_objective_match = std::abs(row.clp_objective - row.lcp_objective) <= kObjRelTol * scale;
  row.clp_success = run.status == "optimal" && std::isfinite(run.objective) &&
                    (row.clp_duals == "unmapped" || row.clp_duals == "none" || row.clp_res.primal <= opt.eps) &&
                    (!row.lcp_success || row.clp_objective_match);
  row.clp_success_strict = row.clp_success && row.clp_duals != "unmapped" && row.clp_duals != "none" &&
                           row.clp_res.dual <= opt.eps && row.clp_res.gap <= opt.eps;
}

std::string csv_text(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return out + "\"";
}

void write_csv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream out(path);
  if (!out) {
    std::cerr << "error: cannot write " << path << "\n";
    return;
  }
  out.precision(17);
  out << "problem,n,m,lcp_status,lcp_iterations,lcp_seconds,lcp_objective,lcp_primal_residual,"
         "lcp_dual_residual,lcp_duality_gap,lcp_check_primal,lcp_check_dual,lcp_check_gap,lcp_success,"
         "clp_status,clp_seconds,clp_wall_seconds,clp_objective,clp_primal_residual,clp_dual_residual,"
         "clp_duality_gap,clp_dual_sign_violation,clp_duals,clp_objective_match,clp_success,clp_success_strict,"
         "message\n";
  for (const Row& r : rows) {
    out << r.problem << ',' << r.n << ',' << r.m << ',' << r.lcp_status << ',' << r.lcp_iterations << ','
        << r.lcp_seconds << ',' << r.lcp_objective << ',' << r.lcp_primal << ',' << r.lcp_dual << ',' << r.lcp_gap
        << ',' << r.lcp_check.primal << ',' << r.lcp_check.dual << ',' << r.lcp_check.gap << ',' << r.lcp_success
        << ',' << r.clp_status << ',' << r.clp_seconds << ',' << r.clp_wall << ',' << r.clp_objective << ','
        << r.clp_res.primal << ',' << r.clp_res.dual << ',' << r.clp_res.gap << ',' << r.clp_res.sign_violation
        << ',' << r.clp_duals << ',' << r.clp_objective_match << ',' << r.clp_success << ','
        << r.clp_success_strict << ',' << csv_text(r.message) << '\n';
  }
}

double shifted_geometric_mean(const std::vector<double>& t) {
  double sum = 0.0;
  for (double v : t) sum += std::log(v + kShift);
  return t.empty() ? kNan : std::exp(sum / static_cast<double>(t.size())) - kShift;
}

void print_summary(const std::vector<Row>& rows, const Options& opt) {
  std::vector<double> t_lcp, t_clp;
  int ok_lcp = 0, ok_clp = 0, ok_clp_strict = 0;
  for (const Row& r : rows) {
    ok_lcp += r.lcp_success;
    ok_clp += r.clp_success;
    ok_clp_strict += r.clp_success_strict;
    t_lcp.push_back(r.lcp_success ? std::min(r.lcp_seconds, opt.time_limit) : opt.time_limit);
    t_clp.push_back(r.clp_success ? std::min(r.clp_seconds, opt.time_limit) : opt.time_limit);
  }
  const double count = static_cast<double>(std::max<std::size_t>(rows.size(), 1));
  std::printf("\nSummary over %zu problems (eps %.1e, time limit %.0f s, sgm shift %.0f s)\n", rows.size(), opt.eps,
              opt.time_limit, kShift);
  std::printf("  lcprelax  success %3d (%5.1f%%)  sgm time %.4f s\n", ok_lcp, 100.0 * ok_lcp / count,
              shifted_geometric_mean(t_lcp));
  if (opt.use_clp) {
    std::printf("  clp       success %3d (%5.1f%%)  sgm time %.4f s  (primal residual + objective criterion)\n",
                ok_clp, 100.0 * ok_clp / count, shifted_geometric_mean(t_clp));
    std::printf("  clp       strict  %3d (%5.1f%%)  (also dual residual and gap <= eps, duals z = -pi, zb = -d)\n",
                ok_clp_strict, 100.0 * ok_clp_strict / count);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse_args(argc, argv);
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(opt.dir, ec)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    const bool wanted = opt.only.empty() || std::find(opt.only.begin(), opt.only.end(),
                                                      entry.path().stem().string()) != opt.only.end();
    if (entry.is_regular_file() && ext == ".qps" && wanted) files.push_back(entry.path());
  }
  if (ec) usage("cannot read directory " + opt.dir.string() + ": " + ec.message());
  if (files.empty()) usage("no .qps files in " + opt.dir.string());
  std::sort(files.begin(), files.end());
  const fs::path work_dir = fs::temp_directory_path() / ("lcprelax_mm_" + std::to_string(::getpid()));

  std::printf("%-12s %7s %7s | %-17s %5s %10s %9s %9s %9s | %-11s %10s %9s %9s %4s\n", "problem", "n", "m",
              "lcprelax", "iter", "seconds", "primal", "dual", "gap", "clp", "seconds", "primal", "dual", "ok");
  std::vector<Row> rows;
  for (const fs::path& file : files) {
    Row row;
    row.problem = file.stem().string();
    lcprelax::io::QpsModel model;
    bool have_model = false;
    try {
      model = lcprelax::io::read_qps(file.string());
      have_model = true;
      row.n = model.problem.num_variables();
      row.m = model.problem.num_equalities() + model.problem.num_inequalities();
      solve_lcprelax(model, opt, row);
    } catch (const std::exception& e) {
      row.lcp_status = "read_error";
      row.message = e.what();
    }
    if (opt.use_clp) solve_clp(file, have_model ? &model : nullptr, opt, work_dir, row);
    std::printf("%-12s %7d %7d | %-17s %5d %10.4f %9.1e %9.1e %9.1e | %-11s %10.4f %9.1e %9.1e %2s%2s\n",
                row.problem.c_str(), row.n, row.m, row.lcp_status.c_str(), row.lcp_iterations, row.lcp_seconds,
                row.lcp_primal, row.lcp_dual, row.lcp_gap, row.clp_status.c_str(), row.clp_seconds,
                row.clp_res.primal, row.clp_res.dual, row.lcp_success ? "L" : "-", row.clp_success ? "C" : "-");
    std::fflush(stdout);
    rows.push_back(std::move(row));
  }
  fs::remove_all(work_dir, ec);
  write_csv(opt.out, rows);
  print_summary(rows, opt);
  std::printf("CSV written to %s\n", opt.out.c_str());
  return 0;
}
