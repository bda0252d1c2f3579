// `lcprelax lcp FILE.dat [--solver lemke|ipm] [--solution OUT.json] [--json]` and
// `lcprelax fc2d FILE.dat [--solver lemke|ipm] [--solution OUT.json] [--json]` (docs/cli.md):
// Siconos numerics problems, errors as Siconos defines them (io/siconos_errors.hpp). Human
// output: a brief report (cli_report.hpp) of the same fields, status first.
// lcp JSON: status, n, error, pivots (lemke) or iterations (ipm), seconds, and message when
// not solved; OUT: z, w, written only when solved (else a line on stderr says so).
// fc2d JSON: status, contacts, error, seconds (lemke: pivots, crash_sweeps, crash_pivots,
// purification_steps, start = guess | crash | cold); OUT: r, u (u = W r + q). fc2d is
// solved as the LCP of lcp/fc2d_lcp.hpp; with --solver ipm that LCP must be monotone, which
// it generally is not: then bad input (exit 2) saying so. Lemke starts by default from the
// answer of projected Gauss–Seidel sweeps purified into a vertex basis (--crash purify,
// lcp/fc2d_pgs.hpp; purified start of lemke.hpp), or from the basis that answer suggests
// (--crash pgs; crash start of lemke.hpp).
#include "cli_common.hpp"
#include "cli_report.hpp"

#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/fc2d_pgs.hpp>
#include <lcprelax/lcp/lcp_ipm.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <iostream>
#include <memory>

