#pragma once
// Mini-batch training loop: epochs over a shuffled training set, a batched parallel
// evaluation per mini-batch (batch.hpp), one optimizer step per mini-batch on the free
// parameters ξ (parameters.hpp, optimizer.hpp), validation after each epoch, progress on
// a terminal and a CSV log of every epoch.
//
// Conventions:
// - A mini-batch step uses the MEAN of the per-sample gradients over the batch
//   (∂/∂ξ of (1/|B|) Σ_{i∈B} ℓᵢ), so the learning rate does not depend on the batch size.
// - EpochRecord::loss is the mean per-sample loss over the epoch's mini-batches (each
//   evaluated at the parameters of its own step); validation_loss the mean over the
//   validation samples at the end of the epoch (NaN without validation samples).
// - The shuffle uses a std::mt19937_64 seeded with TrainSettings::seed and a Fisher–Yates
//   pass of our own (the same permutation on every standard library), so a run is
//   reproducible and the same for every thread count.
// - A sample that fails to evaluate is skipped and counted (EpochRecord::failed); a batch
//   in which every sample fails leaves the parameters unchanged.
#include <lcprelax/learn/batch.hpp>
#include <lcprelax/learn/optimizer.hpp>
#include <lcprelax/learn/parameters.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace lcprelax::learn {

/// A learning problem: per-sample loss ℓᵢ(θ) and ∂ℓᵢ/∂θ. evaluate() is called
/// concurrently for different samples (thread ∈ [0, threads) identifies the workspace);
/// it may keep per-sample state (e.g. a warm start) because one sample is never evaluated
/// twice at the same time.
class Objective {
 public:
  virtual ~Objective() = default;
  virtual Index num_samples() const = 0;
  /// Called once per mini-batch before its evaluations (single-threaded): e.g. rebuild
  /// per-thread workspaces for the current θ.
  virtual void prepare(const ParameterSet& /*theta*/, int /*threads*/) {}
  virtual SampleResult evaluate(Index sample, const ParameterSet& theta, int thread) = 0;
};

struct TrainSettings {
  int epochs = 100;               ///< ≥ 0
  int batch = 0;                  ///< mini-batch size; 0 = the whole training set
  int threads = 0;                ///< OpenMP threads (≤ 0: default)
  std::uint64_t seed = 1;         ///< shuffle seed
  bool shuffle = true;
  OptimizerSettings optimizer;
  bool progress = false;          ///< one line per epoch on stderr
  std::string log_csv;            ///< if non-empty, CSV log of every epoch
  /// Data-parallel over MPI ranks (batch.hpp evaluate_batch_distributed): every rank
  /// calls train() with the same data and settings; sample i is evaluated on rank
  /// i mod R, results are gathered and summed in a fixed order, so the parameters stay
  /// identical on every rank and equal those of one process. Progress and the CSV log
  /// are written by rank 0 only. Without MPI (or with one rank) it changes nothing.
  bool distributed = false;
  std::string validation_error() const;  ///< empty if valid, else a message naming the first bad field
};

struct EpochRecord {
  int epoch = 0;                  ///< 1-based
  double loss = 0.0;              ///< mean training loss over the epoch
  double validation_loss = 0.0;   ///< mean validation loss at the epoch's end (NaN if none)
  double gradient_norm = 0.0;     ///< ‖mean ∂ℓ/∂ξ‖₂ of the epoch's last batch
  Vector theta;                   ///< θ at the epoch's end
  double seconds = 0.0;           ///< wall time since the start of training
  double samples_per_second = 0.0;
  int failed = 0;                 ///< failed sample evaluations in the epoch
};

struct TrainResult {
  std::vector<EpochRecord> history;
  double seconds = 0.0;
  int failed = 0;                 ///< over all epochs
  std::string first_failure;
};

/// Mean loss and mean gradient ∂ℓ/∂θ over `samples` at the current θ (no update);
/// distributed as in TrainSettings::distributed (collective over the ranks then).
BatchResult evaluate_mean(Objective& objective, const ParameterSet& theta, const std::vector<Index>& samples,
                          int threads, bool distributed = false);

/// Trains `theta` in place. Throws InputError on invalid settings, empty training set or
/// out-of-range sample indices.
TrainResult train(Objective& objective, ParameterSet& theta, const std::vector<Index>& training,
                  const std::vector<Index>& validation, const TrainSettings& settings);

/// Deterministic split of 0..n−1 into (training, validation) with a fraction in validation.
void split_samples(Index n, double validation_fraction, std::uint64_t seed, std::vector<Index>& training,
                   std::vector<Index>& validation);

}  // namespace lcprelax::learn
