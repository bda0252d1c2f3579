#pragma once
// Runs the built `lcprelax` executable for the CLI tests: stdout captured by popen, stderr
// by a temporary file, and the exit code (docs/cli.md: 0 solved, 1 solve failed, 2 bad input;
// with --json, bad input prints {"status": "invalid_input", "message": ...}).
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace lcprelax::testing_support {

namespace fs = std::filesystem;

inline const std::string kCli = LCPRELAX_CLI;
inline const std::string kData = LCPRELAX_TEST_DATA_DIR;

struct CliRun {
  int exit_code = -1;
  std::string out;  ///< stdout (stderr goes to err_file)
  std::string err;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline std::string temp_path(const std::string& name) {
  return (fs::temp_directory_path() / ("lcprelax_cli_" + std::to_string(::getpid()) + "_" + name)).string();
}

/// Runs `lcprelax <args>` through the shell; stdout is captured by popen, stderr by a file.
inline CliRun run_cli(const std::string& args) {
  const std::string err_file = temp_path("stderr.txt");
  const std::string command = "'" + kCli + "' " + args + " 2>'" + err_file + "'";
  CliRun r;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  char buffer[4096];
  std::size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.out.append(buffer, got);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = slurp(err_file);
  fs::remove(err_file);
  return r;
}

/// Starts `lcprelax <args>` (split on spaces, no shell) in a child process with stdout and
/// stderr discarded, for the kill tests; returns its pid (the caller waits for or kills it).
inline pid_t spawn_cli(const std::string& args) {
  std::vector<std::string> words{kCli};
  std::istringstream in(args);
  for (std::string w; in >> w;) words.push_back(w);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    ::execv(kCli.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

/// The lines of a brief report (the human output of every subcommand, apps/cli_report.hpp:
/// `name  value unit`, names padded to one column): name → "value unit". Empty when a line
/// does not have that form (a name, then two or more spaces, then the value).
inline std::vector<std::pair<std::string, std::string>> report_lines(const std::string& out) {
  std::vector<std::pair<std::string, std::string>> lines;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    const std::size_t gap = line.find("  ");
    const std::size_t value = gap == std::string::npos ? gap : line.find_first_not_of(' ', gap);
    if (gap == 0 || value == std::string::npos) return {};
    lines.emplace_back(line.substr(0, gap), line.substr(value));
  }
  return lines;
}

/// The "value unit" of the report line `name`, or "(no line NAME)".
inline std::string report_value(const std::string& out, const std::string& name) {
  for (const auto& [n, v] : report_lines(out))
    if (n == name) return v;
  return "(no line " + name + ")";
}

/// Whether `out` is exactly the one JSON object of bad input under --json (docs/cli.md):
/// status "invalid_input" and a non-empty message.
inline bool invalid_input_json(const std::string& out) {
  const auto j = nlohmann::json::parse(out, nullptr, /*allow_exceptions=*/false);
  return j.is_object() && j.value("status", "") == "invalid_input" && !j.value("message", "").empty();
}

}  // namespace lcprelax::testing_support
