// libFuzzer target: the Matrix Market reader (sparse/matrix_market.hpp) on arbitrary bytes,
// as a matrix and as a vector, once with the input's size known (a regular file) and once
// unknown (a pipe: dimensions checked against the bytes read). Dictionary:
// matrix_market.dict; seeds: tests/data/fuzz/*.mtx (written by scripts/fuzz.sh).
#include <lcprelax/sparse/matrix_market.hpp>

#include "fuzz_check.hpp"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lcprelax;
  const std::string text = fuzz::text(data, size);
  {
    std::istringstream in(text);
    fuzz::read_or_input_error([&] { (void)sparse::parse_matrix_market(in, "fuzz.mtx", size); });
  }
  {
    std::istringstream in(text);
    fuzz::read_or_input_error([&] { (void)sparse::parse_matrix_market_vector(in, "fuzz.mtx"); });
  }
  return 0;
}
