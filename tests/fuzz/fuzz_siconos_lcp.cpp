// libFuzzer target: the Siconos LCP .dat reader (io/siconos_reader.hpp) on arbitrary bytes,
// with the input's size known (as for a regular file) so that the size checks run too.
// Dictionary: siconos.dict; seeds: tests/data/siconos (lcp, handmade, malformed).
#include <lcprelax/io/siconos_reader.hpp>

#include "fuzz_check.hpp"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(lcprelax::fuzz::text(data, size));
  lcprelax::fuzz::read_or_input_error([&] { (void)lcprelax::io::parse_siconos_lcp(in, "fuzz.dat", size); });
  return 0;
}
