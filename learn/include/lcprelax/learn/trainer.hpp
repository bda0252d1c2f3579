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
//
// Levenberg–Marquardt (OptimizerKind::lm, full batch only, at most 400 parameters, objectives with
// evaluate_residuals() only, else InputError): an epoch is one damped Gauss–Newton
// iteration (learn/src/levenberg_marquardt.hpp); a run whose iteration finds no decrease at
// any damping ends with "lm found no decrease ...".
//
// L-BFGS (OptimizerKind::lbfgs, full batch only, else InputError): an epoch is one
// quasi-Newton iteration — the training set's loss and gradient at the epoch's θ, then a
// backtracking line search whose trial points are further evaluations of the whole set
// (details in learn/src/lbfgs_line_search.hpp). EpochRecord's loss and gradient
// are those at the epoch's starting θ; samples_per_second counts the trial evaluations too.
// A line search that finds no decrease even along −g ends the run ("lbfgs line search found
// no decrease ...", converged = false): θ is then at a kink or at the loss's noise floor.
//
// Stopping: TrainSettings::epochs is a cap; a run ends earlier once it has converged.
// After epoch k the trainer has C_k and g_k, the mean loss and the mean gradient ∂ℓ/∂ξ over
// the WHOLE training set at one θ (EpochRecord::full_loss, full_gradient_norm = ‖g_k‖₂):
// - full batch (batch = 0 or ≥ the training set): the epoch's own evaluation, at the θ the
//   epoch started from (no extra cost);
// - mini-batches: one extra evaluation of the whole training set at the epoch's end θ (one
//   more pass per epoch; only while the test is on, patience > 0).
// Epoch k satisfies the test when every training sample evaluated and
//   Δ_k = |C_{k−1} − C_k| / max(|C_{k−1}|, |C_k|, 1) ≤ rel_loss_tol   (EpochRecord::relative_loss_change)
//   ‖g_k‖₂ ≤ grad_tol,
// the relative change being that of L-BFGS-B's `factr`/SciPy's `ftol` test (Zhu, Byrd, Lu &
// Nocedal, ACM TOMS 23(4), 1997): relative for |C| ≥ 1, absolute below, so a loss that
// decays geometrically towards 0 still passes it. The run stops, converged, after
// `patience` consecutive such epochs (EpochRecord::streak); epoch 1 has no Δ and never
// counts. Otherwise it stops at the cap with TrainResult::converged = false.
// Why these numbers and not the epoch loss: with mini-batches (and Adam) the epoch loss
// mixes several θ and the sampling of the batches, so it is noisy — a lucky epoch would
// stop a run early and the noise floor of its change would keep it from ever stopping.
// C_k and g_k are deterministic functions of θ, so the only noise left is the movement of θ
// itself: a constant learning rate on mini-batches keeps θ jittering around the minimum and
// ‖g‖ at a floor set by that jitter, which is honestly reported as "epoch cap reached"
// (use a schedule, OptimizerSettings::decay, a larger batch or a looser grad_tol). The
// patience window keeps an oscillating optimizer (Adam crossing the minimum, where the loss
// momentarily stops changing) from stopping on one epoch. The numbers come from
// evaluate_batch / evaluate_batch_distributed (sums in a fixed order, identical for every
// thread count and on every rank), so the decision is identical on every rank and for
// every thread count.
//
// Checkpoints (checkpoint.hpp): with TrainSettings::checkpoint set, the complete state of
// the run (θ, optimizer moments, shuffle generator and order, convergence test, history,
// the objective's warm starts) is written atomically after every epoch; with
// TrainSettings::resume, train() continues from such a file and ends with θ bitwise equal
// to that of a run that was never interrupted (with any thread count).
#include <lcprelax/learn/batch.hpp>
#include <lcprelax/learn/least_squares.hpp>
#include <lcprelax/learn/optimizer.hpp>
#include <lcprelax/learn/parameters.hpp>
#include <lcprelax/learn/state_stream.hpp>

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
  /// State kept between evaluations that later results depend on (per-sample warm starts,
  /// proximal centres), for checkpoints: save_state() appends it to `out`, load_state()
  /// reads back exactly what save_state() wrote (failing through `in`, InputError, when it
  /// does not fit this objective). An objective without such state keeps the defaults.
  virtual void save_state(StateWriter& /*out*/) const {}
  virtual void load_state(StateReader& /*in*/) {}
  /// Least-squares objectives (least_squares.hpp): empty when evaluate_residuals() is
  /// available, else why not (the message train() gives for OptimizerKind::lm).
  virtual std::string residuals_unavailable() const { return "this loss is not a sum of squares"; }
  /// rᵢ and ∂rᵢ/∂θ with ℓᵢ = ‖rᵢ‖² (same θ, thread and prepare() rules as evaluate()).
  /// The default throws std::logic_error.
  virtual ResidualResult evaluate_residuals(Index sample, const ParameterSet& theta, int thread);
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
  /// Convergence test (header comment): stop after `patience` consecutive epochs with the
  /// relative loss change Δ_k ≤ rel_loss_tol and the full-training-set gradient norm
  /// ‖∂C/∂ξ‖₂ ≤ grad_tol. Defaults measured on `lcprelax learn block --method relaxed
  /// --init-mu 1` (full batch, Adam α = 0.05, loss ≈ 5e-5 at the minimum): Δ_k falls below
  /// 1e-9 near epoch 200 (μ = 0.10025), ‖g‖ below 1e-7 from epoch 274, and the run stops
  /// after 278 epochs at μ = 0.100146, the minimizer itself to 5e-7.
  double rel_loss_tol = 1e-9;     ///< finite, ≥ 0
  double grad_tol = 1e-7;         ///< finite, ≥ 0
  int patience = 5;               ///< ≥ 0; 0 switches the test off (exactly `epochs` epochs)
  /// Checkpoint file (checkpoint.hpp): if non-empty, the run's state is written to it
  /// atomically after every epoch (under MPI each rank writes its own file,
  /// checkpoint_path_for_rank). Checked for writability before the first epoch.
  std::string checkpoint;
  /// If non-empty, continue the run saved in this checkpoint (its identity must match this
  /// call's, checkpoint.hpp); `epochs` stays the cap counted from the run's start and must
  /// be ≥ the epochs already done. The CSV log is rewritten from the saved history.
  std::string resume;
  /// The caller's description of the problem (data, model, loss settings), stored in the
  /// checkpoint and compared on resume.
  std::string problem;
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
  /// C_k: mean loss over the whole training set (header comment; NaN when mini-batched
  /// with patience 0 or when no sample evaluated).
  double full_loss = 0.0;
  double full_gradient_norm = 0.0;     ///< ‖g_k‖₂, ‖mean ∂ℓ/∂ξ‖₂ over the training set (NaN as full_loss)
  double relative_loss_change = 0.0;   ///< Δ_k (NaN in epoch 1 or without C_{k−1}, C_k)
  int streak = 0;                      ///< consecutive epochs up to this one that satisfy the test
};

