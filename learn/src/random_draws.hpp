#pragma once
// Library-independent random draws for the generated datasets (internal to learn/): the
// same numbers from the same seed on every standard library, unlike std::*_distribution.
#include <cmath>
#include <random>

namespace lcprelax::learn::detail {

/// A uniform double in [a, b) from the generator's top 53 bits.
inline double uniform(std::mt19937_64& rng, double a, double b) {
  return a + (b - a) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// A standard normal by Box–Muller from two uniforms (u1 in (0, 1], so the log is finite).
inline double normal(std::mt19937_64& rng) {
  const double u1 = 1.0 - uniform(rng, 0.0, 1.0), u2 = uniform(rng, 0.0, 1.0);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
}

}  // namespace lcprelax::learn::detail
