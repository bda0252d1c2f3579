// libFuzzer target: the trajectory CSV reader (scenes/trajectory_csv.hpp) on arbitrary bytes.
// Dictionary: csv.dict; seeds: tests/data/fuzz/*.csv and tests/data/block/*.csv.
#include <lcprelax/scenes/trajectory_csv.hpp>

#include "fuzz_check.hpp"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(lcprelax::fuzz::text(data, size));
  lcprelax::fuzz::read_or_input_error([&] { (void)lcprelax::read_trajectory(in, "fuzz.csv"); });
  return 0;
}
