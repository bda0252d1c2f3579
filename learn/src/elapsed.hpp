#pragma once
// Wall-clock timing of the learning code's phases (assembly / solve / backward), internal.
#include <chrono>

namespace lcprelax::learn::detail {

using Clock = std::chrono::steady_clock;

/// Seconds elapsed since t.
inline double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace lcprelax::learn::detail
