// Lemke peers: lcprelax's Lemke (dense and sparse basis) and Siconos numerics on every
// Siconos test problem (target: Siconos problems to error ≤ 1e-10).
//
//   run_lemke_peers [DATA_DIR] [--out lemke_peers.csv] [--dense-max-contacts 320]
//                   [--nsgs-max-iter 100000] [--pile NC]... [--refactor-interval K]
//                   [--no-files] [--no-siconos]
//
// DATA_DIR (default: the source tree's tests/data/siconos) holds lcp/*.dat and fc2d/*.dat.
// --pile NC (repeatable) adds the generated NC-contact pile of bench_lemke
// (lemke_problems.hpp, seed 2024) as an fc2d problem named pile_NC. --refactor-interval
// sets LemkeSettings::refactor_interval of the lcprelax solves (default: the library's);
// --no-files skips DATA_DIR, --no-siconos the Siconos solvers.
// Solvers per problem:
//   LCP:  lcprelax_dense, lcprelax_sparse (LemkeSolver with method dense / sparse),
//         siconos_lemke (lcp_lexicolemke through linearComplementarity_driver).
//   fc2d: lcprelax_dense (skipped above --dense-max-contacts contacts: minutes on the
//         667-contact granular problem), lcprelax_sparse (both on fc2d_to_lcp, 4nc
//         unknowns), lcprelax_crash (sparse, crash-started from 50 projected Gauss–Seidel
//         sweeps, lcp/fc2d_pgs.hpp, their time included; with LemkeSettings::crash_flip_rounds
//         as by default, and lcprelax_crash_noflip with 0), lcprelax_purify (the same PGS
//         answer purified into a vertex basis first: Fc2dCrash::purified, the default of
//         `lcprelax fc2d`), siconos_fc2d_lemke (SICONOS_FRICTION_2D_LEMKE, its own 3nc-unknown
//         LCP), siconos_fc2d_nsgs (SICONOS_FRICTION_2D_NSGS, tolerance 1e-10).
// Every answer is scored with lcprelax::io::lcp_error / io::fc2d_error, i.e. the error as
// Siconos defines it, recomputed from the returned z (LCP) or r (fc2d, u = W r + q):
// `error`. Siconos divides by ‖q‖₂ (LCP) or max(‖r‖, ‖u‖, ‖q‖) (fc2d) only when that
// exceeds DBL_EPSILON, so on a problem with tiny q (the granular file: ‖q‖₂ = 4e-18) the
// error is absolute and r = 0 already scores 2e-18. `error_scaled` is the same error on
// the problem scaled to ‖q‖₂ = 1 (q, z or r divided by ‖q‖₂): equal to `error` whenever
// Siconos normalizes, meaningful when it does not. The `siconos_residual` column is
// Siconos' own value (dparam[SICONOS_DPARAM_RESIDU]).
// `iterations`: lcprelax pivots (the first, z₀ entering, included); Siconos Lemke pivots
// (that one excluded) or NSGS sweeps. `ok` = status solved and error_scaled ≤ 1e-10.
// Times: one solve, wall clock, data conversion excluded; problems solving in under
// 10 ms are repeated up to 50 times and the minimum is reported.
#include "lemke_problems.hpp"
#include "siconos_runner.hpp"

#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/fc2d_pgs.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using lcprelax::Index;
using lcprelax::Vector;
using lcprelax::bench::SiconosFc2dSolver;
using lcprelax::bench::SiconosResult;

