// Parallel per-sample evaluation with a fixed-order reduction (batch.hpp).
#include <lcprelax/learn/batch.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include <algorithm>
#include <exception>

#ifdef LCPRELAX_HAS_OPENMP
#include <omp.h>
#endif

namespace lcprelax::learn {

int resolve_threads(int threads) {
#ifdef LCPRELAX_HAS_OPENMP
  return threads > 0 ? threads : omp_get_max_threads();
#else
  (void)threads;
  return 1;
#endif
}

namespace {

// Result slots of the calling thread's last batch, reused by its next one. Each sample's
// gradient is allocated by the thread that evaluates it. Kept, a slot's previous gradient
// is freed when its new result is moved in, by the thread that evaluates it, which then
// reuses that memory from its own cache; freeing the slots after every batch would put all
// those frees in the serial part, on the main thread, half of them into the other threads'
// malloc arenas (their locks, no tcache). A nested call on the same thread finds the cache
// empty (moved out) and uses fresh slots.
thread_local std::vector<SampleResult> slot_cache;

std::vector<SampleResult> take_slots(std::size_t n) {
  std::vector<SampleResult> slots = std::move(slot_cache);
  slot_cache.clear();
  slots.resize(n);
  return slots;
}

void keep_slots(std::vector<SampleResult>&& slots) { slot_cache = std::move(slots); }

// Evaluates f at the positions k of `samples` with mine[k] (all when mine is empty) into
// slots (size n; the slots of skipped positions are left as they are).
void evaluate_slots(const std::vector<Index>& samples, Index num_params, int threads, const SampleFunction& f,
                    const std::vector<char>& mine, std::vector<SampleResult>& slots) {
  const int n = static_cast<int>(samples.size());
  const int nthreads = resolve_threads(threads);
#ifdef LCPRELAX_HAS_OPENMP
  // Chunks of consecutive samples (about 16 per thread) rather than single samples: threads
  // then rarely write neighbouring result slots or per-sample warm starts at the same time
  // (false sharing), and the scheduler is touched less often for µs-sized samples. The
  // reduction below is in sample order, so the chunking never changes results.
  const int chunk = std::max(1, n / (16 * nthreads));
#pragma omp parallel for schedule(dynamic, chunk) num_threads(nthreads)
#endif
  for (int k = 0; k < n; ++k) {
    int thread = 0;
#ifdef LCPRELAX_HAS_OPENMP
    thread = omp_get_thread_num();
#endif
    if (!mine.empty() && !mine[static_cast<std::size_t>(k)]) continue;
    SampleResult& slot = slots[static_cast<std::size_t>(k)];
    try {
      slot = f(samples[static_cast<std::size_t>(k)], thread);
      if (slot.ok && slot.gradient.size() != num_params) {
        slot.ok = false;
        slot.message = "gradient of length " + std::to_string(slot.gradient.size()) + ", expected " +
                       std::to_string(num_params);
      }
    } catch (const std::exception& e) {
      slot.ok = false;
      slot.message = e.what();
    }
  }
  (void)nthreads;
}

BatchResult reduce_in_order(const std::vector<Index>& samples, Index num_params, const std::vector<SampleResult>& slots) {
  const int n = static_cast<int>(samples.size());
  BatchResult out;
  out.gradient = Vector::Zero(num_params);
  for (int k = 0; k < n; ++k) {  // fixed order: bitwise identical for every thread count
    const SampleResult& r = slots[static_cast<std::size_t>(k)];
    if (!r.ok) {
      if (out.failed++ == 0) out.first_failure = "sample " + std::to_string(samples[static_cast<std::size_t>(k)]) + ": " + r.message;
      continue;
    }
    out.loss += r.loss;
    out.gradient += r.gradient;
    ++out.evaluated;
  }
  return out;
}

}  // namespace

BatchResult evaluate_batch(const std::vector<Index>& samples, Index num_params, int threads,
                           const SampleFunction& f) {
  std::vector<SampleResult> slots = take_slots(samples.size());
  evaluate_slots(samples, num_params, threads, f, {}, slots);
  BatchResult out = reduce_in_order(samples, num_params, slots);
  keep_slots(std::move(slots));
  return out;
}

BatchResult evaluate_batch_distributed(const std::vector<Index>& samples, Index num_params, int threads,
                                       const SampleFunction& f) {
  const int ranks = mpi::mpi_size(), rank = mpi::mpi_rank();
  if (ranks <= 1) return evaluate_batch(samples, num_params, threads, f);
  const std::size_t n = samples.size(), width = static_cast<std::size_t>(num_params) + 2;  // ok, loss, gradient
  std::vector<char> mine(n);
  for (std::size_t k = 0; k < n; ++k) mine[k] = samples[k] % ranks == rank;
  std::vector<SampleResult> slots = take_slots(n);
  evaluate_slots(samples, num_params, threads, f, mine, slots);
  std::vector<double> packed(n * width, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    if (!mine[k] || !slots[k].ok) continue;
    double* row = packed.data() + k * width;
    row[0] = 1.0;
    row[1] = slots[k].loss;
    for (Index j = 0; j < num_params; ++j) row[2 + j] = slots[k].gradient(j);
  }
  const std::vector<double> all = mpi::allgather(packed);  // rank-major: R blocks of n·width
  for (std::size_t k = 0; k < n; ++k) {
    if (mine[k]) continue;
    const int owner = static_cast<int>(samples[k] % ranks);
    const double* row = all.data() + static_cast<std::size_t>(owner) * n * width + k * width;
    SampleResult& slot = slots[k];
    slot.ok = row[0] == 1.0;
    if (!slot.ok) {
      slot.message = "failed on rank " + std::to_string(owner);
      continue;
    }
    slot.loss = row[1];
    slot.gradient = Eigen::Map<const Vector>(row + 2, num_params);
  }
  BatchResult out = reduce_in_order(samples, num_params, slots);
  keep_slots(std::move(slots));
  return out;
}

}  // namespace lcprelax::learn