namespace lcprelax::cli {
namespace {

struct LcpOptions {
  std::string file;
  std::string solver = "lemke";
  std::string solution;
  std::string crash = "purify";  // fc2d only
  int crash_sweeps = 50;
  bool json = false;
};

LcpResult solve(const SparseMatrix& M, const Vector& q, const std::string& solver) {
  if (solver == "ipm") return solve_lcp_ipm(M, q);
  LemkeSolver lemke;
  lemke.setup(M, q);
  return lemke.solve();
}

// The JSON object, or the brief report (cli_report.hpp) made from the same fields: status
// first, then the problem's size, the Siconos error, the solver's work and the time.
void report(const LcpOptions& o, const Json& j) {
  if (o.json) {
    print_json(j);
    return;
  }
  const auto number = [&j](const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
  };
  BriefReport r;
  r.add("status", j["status"].get<std::string>());
  if (j.contains("message")) r.add("message", j["message"].get<std::string>());
  if (j.contains("n")) r.add_count("size", j["n"].get<long long>(), "unknowns");
  if (j.contains("contacts")) r.add_count("contacts", j["contacts"].get<long long>());
  r.add("Siconos error", number("error"), "", 3);
  if (j.contains("iterations")) r.add_count("iterations", j["iterations"].get<long long>(), "(interior point)");
  if (j.contains("pivots")) r.add_count("pivots", j["pivots"].get<long long>(), "(Lemke)");
  if (j.contains("start")) {
    const long long purified = j.value("purification_steps", 0LL);
    r.add("start", j["start"].get<std::string>() + " (" + std::to_string(j["crash_sweeps"].get<int>()) +
                       " Gauss-Seidel sweeps, " +
                       (purified > 0 ? std::to_string(purified) + " purification steps, " : std::string()) +
                       std::to_string(j["crash_pivots"].get<long long>()) + " pivots from their basis)");
  }
  r.add("time", number("seconds"), "s", 3);
  r.print();
}

// --solution OUT is written only for a solved problem (a failed solve's z, r can be huge and
// meaningless: fc2d wrote r = [4e7, 0]); otherwise stderr says it was not written.
void write_solution(const LcpOptions& o, bool solved, const Json& solution) {
  if (o.solution.empty()) return;
  if (solved) write_json_file(o.solution, solution);
  else std::cerr << "lcprelax: not solved: --solution " << o.solution << " not written\n";
}

int run_lcp(const LcpOptions& o) {
  require_writable_file("--solution", o.solution);
  const io::LcpData d = io::read_siconos_lcp(o.file);
  const Stopwatch watch;
  const LcpResult r = solve(d.M, d.q, o.solver);
  const double seconds = watch.seconds();
  const bool ok = r.info.status == LcpStatus::solved;
  Json j;
  j["status"] = to_string(r.info.status);
  j["n"] = d.q.size();
  j["error"] = ok ? number_or_null(io::lcp_error(d.M, d.q, r.z)) : Json(nullptr);
  j[o.solver == "ipm" ? "iterations" : "pivots"] = r.info.pivots;
  j["seconds"] = seconds;
  if (!ok) j["message"] = r.info.message;
  write_solution(o, ok, Json{{"z", array_or_nulls(r.z)}, {"w", array_or_nulls(r.w)}});
  report(o, j);
  return ok ? kExitSuccess : kExitSolveFailed;
}

int run_fc2d(const LcpOptions& o) {
  require_option(o.crash == "pgs" || o.crash == "purify" || o.crash == "none", "--crash",
                 "must be pgs, purify or none");
  require_option(o.crash_sweeps >= 1 && o.crash_sweeps <= 100000, "--crash-sweeps", "must be in [1, 100000]");
  require_writable_file("--solution", o.solution);
  const io::Fc2dData d = io::read_siconos_fc2d(o.file);
  const Stopwatch watch;
  const Fc2dLcp lcp = fc2d_to_lcp(d.W, d.q, d.mu);
  LcpResult r;
  int sweeps = 0;
  if (o.solver == "lemke" && o.crash != "none") {
    // Crash start (lemke.hpp): Lemke from the basis that PGS sweeps suggest (fc2d_pgs.hpp),
    // or from their answer purified into a vertex basis first (--crash purify).
    r = solve_fc2d_lemke_crash(d.W, d.q, d.mu, lcp, o.crash_sweeps, LemkeSettings{}, &sweeps,
                               o.crash == "purify" ? Fc2dCrash::purified : Fc2dCrash::basis);
  } else {
    try {
      r = solve(lcp.M, lcp.q, o.solver);
    } catch (const InputError& e) {  // ipm on the (generally non-monotone) LCP of the fc2d problem
      throw InputError(std::string("--solver ") + o.solver + ": " + e.what() +
                       " (the LCP of a 2-D frictional contact problem, lcp/fc2d_lcp.hpp, is generally not "
                       "monotone: use --solver lemke)");
    }
  }
  Vector reactions, velocities;
  const bool ok = r.info.status == LcpStatus::solved;
  if (r.z.size() == lcp.q.size()) fc2d_from_lcp(r.z, d.W, d.q, reactions, velocities);
  const double seconds = watch.seconds();
  Json j;
  j["status"] = to_string(r.info.status);
  j["contacts"] = d.contacts;
  j["error"] = ok ? number_or_null(io::fc2d_error(d, reactions)) : Json(nullptr);
  j["seconds"] = seconds;
  if (o.solver == "lemke") {
    j["pivots"] = r.info.pivots;
    j["crash_sweeps"] = sweeps;
    j["crash_pivots"] = r.info.crash_pivots;
    j["purification_steps"] = r.info.purification_steps;
    // How the solution was reached: the PGS basis was already the solution's (guess), Lemke
    // from it (crash), or from the all-w basis (cold: --crash none, or after a failed crash).
    j["start"] = r.info.warm_started                                      ? "guess"
                 : r.info.crash_started && r.info.crash_pivots == r.info.pivots ? "crash"
                                                                                : "cold";
  }
  if (!ok) j["message"] = r.info.message;
  write_solution(o, ok, Json{{"r", array_or_nulls(reactions)}, {"u", array_or_nulls(velocities)}});
  report(o, j);
  return ok ? kExitSuccess : kExitSolveFailed;
}

Command add_command(CLI::App& parent, const char* name, const char* help, int (*run)(const LcpOptions&)) {
  auto options = std::make_shared<LcpOptions>();
  const bool fc2d = run == run_fc2d;
  CLI::App* app = parent.add_subcommand(name, help);
  app->add_option("file", options->file,
                  fc2d ? "Siconos numerics 2-D frictional contact file (.dat; docs/formats.md)"
                       : "Siconos numerics LCP file (.dat; docs/formats.md)")
      ->required();
  app->add_option("--solver", options->solver,
                  fc2d ? "lemke (pivoting; the default) or ipm (interior point; refused unless the problem's LCP is "
                         "monotone, which a frictional contact problem generally is not)"
                       : "lemke (pivoting; any M, the default) or ipm (interior point; needs a monotone M, i.e. "
                         "M + Mᵀ positive semidefinite)")
      ->check(CLI::IsMember({"lemke", "ipm"}))
      ->capture_default_str();
  app->add_option("--solution", options->solution,
                  fc2d ? "write the reactions r and velocities u = W r + q to this JSON file (only when solved)"
                       : "write z and w = M z + q to this JSON file (only when solved)");
  if (fc2d) {
    app->add_option("--crash", options->crash,
                    "lemke's first basis: pgs (the one that projected Gauss-Seidel sweeps suggest), purify (their "
                    "answer purified into a vertex basis first) or none (Lemke's usual start)")
        ->capture_default_str();
    app->add_option("--crash-sweeps", options->crash_sweeps, "most Gauss-Seidel sweeps of --crash pgs or purify")
        ->capture_default_str();
  }
  add_json_flag(*app, options->json);
  app->footer(exit_codes_help("solved (status solved; the Siconos error is printed)",
                              "not solved (status ray_termination, pivot_limit or numerical_error; message says why)"));
  return Command{app, [options, run] { return run(*options); }};
}

}  // namespace

Command add_lcp_command(CLI::App& parent) {
  return add_command(parent, "lcp", "Solve a linear complementarity problem 0 ≤ z ⊥ Mz + q ≥ 0 read from a Siconos file", run_lcp);
}

Command add_fc2d_command(CLI::App& parent) {
  return add_command(parent, "fc2d", "Solve a 2-D frictional contact problem read from a Siconos file (as an LCP)", run_fc2d);
}

}  // namespace lcprelax::cli
