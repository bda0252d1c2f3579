#pragma once
// Exceptions for bad input (malformed files, NaN/Inf data, inconsistent dimensions).
// Algorithmic outcomes (infeasible, max iterations, ...) are never exceptions: they are
// statuses in each solver's Info.
#include <stdexcept>
#include <string>

namespace lcprelax {

/// Thrown for invalid user input; what() names the offending field, file or line.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lcprelax
