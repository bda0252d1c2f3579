#pragma once
// Wall-clock timing of solver phases (the *_seconds fields of the stats and results):
// seconds on std::chrono::steady_clock, which never goes backwards.
#include <chrono>

namespace lcprelax {

using SteadyClock = std::chrono::steady_clock;

/// Seconds elapsed since t0 (steady clock).
inline double seconds_since(SteadyClock::time_point t0) {
  return std::chrono::duration<double>(SteadyClock::now() - t0).count();
}

}  // namespace lcprelax
