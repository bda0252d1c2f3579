#pragma once
// Batched, parallel evaluation of per-sample losses and gradients with a fixed-order
// reduction.
//
// evaluate_batch() calls f(sample, thread) for every sample of a mini-batch, in parallel
// with OpenMP (`threads` threads, thread ∈ [0, threads) so that f can use one workspace
// per thread), stores each sample's result in its own slot, and then sums the slots
// sequentially in the order of `samples`. The floating-point sum is therefore the same
// for 1 and N threads: losses and gradients are bitwise identical (tests/learn_infra_test.cpp).
// A sample whose evaluation fails (ok = false, or f throws) is counted in `failed` and left
// out of the sums; its message is kept in first_failure.
//
// The per-sample result slots (one SampleResult with its gradient per sample) are kept by
// the calling thread for its next call (thread_local), so that gradients are not freed
// on the main thread after every batch (batch.cpp): memory of the order of n·(θ size)
// doubles stays allocated per calling thread.
#include <lcprelax/sparse/types.hpp>

#include <functional>
#include <string>
#include <vector>

namespace lcprelax::learn {

struct SampleResult {
  bool ok = true;
  std::string message;   ///< why it failed when !ok
  double loss = 0.0;     ///< ℓᵢ
  Vector gradient;       ///< ∂ℓᵢ/∂θ (parameter order of the ParameterSet)
};

struct BatchResult {
  double loss = 0.0;     ///< Σ ℓᵢ over the samples that succeeded
  Vector gradient;       ///< Σ ∂ℓᵢ/∂θ over the samples that succeeded
  int evaluated = 0;     ///< samples that succeeded
  int failed = 0;
  std::string first_failure;  ///< message of the first failed sample (in sample order)
};

using SampleFunction = std::function<SampleResult(Index sample, int thread)>;

/// Evaluates f on `samples` with `threads` threads (≤ 0: the OpenMP default) and reduces in
/// sample order. Every successful result's gradient must have length num_params.
BatchResult evaluate_batch(const std::vector<Index>& samples, Index num_params, int threads,
                           const SampleFunction& f);

/// Data-parallel evaluate_batch() over the MPI ranks (mpi/mpi_session.hpp): sample i is
/// evaluated by rank i mod R only (the dataset is sharded by rank, so a sample's warm
/// start stays on one rank), each rank with `threads` OpenMP threads; the per-sample
/// results (ok, loss, gradient) are then all-gathered and every rank sums them in the
/// order of `samples`. The result is identical on every rank and bitwise equal to the
/// one-process evaluate_batch() whenever each sample's evaluation is deterministic.
/// Messages of failures on other ranks read "failed on rank r". With one process (or a
/// build without PETSc/MPI) this is evaluate_batch(). Collective: every rank must call it
/// with the same samples.
BatchResult evaluate_batch_distributed(const std::vector<Index>& samples, Index num_params, int threads,
                                       const SampleFunction& f);

/// The number of threads evaluate_batch() uses for `threads` (≤ 0: the OpenMP default; 1
/// without OpenMP).
int resolve_threads(int threads);

}  // namespace lcprelax::learn
