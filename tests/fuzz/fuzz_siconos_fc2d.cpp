// libFuzzer target: the Siconos fc2d .dat reader (io/siconos_reader.hpp) on arbitrary bytes,
// with the input's size known. Dictionary: siconos.dict; seeds: tests/data/siconos (fc2d,
// handmade, malformed).
#include <lcprelax/io/siconos_reader.hpp>

#include "fuzz_check.hpp"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(lcprelax::fuzz::text(data, size));
  lcprelax::fuzz::read_or_input_error([&] { (void)lcprelax::io::parse_siconos_fc2d(in, "fuzz.dat", size); });
  return 0;
}