struct TrainResult {
  std::vector<EpochRecord> history;
  double seconds = 0.0;
  int failed = 0;                 ///< over all epochs
  std::string first_failure;
  bool converged = false;         ///< the convergence test held for `patience` epochs
  /// Why the run ended: "converged: relative loss change <= 1e-09 and gradient norm <= 1e-07
  /// for 5 epochs", "epoch cap reached (N epochs)", "lbfgs line search found no decrease
  /// along -gradient after N epochs (...)" or, with patience = 0, "epoch cap reached
  /// (N epochs, convergence test off)".
  std::string stop_reason;
};

/// Mean loss and mean gradient ∂ℓ/∂θ over `samples` at the current θ (no update);
/// distributed as in TrainSettings::distributed (collective over the ranks then).
BatchResult evaluate_mean(Objective& objective, const ParameterSet& theta, const std::vector<Index>& samples,
                          int threads, bool distributed = false);

/// Trains `theta` in place. Throws InputError on invalid settings, empty training set,
/// out-of-range sample indices, an unwritable checkpoint, or a resume checkpoint that is
/// unreadable, corrupt or of another run.
TrainResult train(Objective& objective, ParameterSet& theta, const std::vector<Index>& training,
                  const std::vector<Index>& validation, const TrainSettings& settings);

/// Deterministic split of 0..n−1 into (training, validation) with a fraction in validation.
void split_samples(Index n, double validation_fraction, std::uint64_t seed, std::vector<Index>& training,
                   std::vector<Index>& validation);

}  // namespace lcprelax::learn
