// JSON output helpers of the lcprelax command line (see cli_common.hpp).
#include "cli_common.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <iostream>

namespace lcprelax::cli {

void add_json_flag(CLI::App& command, bool& json) {
  command.add_flag("--json", json,
                   "print exactly one JSON object on stdout instead of the report (fields: docs/cli.md)");
}

std::string exit_codes_help(const std::string& success, const std::string& failure) {
  return "Exit codes:\n"
         "  0  " +
         (success.empty() ? std::string("success") : success) +
         "\n"
         "  1  " +
         (failure.empty() ? std::string("the run finished but did not succeed (the status says why)") : failure) +
         "; also an internal error or out of memory\n"
         "  2  bad input: a missing or malformed file, an invalid option value or an unwritable\n"
         "     output path; the message is on stderr (with --json stdout also holds\n"
         "     {\"status\": \"invalid_input\", \"message\": ...}) and nothing is computed\n";
}

CLI::Option* add_threads_option(CLI::App& command, int& threads, const std::string& over) {
  return command
      .add_option("--threads", threads,
                  "threads over " + over + "; 0: all cores (OpenMP's default, capped by OMP_NUM_THREADS); at most " +
                      std::to_string(kMaxThreads) + "; the results are the same for every thread count")
      ->capture_default_str();
}

Json number_or_null(double v) {
  if (!std::isfinite(v)) return nullptr;
  return v;
}

Json array_or_nulls(const Vector& v) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(number_or_null(v[i]));
  return a;
}

void print_json(const Json& object) {
  std::cout << object.dump() << '\n' << std::flush;
}

void write_json_file(const std::string& path, const Json& object) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot open for writing");
  out << object.dump() << '\n';
  out.close();
  if (!out) throw InputError(path + ": write failed");
}

void require_option(bool ok, const std::string& option, const std::string& requirement) {
  if (!ok) throw InputError(option + ": " + requirement);
}

void require_threads(int threads) {
  require_option(threads >= 0 && threads <= kMaxThreads, "--threads",
                 "must be in [0, " + std::to_string(kMaxThreads) + "] (0: all cores), got " + std::to_string(threads));
}

learn::TrainSettings learn_train_settings(int epochs, int batch, int threads, std::uint64_t seed,
                                          const std::string& optimizer, double learning_rate, double momentum,
                                          bool json, const std::string& log_csv, const LearnStopOptions& stop) {
  require_threads(threads);
  require_writable_file("--log", log_csv);
  learn::TrainSettings t;
  t.epochs = epochs;
  t.batch = batch;
  t.threads = threads;
  t.seed = seed;
  t.optimizer.kind = learn::parse_optimizer_kind(optimizer);
  t.optimizer.learning_rate = learning_rate;
  t.optimizer.momentum = momentum;
  t.progress = !json && epochs > 0 && isatty(STDERR_FILENO);
  t.log_csv = log_csv;
  t.rel_loss_tol = stop.rel_loss_tol;
  t.grad_tol = stop.grad_tol;
  t.patience = stop.patience;
  t.distributed = mpi::mpi_size() > 1;  // under mpiexec: samples sharded over the ranks
  const std::string bad = t.validation_error();
  if (!bad.empty()) throw InputError("training settings: " + bad);
  return t;
}

void add_learn_stop_options(CLI::App& command, LearnStopOptions& stop) {
  command.add_option("--rel-loss-tol", stop.rel_loss_tol,
                     "training stops early (converged) once, for --patience epochs in a row, the mean training "
                     "loss changes by at most this, relative to max(|loss|, 1), ...")
      ->capture_default_str();
  command.add_option("--grad-tol", stop.grad_tol,
                     "... and the length (2-norm) of its gradient with respect to the learned parameters (log "
                     "scale for positive ones) is at most this ...")
      ->capture_default_str();
  command.add_option("--patience", stop.patience, "... for this many epochs in a row (0: always run --epochs epochs)")
      ->capture_default_str();
}

void add_train_outcome(Json& j, const learn::TrainResult& result, int epochs_cap) {
  if (epochs_cap > 0) {
    j["epochs"] = static_cast<int>(result.history.size());
    j["stop_reason"] = result.stop_reason;
    j["converged"] = result.converged;
  } else {
    j["epochs"] = 0;
    j["stop_reason"] = "epoch cap reached (0 epochs)";
    j["converged"] = false;
  }
}

}  // namespace lcprelax::cli
