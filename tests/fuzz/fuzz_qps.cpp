// libFuzzer target: the QPS reader (io/qps_reader.hpp) on arbitrary bytes. Dictionary:
// qps.dict; seeds: tests/data/qps, tests/data/maros_meszaros (small files), tests/data/fuzz.
#include <lcprelax/io/qps_reader.hpp>

#include "fuzz_check.hpp"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(lcprelax::fuzz::text(data, size));
  lcprelax::fuzz::read_or_input_error([&] { (void)lcprelax::io::parse_qps(in, "fuzz.qps"); });
  return 0;
}
