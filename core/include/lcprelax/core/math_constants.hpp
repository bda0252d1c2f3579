#pragma once
// Mathematical constants of the library (double precision).
#include <limits>

namespace lcprelax {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kHalfPi = 1.57079632679489661923;
inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace lcprelax
