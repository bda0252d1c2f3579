// Parallel per-sample evaluation with a fixed-order reduction (batch.hpp).
#include <lcprelax/learn/batch.hpp>

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

BatchResult evaluate_batch(const std::vector<Index>& samples, Index num_params, int threads,
                           const SampleFunction& f) {
  const int n = static_cast<int>(samples.size());
  std::vector<SampleResult> slots(samples.size());
  const int nthreads = resolve_threads(threads);
#ifdef LCPRELAX_HAS_OPENMP
#pragma omp parallel for schedule(dynamic) num_threads(nthreads)
#endif
  for (int k = 0; k < n; ++k) {
    int thread = 0;
#ifdef LCPRELAX_HAS_OPENMP
    thread = omp_get_thread_num();
#endif
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

}  // namespace lcprelax::learn
