// Mini-batch training loop (trainer.hpp).
#include <lcprelax/learn/trainer.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>

namespace lcprelax::learn {

namespace {

// Fisher–Yates with our own bounded draw (std::shuffle's is implementation-defined).
void shuffle(std::vector<Index>& v, std::mt19937_64& rng) {
  for (std::size_t i = v.size(); i > 1; --i) {
    const std::size_t j = static_cast<std::size_t>(rng() % i);
    std::swap(v[i - 1], v[j]);
  }
}

void check_indices(const std::vector<Index>& s, Index n, const char* what) {
  for (Index i : s)
    if (i < 0 || i >= n) throw InputError(std::string(what) + " sample index " + std::to_string(i) + " out of range");
}

}  // namespace

std::string TrainSettings::validation_error() const {
  if (epochs < 0) return "epochs must be ≥ 0";
  if (batch < 0) return "batch must be ≥ 0";
  return optimizer.validation_error();
}

BatchResult evaluate_mean(Objective& objective, const ParameterSet& theta, const std::vector<Index>& samples,
                          int threads, bool distributed) {
  objective.prepare(theta, resolve_threads(threads));
  const SampleFunction f = [&](Index i, int t) { return objective.evaluate(i, theta, t); };
  BatchResult r = distributed ? evaluate_batch_distributed(samples, theta.size(), threads, f)
                              : evaluate_batch(samples, theta.size(), threads, f);
  if (r.evaluated > 0) {
    r.loss /= r.evaluated;
    r.gradient /= r.evaluated;
  }
  return r;
}

TrainResult train(Objective& objective, ParameterSet& theta, const std::vector<Index>& training,
                  const std::vector<Index>& validation, const TrainSettings& settings) {
  const std::string error = settings.validation_error();
  if (!error.empty()) throw InputError("training settings: " + error);
  if (training.empty()) throw InputError("training set is empty");
  check_indices(training, objective.num_samples(), "training");
  check_indices(validation, objective.num_samples(), "validation");

  Optimizer optimizer(settings.optimizer);
  std::mt19937_64 rng(settings.seed);
  std::vector<Index> order = training;
  const std::size_t batch = settings.batch > 0 ? static_cast<std::size_t>(settings.batch) : order.size();
  const bool writer = !settings.distributed || mpi::mpi_rank() == 0;  // progress and log
  std::ofstream log;
  if (!settings.log_csv.empty() && writer) {
    log.open(settings.log_csv);
    if (!log) throw InputError("cannot write the training log '" + settings.log_csv + "'");
    log << "epoch,loss,validation_loss,gradient_norm,seconds,samples_per_second,failed";
    for (Index i = 0; i < theta.size(); ++i) log << ',' << theta[i].name;
    log << '\n';
    log.precision(17);
  }

  TrainResult out;
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  long evaluated_total = 0;
  for (int epoch = 1; epoch <= settings.epochs; ++epoch) {
    if (settings.shuffle) shuffle(order, rng);
    EpochRecord rec;
    rec.epoch = epoch;
    double loss_sum = 0.0;
    long loss_count = 0;
    for (std::size_t b0 = 0; b0 < order.size(); b0 += batch) {
      const std::vector<Index> samples(order.begin() + static_cast<std::ptrdiff_t>(b0),
                                       order.begin() + static_cast<std::ptrdiff_t>(std::min(order.size(), b0 + batch)));
      const BatchResult r = evaluate_mean(objective, theta, samples, settings.threads, settings.distributed);
      rec.failed += r.failed;
      if (r.failed > 0 && out.first_failure.empty()) out.first_failure = r.first_failure;
      if (r.evaluated == 0) continue;
      loss_sum += r.loss * r.evaluated;
      loss_count += r.evaluated;
      evaluated_total += r.evaluated;
      const Vector g = theta.chain_gradient(r.gradient);
      rec.gradient_norm = g.norm();
      Vector xi = theta.free();
      optimizer.step(xi, g);
      theta.set_free(xi);
    }
    rec.loss = loss_count > 0 ? loss_sum / static_cast<double>(loss_count) : std::numeric_limits<double>::quiet_NaN();
    rec.validation_loss = std::numeric_limits<double>::quiet_NaN();
    if (!validation.empty()) rec.validation_loss = evaluate_mean(objective, theta, validation, settings.threads, settings.distributed).loss;
    rec.theta = theta.values();
    rec.seconds = elapsed();
    rec.samples_per_second = rec.seconds > 0.0 ? static_cast<double>(evaluated_total) / rec.seconds : 0.0;
    out.failed += rec.failed;
    if (settings.progress && writer) {
      const double eta = rec.seconds / epoch * (settings.epochs - epoch);
      std::fprintf(stderr, "\repoch %d/%d  loss %.6g  val %.6g  %.0f samples/s  ETA %.0f s ", epoch, settings.epochs,
                   rec.loss, rec.validation_loss, rec.samples_per_second, eta);
      for (Index i = 0; i < theta.size() && i < 6; ++i) std::fprintf(stderr, " %s=%.6g", theta[i].name.c_str(), theta[i].value);
      std::fflush(stderr);
    }
    if (log) {
      log << epoch << ',' << rec.loss << ',' << rec.validation_loss << ',' << rec.gradient_norm << ',' << rec.seconds
          << ',' << rec.samples_per_second << ',' << rec.failed;
      for (Index i = 0; i < theta.size(); ++i) log << ',' << theta[i].value;
      log << '\n';
    }
    out.history.push_back(std::move(rec));
  }
  if (settings.progress && writer && settings.epochs > 0) std::fprintf(stderr, "\n");
  out.seconds = elapsed();
  return out;
}

void split_samples(Index n, double validation_fraction, std::uint64_t seed, std::vector<Index>& training,
                   std::vector<Index>& validation) {
  if (n < 0 || !(validation_fraction >= 0.0 && validation_fraction < 1.0))
    throw InputError("split_samples: n must be ≥ 0 and the validation fraction in [0, 1)");
  std::vector<Index> all(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) all[static_cast<std::size_t>(i)] = i;
  std::mt19937_64 rng(seed);
  shuffle(all, rng);
  const std::size_t nv = static_cast<std::size_t>(std::floor(validation_fraction * static_cast<double>(n)));
  validation.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(nv));
  training.assign(all.begin() + static_cast<std::ptrdiff_t>(nv), all.end());
}

}  // namespace lcprelax::learn
