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
  command.add_flag("--json", json, "Print exactly one JSON object on stdout");
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

learn::TrainSettings learn_train_settings(int epochs, int batch, int threads, std::uint64_t seed,
                                          const std::string& optimizer, double learning_rate, double momentum,
                                          bool json, const std::string& log_csv) {
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
  t.distributed = mpi::mpi_size() > 1;  // under mpiexec: samples sharded over the ranks
  const std::string bad = t.validation_error();
  if (!bad.empty()) throw InputError("training settings: " + bad);
  return t;
}

}  // namespace lcprelax::cli
