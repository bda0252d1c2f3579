#pragma once
// Runs COIN-OR Clp's barrier QP solver (the `clp` command of Debian's coinor-clp) on a QPS
// file and reads back its status, objective, time and full-precision solution
// (header-only helper of run_maros_meszaros).
//
// Invocation (Clp 1.17):
//   timeout -k 5 T clp IN.qps -barrier -printingOptions all -solution OUT.txt
//                                      -saveSolution OUT.bin  > OUT.log 2>&1
// - IN.qps is a copy of the file where FR/MI/PL bound lines without a value get " 0.0"
//   (Clp's reader requires the value field and otherwise rejects the model);
// - OUT.txt's first line is "<Status> - objective value V"; with printingOptions all it
//   lists every row and then every column as "index name value dual" (a leading "**"
//   marks an infeasible entry); only the names are used, because it prints 8 digits;
// - OUT.bin (saveSolution) holds, in binary: int m, int n, double objective (with the
//   constant term), m row activities, m row duals π, n column values, n reduced costs d;
// - the log's "Optimal objective V - K iterations time T" gives Clp's own solve time
//   (import excluded).
// Clp's duals satisfy Px + q − Gᵀπ − d = 0, so in lcprelax's convention (docs/conventions.md)
// z = −π and z_bounds = −d (checked by hand on HS21 and QAFIRO: an active ≤ row has π < 0,
// a variable at its lower bound has d > 0).
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

namespace lcprelax::bench {

struct ClpRun {
  std::string status = "not_run";  ///< "optimal", "time_limit", "error", or Clp's word, lower case
  double objective = std::numeric_limits<double>::quiet_NaN();
  double wall_seconds = std::numeric_limits<double>::quiet_NaN();   ///< process, incl. import
  double solve_seconds = std::numeric_limits<double>::quiet_NaN();  ///< Clp's reported time
  std::vector<std::string> row_names, column_names;  ///< Clp's order, from OUT.txt
  std::vector<double> row_activity, row_dual, x, reduced_cost;  ///< from OUT.bin
  std::string message;
};

namespace detail {

inline std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

inline std::vector<std::string> split_ws(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> tokens;
  for (std::string t; in >> t;) tokens.push_back(t);
  return tokens;
}

/// Copies `in` to `out`, appending " 0.0" to BOUNDS lines "FR|MI|PL bound column".
inline bool write_clp_compatible_qps(const std::filesystem::path& in, const std::filesystem::path& out) {
  std::ifstream src(in);
  std::ofstream dst(out);
  if (!src || !dst) return false;
  bool in_bounds = false;
  for (std::string line; std::getline(src, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty() && !std::isspace(static_cast<unsigned char>(line[0])) && line[0] != '*') {
      in_bounds = split_ws(line).front() == "BOUNDS";
    } else if (in_bounds) {
      const auto t = split_ws(line);
      if (t.size() == 3 && (t[0] == "FR" || t[0] == "MI" || t[0] == "PL")) line += " 0.0";
    }
    dst << line << '\n';
  }
  return static_cast<bool>(dst);
}

inline std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// Reads OUT.bin into `run`; false when the file is missing or truncated.
inline bool read_clp_binary(const std::filesystem::path& path, ClpRun& run) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  int m = -1, n = -1;
  bool ok = std::fread(&m, sizeof m, 1, f) == 1 && std::fread(&n, sizeof n, 1, f) == 1 && m >= 0 && n >= 0 &&
            std::fread(&run.objective, sizeof(double), 1, f) == 1;
  auto read_vec = [&](std::vector<double>& v, int size) {
    v.assign(static_cast<std::size_t>(size), 0.0);
    ok = ok && std::fread(v.data(), sizeof(double), v.size(), f) == v.size();
  };
  if (ok) {
    read_vec(run.row_activity, m);
    read_vec(run.row_dual, m);
    read_vec(run.x, n);
    read_vec(run.reduced_cost, n);
  }
  std::fclose(f);
  return ok;
}

/// Reads the status word and the row/column names of OUT.txt.
inline void read_clp_text(const std::filesystem::path& path, ClpRun& run) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return;
  const auto dash = line.find(" - objective value");
  run.status = lower(line.substr(0, dash == std::string::npos ? line.size() : dash));
  const std::size_t m = run.row_activity.size();
  std::vector<std::string> names;
  while (std::getline(in, line)) {
    auto t = split_ws(line);
    if (!t.empty() && t[0] == "**") t.erase(t.begin());
    if (t.size() >= 4) names.push_back(t[1]);
  }
  if (names.size() == m + run.x.size()) {
    run.row_names.assign(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(m));
    run.column_names.assign(names.begin() + static_cast<std::ptrdiff_t>(m), names.end());
  }
}

/// Clp's own time from the log line "... iterations time T".
inline double read_clp_time(const std::filesystem::path& log) {
  std::ifstream in(log);
  double t = std::numeric_limits<double>::quiet_NaN();
  for (std::string line; std::getline(in, line);) {
    const auto pos = line.rfind(" time ");
    if (line.rfind("Optimal objective", 0) == 0 || (pos != std::string::npos && line.find("iterations") != std::string::npos)) {
      if (pos != std::string::npos) t = std::strtod(line.c_str() + pos + 6, nullptr);
    }
  }
  return t;
}

}  // namespace detail

/// Runs Clp's barrier on `qps` with a wall-clock limit; scratch files go to `work_dir`
/// (removed afterwards).
inline ClpRun run_clp_barrier(const std::string& clp, const std::filesystem::path& qps,
                              const std::filesystem::path& work_dir, double time_limit) {
  namespace fs = std::filesystem;
  ClpRun run;
  fs::create_directories(work_dir);
  const std::string stem = qps.stem().string();
  const fs::path in = work_dir / (stem + ".qps"), txt = work_dir / (stem + ".sol.txt");
  const fs::path bin = work_dir / (stem + ".sol.bin"), log = work_dir / (stem + ".log");
  if (!detail::write_clp_compatible_qps(qps, in)) {
    run.status = "error";
    run.message = "cannot write " + in.string();
    return run;
  }
  const long limit = std::max(1L, static_cast<long>(std::ceil(time_limit)));
  const std::string cmd = "timeout -k 5 " + std::to_string(limit) + " " + detail::shell_quote(clp) + " " +
                          detail::shell_quote(in.string()) + " -barrier -printingOptions all -solution " +
                          detail::shell_quote(txt.string()) + " -saveSolution " + detail::shell_quote(bin.string()) +
                          " > " + detail::shell_quote(log.string()) + " 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  const int raw = std::system(cmd.c_str());
  run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int code = raw == -1 ? -1 : (WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw));

  if (code == 124 || code == 137) {
    run.status = "time_limit";
  } else if (!detail::read_clp_binary(bin, run)) {
    run.status = "error";
    run.message = "no solution written (exit code " + std::to_string(code) + ")";
  } else {
    detail::read_clp_text(txt, run);
    if (run.status == "not_run") run.status = "unknown";
    run.solve_seconds = detail::read_clp_time(log);
  }
  std::error_code ec;
  for (const auto& p : {in, txt, bin, log}) fs::remove(p, ec);
  return run;
}

}  // namespace lcprelax::bench