namespace {

constexpr double kTarget = 1e-10;  // Siconos error target

struct Options {
  fs::path dir = LCPRELAX_SICONOS_DATA_DIR;
  std::string out = "lemke_peers.csv";
  long dense_max_contacts = 320;
  long nsgs_max_iter = 100000;
  std::vector<Index> piles;
  int refactor_interval = lcprelax::LemkeSettings{}.refactor_interval;
  bool files = true, siconos = true;
};

struct Row {
  std::string problem, kind, solver, status;
  Index n = 0, contacts = 0;
  long iterations = 0;
  double error = std::numeric_limits<double>::quiet_NaN();
  double error_scaled = std::numeric_limits<double>::quiet_NaN();
  double siconos_residual = std::numeric_limits<double>::quiet_NaN();
  double seconds = 0.0;
  bool ok() const { return status == "solved" && error_scaled <= kTarget; }
};

struct Errors {
  double error, scaled;  // Siconos error as is, and on the problem scaled to ‖q‖₂ = 1
};
using Score = std::function<Errors(const Vector&)>;

// Runs `solve` (which returns its own solve time) once; if that is under 10 ms, repeats
// up to 50 times (or 0.2 s in all) and keeps the minimum.
double min_time(const std::function<double()>& solve) {
  double best = solve(), total = best;
  for (int k = 1; k < 50 && best < 0.01 && total < 0.2; ++k) {
    const double t = solve();
    best = std::min(best, t);
    total += t;
  }
  return best;
}

// A row for one lcprelax solve `run` (timed as a whole), scored by score(z).
Row lcprelax_row(const std::string& solver, const std::function<lcprelax::LcpResult()>& run, const Score& score) {
  lcprelax::LcpResult result;
  Row row;
  row.seconds = min_time([&] {
    const auto t0 = std::chrono::steady_clock::now();
    result = run();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  });
  row.solver = solver;
  row.status = lcprelax::to_string(result.info.status);
  row.iterations = result.info.pivots;
  if (result.info.status == lcprelax::LcpStatus::solved) {
    const Errors e = score(result.z);
    row.error = e.error;
    row.error_scaled = e.scaled;
  }
  return row;
}

lcprelax::LemkeSettings lemke_settings(lcprelax::LemkeMethod method, int refactor_interval) {
  lcprelax::LemkeSettings settings;
  settings.method = method;
  settings.refactor_interval = refactor_interval;
  return settings;
}

// LemkeSolver from the all-w basis, with the dense or sparse basis.
Row lemke_row(const lcprelax::SparseMatrix& M, const Vector& q, lcprelax::LemkeMethod method, int refactor_interval,
              const Score& score) {
  const char* name = method == lcprelax::LemkeMethod::dense ? "lcprelax_dense" : "lcprelax_sparse";
  return lcprelax_row(
      name,
      [&] {
        lcprelax::LemkeSolver solver(lemke_settings(method, refactor_interval));
        solver.setup(M, q);
        return solver.solve();
      },
      score);
}

// score(x) for Siconos' x (LCP: z, fc2d: r).
Row siconos_row(const std::string& solver, const std::function<SiconosResult()>& run, const Score& score) {
  SiconosResult r;
  Row row;
  row.solver = solver;
  row.seconds = min_time([&] {
    r = run();
    return r.seconds;
  });
  row.status = r.status();
  row.iterations = r.iterations;
  row.siconos_residual = r.residual;
  if (r.x.allFinite()) {
    const Errors e = score(r.x);
    row.error = e.error;
    row.error_scaled = e.scaled;
  }
  return row;
}

std::vector<fs::path> dat_files(const fs::path& dir) {
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".dat") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

void run_lcp(const fs::path& file, const Options& opt, std::vector<Row>& rows) {
  const lcprelax::io::LcpData d = lcprelax::io::read_siconos_lcp(file.string());
  const double s = d.q.norm() > 0 ? d.q.norm() : 1.0;
  const Vector q_scaled = d.q / s;
  const Score error = [&](const Vector& z) {
    return Errors{lcprelax::io::lcp_error(d.M, d.q, z), lcprelax::io::lcp_error(d.M, q_scaled, z / s)};
  };
  const Index n = static_cast<Index>(d.q.size());
  std::vector<Row> out;
  out.push_back(lemke_row(d.M, d.q, lcprelax::LemkeMethod::dense, opt.refactor_interval, error));
  out.push_back(lemke_row(d.M, d.q, lcprelax::LemkeMethod::sparse, opt.refactor_interval, error));
  const long max_pivots = std::max<long>(10000, 50L * (n + 1) + (n < 23 ? (1L << n) : 0));
  if (opt.siconos)
    out.push_back(siconos_row(
        "siconos_lemke", [&] { return lcprelax::bench::siconos_lcp_lemke(d.M, d.q, max_pivots); }, error));
  for (Row& r : out) {
    r.problem = file.stem().string();
    r.kind = "lcp";
    r.n = n;
    rows.push_back(r);
  }
}

void run_fc2d(const std::string& name, const lcprelax::io::Fc2dData& d, const Options& opt, std::vector<Row>& rows) {
  const lcprelax::Fc2dLcp lcp = lcprelax::fc2d_to_lcp(d.W, d.q, d.mu);
  lcprelax::io::Fc2dData scaled = d;
  const double s = d.q.norm() > 0 ? d.q.norm() : 1.0;
  scaled.q /= s;
  const Score fc2d_error = [&](const Vector& r) {
    return Errors{lcprelax::io::fc2d_error(d, r), lcprelax::io::fc2d_error(scaled, r / s)};
  };
  const Score lcp_error = [&](const Vector& z) {
    Vector r, u;
    lcprelax::fc2d_from_lcp(z, d.W, d.q, r, u);
    return fc2d_error(r);
  };
  std::vector<Row> out;
  if (d.contacts <= opt.dense_max_contacts)
    out.push_back(lemke_row(lcp.M, lcp.q, lcprelax::LemkeMethod::dense, opt.refactor_interval, lcp_error));
  out.push_back(lemke_row(lcp.M, lcp.q, lcprelax::LemkeMethod::sparse, opt.refactor_interval, lcp_error));
  // Sparse Lemke crash-started from 50 PGS sweeps (their time included).
  out.push_back(lcprelax_row(
      "lcprelax_crash",
      [&] {
        return lcprelax::solve_fc2d_lemke_crash(d.W, d.q, d.mu, lcp, 50,
                                                lemke_settings(lcprelax::LemkeMethod::sparse, opt.refactor_interval));
      },
      lcp_error));
  // Sparse Lemke from the same PGS answer purified into a vertex basis (the default of
  // `lcprelax fc2d`; lemke.hpp's purified start), its time included.
  out.push_back(lcprelax_row(
      "lcprelax_purify",
      [&] {
        return lcprelax::solve_fc2d_lemke_crash(d.W, d.q, d.mu, lcp, 50,
                                                lemke_settings(lcprelax::LemkeMethod::sparse, opt.refactor_interval),
                                                nullptr, lcprelax::Fc2dCrash::purified);
      },
      lcp_error));
  // The same crash start without the block principal pivoting rounds (before/after).
  out.push_back(lcprelax_row(
      "lcprelax_crash_noflip",
      [&] {
        lcprelax::LemkeSettings s = lemke_settings(lcprelax::LemkeMethod::sparse, opt.refactor_interval);
        s.crash_flip_rounds = 0;
        return lcprelax::solve_fc2d_lemke_crash(d.W, d.q, d.mu, lcp, 50, s);
      },
      lcp_error));
  const long lemke_max = std::max<long>(10000, 50L * (3 * d.contacts + 1));
  if (opt.siconos) {
    out.push_back(siconos_row(
        "siconos_fc2d_lemke",
        [&] { return lcprelax::bench::siconos_fc2d(d, SiconosFc2dSolver::lemke, kTarget, lemke_max); }, fc2d_error));
    out.push_back(siconos_row(
        "siconos_fc2d_nsgs",
        [&] { return lcprelax::bench::siconos_fc2d(d, SiconosFc2dSolver::nsgs, kTarget, opt.nsgs_max_iter); },
        fc2d_error));
  }
  for (Row& r : out) {
    r.problem = name;
    r.kind = "fc2d";
    r.n = static_cast<Index>(d.q.size());
    r.contacts = d.contacts;
    rows.push_back(r);
  }
}

bool parse(int argc, char** argv, Options& opt) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    const char* v = nullptr;
    if (a == "--out" && (v = value())) opt.out = v;
    else if (a == "--dense-max-contacts" && (v = value())) opt.dense_max_contacts = std::stol(v);
    else if (a == "--nsgs-max-iter" && (v = value())) opt.nsgs_max_iter = std::stol(v);
    else if (a == "--pile" && (v = value())) opt.piles.push_back(std::stoi(v));
    else if (a == "--refactor-interval" && (v = value())) opt.refactor_interval = std::stoi(v);
    else if (a == "--no-files") opt.files = false;
    else if (a == "--no-siconos") opt.siconos = false;
    else if (!a.empty() && a[0] != '-') opt.dir = a;
    else return false;
  }
  return opt.refactor_interval >= 1 && opt.nsgs_max_iter >= 1 && opt.dense_max_contacts >= 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  bool parsed = false;
  try {
    parsed = parse(argc, argv, opt);
  } catch (const std::exception&) {  // std::stol / std::stoi on a bad number
  }
  if (!parsed) {
    std::cerr << "usage: run_lemke_peers [DATA_DIR] [--out FILE.csv] [--dense-max-contacts N] [--nsgs-max-iter N]"
                 " [--pile NC]... [--refactor-interval K] [--no-files] [--no-siconos]\n";
    return 2;
  }
  const std::vector<fs::path> none;
  const auto lcp_files = opt.files ? dat_files(opt.dir / "lcp") : none;
  const auto fc2d_files = opt.files ? dat_files(opt.dir / "fc2d") : none;
  if (opt.files && lcp_files.empty() && fc2d_files.empty()) {
    std::cerr << "no .dat files in " << (opt.dir / "lcp") << " or " << (opt.dir / "fc2d") << "\n";
    return 2;
  }
  std::vector<Row> rows;
  std::printf("%-36s %-5s %5s %4s  %-19s %-16s %10s %10s %10s %8s %11s %3s\n", "problem", "kind", "n", "nc",
              "solver", "status", "error", "err_scaled", "sic_resid", "iter", "seconds", "ok");
  auto print_new = [&](std::size_t from) {
    for (std::size_t k = from; k < rows.size(); ++k) {
      const Row& r = rows[k];
      std::printf("%-36s %-5s %5d %4d  %-19s %-16s %10.2e %10.2e %10.2e %8ld %11.6f %3s\n", r.problem.c_str(),
                  r.kind.c_str(), r.n, r.contacts, r.solver.c_str(), r.status.c_str(), r.error, r.error_scaled,
                  r.siconos_residual, r.iterations, r.seconds, r.ok() ? "yes" : "no");
    }
    std::fflush(stdout);
  };
  for (const auto& f : lcp_files) {
    const std::size_t from = rows.size();
    run_lcp(f, opt, rows);
    print_new(from);
  }
  for (const auto& f : fc2d_files) {
    const std::size_t from = rows.size();
    run_fc2d(f.stem().string(), lcprelax::io::read_siconos_fc2d(f.string()), opt, rows);
    print_new(from);
  }
  for (Index nc : opt.piles) {
    const std::size_t from = rows.size();
    run_fc2d("pile_" + std::to_string(nc), lcprelax::bench::make_pile(nc, 2024), opt, rows);
    print_new(from);
  }
  std::ofstream csv(opt.out);
  csv << "problem,kind,n,contacts,solver,status,error,error_scaled,siconos_residual,iterations,seconds,ok\n";
  for (const Row& r : rows) {
    char line[512];
    std::snprintf(line, sizeof line, "%s,%s,%d,%d,%s,%s,%.3e,%.3e,%.3e,%ld,%.6f,%d\n", r.problem.c_str(),
                  r.kind.c_str(), r.n, r.contacts, r.solver.c_str(), r.status.c_str(), r.error, r.error_scaled,
                  r.siconos_residual, r.iterations, r.seconds, r.ok() ? 1 : 0);
    csv << line;
  }
  std::printf("\nsummary (ok = status solved and error_scaled <= %.0e):\n", kTarget);
  for (const char* s :
       {"lcprelax_dense", "lcprelax_sparse", "lcprelax_crash", "lcprelax_purify", "lcprelax_crash_noflip", "siconos_lemke",
        "siconos_fc2d_lemke", "siconos_fc2d_nsgs"}) {
    int total = 0, ok = 0;
    for (const Row& r : rows)
      if (r.solver == s) ++total, ok += r.ok();
    if (total) std::printf("  %-19s %2d / %2d\n", s, ok, total);
  }
  std::printf("CSV written to %s\n", opt.out.c_str());
  return 0;
}
