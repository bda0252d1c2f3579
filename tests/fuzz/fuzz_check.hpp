#pragma once
// Shared by the libFuzzer targets of tests/fuzz: runs one reader on the input and accepts
// exactly two outcomes, a value or lcprelax::InputError with a non-empty message of at most
// 2 KiB (the readers cut echoed tokens to 64 characters and messages to 1 KiB plus the source
// name). Any other exception escapes, so libFuzzer reports it as a crash; sanitizers report
// memory errors, undefined behaviour, leaks, allocations over -malloc_limit_mb and hangs.
#include <lcprelax/core/errors.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace lcprelax::fuzz {

/// The input as a string (the readers take streams or text).
inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Runs `read()`; returns true when it returned normally, false on InputError.
template <class Read>
bool read_or_input_error(Read&& read) {
  try {
    read();
    return true;
  } catch (const InputError& e) {
    const std::size_t n = std::strlen(e.what());
    if (n == 0 || n > 2048) {
      std::fprintf(stderr, "InputError message of %zu bytes\n", n);
      std::abort();
    }
    return false;
  }
}

}  // namespace lcprelax::fuzz
