// Mini-batch training loop with checkpoints (trainer.hpp, checkpoint.hpp).
#include <lcprelax/learn/trainer.hpp>
#include "lbfgs_line_search.hpp"
#include "levenberg_marquardt.hpp"
#include <lcprelax/learn/checkpoint.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

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
  if (!(std::isfinite(rel_loss_tol) && rel_loss_tol >= 0.0)) return "rel_loss_tol must be finite and ≥ 0";
  if (!(std::isfinite(grad_tol) && grad_tol >= 0.0)) return "grad_tol must be finite and ≥ 0";
  if (patience < 0) return "patience must be ≥ 0";
  return optimizer.validation_error();
}

ResidualResult Objective::evaluate_residuals(Index /*sample*/, const ParameterSet& /*theta*/, int /*thread*/) {
  throw std::logic_error("Objective::evaluate_residuals: not a least-squares objective (" + residuals_unavailable() + ")");
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

namespace {

void write_log_header(std::ostream& log, const ParameterSet& theta) {
  log << "epoch,loss,validation_loss,gradient_norm,seconds,samples_per_second,failed,full_loss,"
         "full_gradient_norm,relative_loss_change";
  for (Index i = 0; i < theta.size(); ++i) log << ',' << theta[i].name;
  log << '\n';
}

void write_log_row(std::ostream& log, const EpochRecord& rec) {
  log << rec.epoch << ',' << rec.loss << ',' << rec.validation_loss << ',' << rec.gradient_norm << ',' << rec.seconds
      << ',' << rec.samples_per_second << ',' << rec.failed << ',' << rec.full_loss << ',' << rec.full_gradient_norm
      << ',' << rec.relative_loss_change;
  for (Index i = 0; i < rec.theta.size(); ++i) log << ',' << rec.theta(i);
  log << '\n';
}

// The loop state of train() that is not in θ or the optimizer (checkpoint.hpp).
struct LoopState {
  std::mt19937_64 rng;
  std::vector<Index> order;
  long evaluated_total = 0;
  double previous_full_loss = std::numeric_limits<double>::quiet_NaN();
  int streak = 0;
};

TrainCheckpoint snapshot(const Objective& objective, const ParameterSet& theta, const Optimizer& optimizer,
                         const LoopState& loop, const TrainResult& out, const CheckpointIdentity& identity) {
  TrainCheckpoint c;
  c.identity = identity;
  c.epoch = static_cast<int>(out.history.size());
  c.converged = out.converged;
  c.streak = loop.streak;
  c.previous_full_loss = loop.previous_full_loss;
  c.evaluated_total = loop.evaluated_total;
  c.failed = out.failed;
  c.first_failure = out.first_failure;
  c.theta = theta.values();
  c.optimizer = optimizer.state();
  std::ostringstream rng;
  rng << loop.rng;
  c.rng = rng.str();
  c.order = loop.order;
  c.history = out.history;
  StateWriter w;
  objective.save_state(w);
  c.objective_state = w.take();
  return c;
}

// Restores θ, the optimizer, the loop state, the result so far and the objective's state
// from the checkpoint at `path` after checking that it belongs to this run.
void resume(const std::string& path, const CheckpointIdentity& identity, const TrainSettings& settings,
            const std::vector<Index>& training, Objective& objective, ParameterSet& theta, Optimizer& optimizer,
            LoopState& loop, TrainResult& out) {
  TrainCheckpoint c = read_checkpoint(path);
  check_checkpoint_identity(c.identity, identity, path);
  const std::string name = "checkpoint '" + path + "'";
  if (c.epoch > settings.epochs)
    throw InputError(name + " has " + std::to_string(c.epoch) + " epochs done, more than the cap of " +
                     std::to_string(settings.epochs));
  if (c.theta.size() != theta.size()) throw InputError(name + ": θ of another size");
  std::vector<Index> a = c.order, b = training;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  if (a != b) throw InputError(name + ": the shuffled order is not a permutation of the training set");
  std::istringstream rng(c.rng);
  rng >> loop.rng;
  if (!rng) throw InputError(name + ": unreadable shuffle generator state");
  theta.set_values(c.theta);
  optimizer.restore(c.optimizer);
  loop.order = std::move(c.order);
  loop.evaluated_total = c.evaluated_total;
  loop.previous_full_loss = c.previous_full_loss;
  loop.streak = c.streak;
  out.history = std::move(c.history);
  out.failed = c.failed;
  out.first_failure = std::move(c.first_failure);
  out.converged = c.converged;
  StateReader in(c.objective_state, name + ": objective state");
  objective.load_state(in);
  in.expect_end();
}

}  // namespace

TrainResult train(Objective& objective, ParameterSet& theta, const std::vector<Index>& training,
                  const std::vector<Index>& validation, const TrainSettings& settings) {
  const std::string error = settings.validation_error();
  if (!error.empty()) throw InputError("training settings: " + error);
  if (training.empty()) throw InputError("training set is empty");
  check_indices(training, objective.num_samples(), "training");
  check_indices(validation, objective.num_samples(), "validation");

  Optimizer optimizer(settings.optimizer);
  LoopState loop;
  loop.rng.seed(settings.seed);
  loop.order = training;
  std::vector<Index>& order = loop.order;
  const std::size_t batch = settings.batch > 0 ? static_cast<std::size_t>(settings.batch) : order.size();
  const int rank = settings.distributed ? mpi::mpi_rank() : 0;
  const bool writer = rank == 0;  // progress and log
  const std::string checkpoint = settings.checkpoint.empty() ? std::string() : checkpoint_path_for_rank(settings.checkpoint, rank);
  if (!checkpoint.empty()) check_checkpoint_writable(checkpoint);
  const CheckpointIdentity identity = checkpoint_identity(objective, theta, training, validation, settings);

  TrainResult out;
  if (!settings.resume.empty())
    resume(checkpoint_path_for_rank(settings.resume, rank), identity, settings, training, objective, theta, optimizer,
           loop, out);
  const int first_epoch = static_cast<int>(out.history.size()) + 1;
  const double seconds_before = out.history.empty() ? 0.0 : out.history.back().seconds;
  std::ofstream log;
  if (!settings.log_csv.empty() && writer) {
    log.open(settings.log_csv);
    if (!log) throw InputError("cannot write the training log '" + settings.log_csv + "'");
    log.precision(17);
    write_log_header(log, theta);
    for (const EpochRecord& rec : out.history) write_log_row(log, rec);  // a resumed run's epochs so far
  }

  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return seconds_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const bool full_batch = batch >= order.size();
  const bool lbfgs = settings.optimizer.kind == OptimizerKind::lbfgs;
  if (lbfgs && !full_batch)
    throw InputError("optimizer lbfgs needs the whole training set per step (batch 0 or at least " +
                     std::to_string(order.size()) + ", not " + std::to_string(settings.batch) + ")");
  const bool lm = settings.optimizer.kind == OptimizerKind::lm;
  if (lm && !full_batch)
    throw InputError("optimizer lm needs the whole training set per step (batch 0 or at least " +
                     std::to_string(order.size()) + ", not " + std::to_string(settings.batch) + ")");
  if (lm && theta.size() > detail::kMaxLmParameters)
    throw InputError("optimizer lm forms a |θ|×|θ| Gauss–Newton matrix per sample: at most " +
                     std::to_string(detail::kMaxLmParameters) + " parameters, this run has " +
                     std::to_string(theta.size()) + " (use adam or lbfgs)");
  if (lm) {
    const std::string why = objective.residuals_unavailable();
    if (!why.empty()) throw InputError("optimizer lm needs a least-squares loss: " + why);
  }
  bool line_search_failed = false, lm_failed = false;
  const bool test_on = settings.patience > 0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int epoch = first_epoch; epoch <= settings.epochs && !out.converged && !line_search_failed && !lm_failed;
       ++epoch) {
    if (settings.shuffle) shuffle(order, loop.rng);
    EpochRecord rec;
    rec.epoch = epoch;
    double loss_sum = 0.0;
    long loss_count = 0;
    int trial_failures = 0;
    for (std::size_t b0 = 0; b0 < order.size(); b0 += batch) {
      const std::vector<Index> samples(order.begin() + static_cast<std::ptrdiff_t>(b0),
                                       order.begin() + static_cast<std::ptrdiff_t>(std::min(order.size(), b0 + batch)));
      const BatchResult r = evaluate_mean(objective, theta, samples, settings.threads, settings.distributed);
      rec.failed += r.failed;
      if (r.failed > 0 && out.first_failure.empty()) out.first_failure = r.first_failure;
      if (r.evaluated == 0) continue;
      loss_sum += r.loss * r.evaluated;
      loss_count += r.evaluated;
      loop.evaluated_total += r.evaluated;
      const Vector g = theta.chain_gradient(r.gradient);
      rec.gradient_norm = g.norm();
      if (lbfgs) {  // one quasi-Newton iteration with its line search (lbfgs_line_search.hpp)
        const detail::LbfgsIteration it = detail::lbfgs_iteration(objective, theta, samples, settings.threads,
                                                                  settings.distributed, optimizer, r.loss, r.evaluated, g);
        loop.evaluated_total += it.evaluated;
        trial_failures += it.failed;
        if (it.failed > 0 && out.first_failure.empty()) out.first_failure = it.first_failure;
        line_search_failed = !it.accepted && it.steepest;
        continue;
      }
      if (lm) {  // one damped Gauss–Newton iteration (levenberg_marquardt.hpp)
        const detail::LmIteration it =
            detail::lm_iteration(objective, theta, samples, settings.threads, settings.distributed, optimizer);
        loop.evaluated_total += it.evaluated;
        trial_failures += it.failed;
        if (it.failed > 0 && out.first_failure.empty()) out.first_failure = it.first_failure;
        lm_failed = !it.accepted;
        continue;
      }
      Vector xi = theta.free();
      optimizer.step(xi, g);
      theta.set_free(xi);
    }
    rec.loss = loss_count > 0 ? loss_sum / static_cast<double>(loss_count) : nan;
    // C_k and g_k over the whole training set (trainer.hpp): the epoch's own evaluation with
    // full batch, one more at the epoch's end θ with mini-batches.
    rec.full_loss = rec.full_gradient_norm = rec.relative_loss_change = nan;
    bool complete = false;  // every training sample evaluated at θ_c
    if (full_batch) {
      complete = rec.failed == 0 && loss_count > 0;
      if (loss_count > 0) rec.full_loss = rec.loss, rec.full_gradient_norm = rec.gradient_norm;
    } else if (test_on) {
      const BatchResult r = evaluate_mean(objective, theta, training, settings.threads, settings.distributed);
      if (r.failed > 0 && out.first_failure.empty()) out.first_failure = r.first_failure;
      complete = r.failed == 0 && r.evaluated > 0;
      if (r.evaluated > 0) rec.full_loss = r.loss, rec.full_gradient_norm = theta.chain_gradient(r.gradient).norm();
    }
    if (complete && std::isfinite(loop.previous_full_loss) && std::isfinite(rec.full_loss))
      rec.relative_loss_change = std::abs(loop.previous_full_loss - rec.full_loss) /
                                 std::max({std::abs(loop.previous_full_loss), std::abs(rec.full_loss), 1.0});
    const bool holds = complete && rec.relative_loss_change <= settings.rel_loss_tol &&
                       rec.full_gradient_norm <= settings.grad_tol;
    loop.streak = holds ? loop.streak + 1 : 0;
    rec.streak = loop.streak;
    loop.previous_full_loss = complete ? rec.full_loss : nan;
    if (test_on && loop.streak >= settings.patience) out.converged = true;
    rec.validation_loss = nan;
    if (!validation.empty()) rec.validation_loss = evaluate_mean(objective, theta, validation, settings.threads, settings.distributed).loss;
    rec.theta = theta.values();
    rec.seconds = elapsed();
    rec.samples_per_second = rec.seconds > 0.0 ? static_cast<double>(loop.evaluated_total) / rec.seconds : 0.0;
    out.failed += rec.failed + trial_failures;
    if (settings.progress && writer) {
      const double eta = rec.seconds / epoch * (settings.epochs - epoch);
      std::fprintf(stderr, "\repoch %d/%d  loss %.6g  val %.6g  %.0f samples/s  ETA %.0f s ", epoch, settings.epochs,
                   rec.loss, rec.validation_loss, rec.samples_per_second, eta);
      for (Index i = 0; i < theta.size() && i < 6; ++i) std::fprintf(stderr, " %s=%.6g", theta[i].name.c_str(), theta[i].value);
      std::fflush(stderr);
    }
    if (log) write_log_row(log, rec);
    out.history.push_back(std::move(rec));
    if (!checkpoint.empty()) write_checkpoint(checkpoint, snapshot(objective, theta, optimizer, loop, out, identity));
  }
  if (settings.progress && writer && first_epoch <= settings.epochs && settings.epochs > 0) std::fprintf(stderr, "\n");
  char reason[160];
  if (out.converged)
    std::snprintf(reason, sizeof reason, "converged: relative loss change <= %g and gradient norm <= %g for %d epochs",
                  settings.rel_loss_tol, settings.grad_tol, settings.patience);
  else if (line_search_failed)
    std::snprintf(reason, sizeof reason,
                  "lbfgs line search found no decrease along -gradient after %d epochs (a kink or the loss's noise floor)",
                  static_cast<int>(out.history.size()));
  else if (lm_failed)
    std::snprintf(reason, sizeof reason,
                  "lm found no decrease at any damping after %d epochs (a kink or the loss's noise floor)",
                  static_cast<int>(out.history.size()));
  else
    std::snprintf(reason, sizeof reason, "epoch cap reached (%d epochs%s)", settings.epochs,
                  test_on ? "" : ", convergence test off");
  out.stop_reason = reason;
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
