#pragma once
// Training checkpoints: everything train() (trainer.hpp) needs to continue a run exactly as
// if it had never stopped, written atomically after every epoch.
//
// Contents (TrainCheckpoint): the epochs completed, θ, the optimizer's moments and step
// count, the shuffle generator's state (std::mt19937_64 via operator<<) and the current
// shuffled order of the training samples, the convergence test's state (previous C_k,
// streak), the counters, the whole epoch history (the log: TrainResult::history, from which
// the CSV log is rewritten on resume), and the objective's own per-sample state
// (Objective::save_state: warm starts, proximal centres), which later evaluations depend on.
// Resuming from it gives parameters BITWISE equal to those of an uninterrupted run
// (tests/learn_checkpoint_resume_test.cpp, tests/learn_checkpoint_kill_test.cpp).
//
// Identity: the checkpoint also records what run it belongs to (checkpoint_identity): the
// caller's problem description (TrainSettings::problem: for the CLI every option that
// defines data, model and loss), the number of samples, every parameter's name, transform,
// bounds and learn flag, the training and validation sets, batch, shuffle, seed, optimizer
// and convergence settings, and the MPI rank count. A resume whose identity differs fails
// with InputError naming the first differing field; the epoch cap and the thread count are
// not part of it (results do not depend on the thread count, batch.hpp).
//
// File format (docs/formats.md, "Training checkpoints"): binary, little-endian:
//   magic "LCPRCKPT" (8 bytes) | version u64 (= 1) | payload length u64 | payload |
//   checksum u64 (FNV-1a 64 of every preceding byte)
// with the payload in the StateWriter encoding (state_stream.hpp; doubles as their exact
// IEEE-754 bits). read_checkpoint rejects a wrong magic, an unknown version, a length that
// disagrees with the file size (truncated or extended file), a checksum mismatch and any
// malformed field with InputError naming the file and the problem.
#include <lcprelax/learn/optimizer.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <string>
#include <utility>
#include <vector>

namespace lcprelax::learn {

/// (field, value) pairs that identify a run; values may span several lines.
using CheckpointIdentity = std::vector<std::pair<std::string, std::string>>;

struct TrainCheckpoint {
  CheckpointIdentity identity;
  int epoch = 0;                  ///< epochs completed
  bool converged = false;         ///< the convergence test ended the run
  int streak = 0;                 ///< convergence test: consecutive epochs that held
  double previous_full_loss = 0;  ///< C_{k} of the last epoch (NaN if none)
  long evaluated_total = 0;       ///< successful sample evaluations so far
  int failed = 0;                 ///< TrainResult::failed so far
  std::string first_failure;
  Vector theta;                   ///< θ after `epoch` epochs
  OptimizerState optimizer;
  std::string rng;                ///< std::mt19937_64 state, text of operator<<
  std::vector<Index> order;       ///< the training samples in their current shuffled order
  std::vector<EpochRecord> history;
  std::string objective_state;    ///< bytes of Objective::save_state
};

/// The identity of the run train() is asked to do (see the header comment).
CheckpointIdentity checkpoint_identity(const Objective& objective, const ParameterSet& theta,
                                       const std::vector<Index>& training, const std::vector<Index>& validation,
                                       const TrainSettings& settings);

/// Throws InputError("checkpoint '<path>' belongs to another run: <field> ...") naming the
/// first field (and, for a multi-line value, the first line) in which `stored` and
/// `current` differ.
void check_checkpoint_identity(const CheckpointIdentity& stored, const CheckpointIdentity& current,
                               const std::string& path);

/// The file's bytes (header, payload, checksum).
std::string encode_checkpoint(const TrainCheckpoint& checkpoint);
/// Parses the bytes of a checkpoint file; `path` names it in errors. Throws InputError on any
/// corruption (header comment) or inconsistency (history length ≠ epoch, non-finite θ, ...).
TrainCheckpoint decode_checkpoint(const std::string& bytes, const std::string& path);

/// Writes `checkpoint` to `path` atomically (temporary file in the same directory, fsync,
/// rename, fsync of the directory): after a kill at any instant `path` holds the previous or
/// the new checkpoint, complete. Throws InputError if it cannot be written.
void write_checkpoint(const std::string& path, const TrainCheckpoint& checkpoint);
/// Reads and validates a checkpoint file (decode_checkpoint); InputError if it cannot be read.
TrainCheckpoint read_checkpoint(const std::string& path);
/// Throws InputError unless `path` can be written (before any training work is done).
void check_checkpoint_writable(const std::string& path);

/// The file of MPI rank `rank` for checkpoint `path`: `path` itself on rank 0,
/// "<path>.rank<r>" on the others (each rank keeps the warm starts of its own samples).
std::string checkpoint_path_for_rank(const std::string& path, int rank);

}  // namespace lcprelax::learn
