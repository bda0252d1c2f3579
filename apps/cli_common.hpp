#pragma once
// Shared pieces of the lcprelax command line (docs/cli.md): exit codes, the way a subcommand
// plugs into main(), and JSON output helpers. A subcommand lives in its own cmd_<name>.cpp
// and exposes one add_<name>_command(); main.cpp lists them.
//
// Error policy: a subcommand's run() returns kExitSuccess or kExitSolveFailed; bad input
// (malformed or missing file, invalid option value, NaN data) is thrown as
// lcprelax::InputError and main() turns it into a message on stderr and kExitBadInput,
// with nothing on stdout.
#include <lcprelax/learn/trainer.hpp>
#include <lcprelax/sparse/types.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace lcprelax::cli {

/// JSON object whose keys keep insertion order (the order of the docs/cli.md contract).
using Json = nlohmann::ordered_json;

enum ExitCode : int {
  kExitSuccess = 0,      ///< solved
  kExitSolveFailed = 1,  ///< the solve ran but did not succeed (the status says why)
  kExitBadInput = 2      ///< bad input: message on stderr, no JSON on stdout
};

/// A registered subcommand: its CLI11 app (to ask whether it was selected) and the action
/// that runs it after parsing, returning an ExitCode.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

/// `lcprelax qp FILE.qps [--eps E] [--max-iter N] [--solution OUT.json] [--json]`.
Command add_qp_command(CLI::App& parent);
/// `lcprelax lcp FILE.dat [--solver lemke|ipm] [--solution OUT.json] [--json]`.
Command add_lcp_command(CLI::App& parent);
/// `lcprelax fc2d FILE.dat [--solver lemke|ipm] [--solution OUT.json] [--json]`.
Command add_fc2d_command(CLI::App& parent);

/// `lcprelax pile [--bodies N] [--steps K] [--model lcp|convex] [--threads T] [--picture OUT] ...`.
Command add_pile_command(CLI::App& parent);

/// `lcprelax learn block|polygon ...` (docs/cli.md). Each learning application lives in its
/// own cmd_learn_<name>.cpp and registers a factory that adds its sub-subcommand to the
/// `learn` app, by a namespace-scope `const bool registered = register_learn_application(f);`.
using LearnApplicationFactory = Command (*)(CLI::App& learn);
bool register_learn_application(LearnApplicationFactory factory);
Command add_learn_command(CLI::App& parent);

/// The stopping options every learn command accepts: --epochs is the cap, --rel-loss-tol,
/// --grad-tol and --patience the convergence test of learn::train (trainer.hpp).
struct LearnStopOptions {
  double rel_loss_tol = learn::TrainSettings{}.rel_loss_tol;
  double grad_tol = learn::TrainSettings{}.grad_tol;
  int patience = learn::TrainSettings{}.patience;
};
/// Adds --rel-loss-tol, --grad-tol and --patience to `command`.
void add_learn_stop_options(CLI::App& command, LearnStopOptions& stop);

/// Training settings common to the learn commands: epochs (the cap), mini-batch, threads,
/// seed, optimizer (sgd|adam) with learning rate and momentum, the convergence test,
/// progress on a terminal unless --json, the CSV log, and data-parallel mode under mpiexec.
/// Throws InputError if invalid.
learn::TrainSettings learn_train_settings(int epochs, int batch, int threads, std::uint64_t seed,
                                          const std::string& optimizer, double learning_rate, double momentum,
                                          bool json, const std::string& log_csv, const LearnStopOptions& stop = {});

/// Adds "epochs" (epochs actually run), "stop_reason" and "converged" of a training run to
/// `j`. `epochs_cap` = 0 means no training ran: "epochs" 0, stop_reason "epoch cap reached
/// (0 epochs)", converged false.
void add_train_outcome(Json& j, const learn::TrainResult& result, int epochs_cap);

/// Adds the `--json` flag every subcommand accepts.
void add_json_flag(CLI::App& command, bool& json);

/// The "Exit codes" section of a command's --help (its footer): 0 with `success`, 1 with
/// `failure` (what success and a failed run mean for this command; empty: the generic
/// wording), 2 bad input. main.cpp, the subcommands and the learn applications each set it.
std::string exit_codes_help(const std::string& success = "", const std::string& failure = "");

/// Adds `--threads T` (default `threads`, normally 0) with one help text for every command:
/// 0 means all cores (OpenMP's default, which OMP_NUM_THREADS caps); `over` names what runs
/// in parallel ("islands", "samples"). The results do not depend on T (batch.hpp: sums in a
/// fixed order; the simulator gathers islands in island order). Validated by require_threads.
CLI::Option* add_threads_option(CLI::App& command, int& threads, const std::string& over);

/// A JSON number, or null when v is NaN or ±∞ (JSON has no such numbers).
Json number_or_null(double v);
/// A JSON array of numbers (non-finite entries as null).
Json array_or_nulls(const Vector& v);
/// Prints `object` as exactly one line on stdout and flushes.
void print_json(const Json& object);
/// Writes `object` to `path`; throws InputError if the file cannot be written.
void write_json_file(const std::string& path, const Json& object);
/// Throws InputError("<option>: <requirement>") unless ok.
void require_option(bool ok, const std::string& option, const std::string& requirement);

/// Most threads any --threads accepts (more crashed OpenMP: 100,000 threads segfaulted, 20,000
/// took 2 GB and 29 s for 20 samples). Larger values are an input error (exit 2).
constexpr int kMaxThreads = 1024;
/// Throws InputError("--threads: must be in [0, 1024] ...") unless 0 ≤ threads ≤ kMaxThreads.
void require_threads(int threads);

/// Output paths checked before the work starts (cli_output_paths.cpp): throw InputError
/// "<option>: cannot write '<path>': <reason>" unless the file can be written (created, then
/// removed again, when missing) or the directory exists or can be created and is writable.
void require_writable_file(const std::string& option, const std::string& path);
void require_writable_directory(const std::string& option, const std::string& dir);

/// Wall-clock stopwatch started at construction.
class Stopwatch {
 public:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace lcprelax::cli
