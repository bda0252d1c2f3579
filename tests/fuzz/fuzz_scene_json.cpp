// libFuzzer target: the scene JSON reader (scenes/scene_json.hpp) on arbitrary bytes; a scene
// that reads is also written back and read again (write_scene may refuse it only with an
// InputError). Dictionary: scene_json.dict; seeds: tests/data/scenes.
#include <lcprelax/scenes/scene_json.hpp>

#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lcprelax;
  const std::string text = fuzz::text(data, size);
  Scene scene;
  if (!fuzz::read_or_input_error([&] { scene = parse_scene(text); })) return 0;
  std::string written;
  if (!fuzz::read_or_input_error([&] { written = write_scene(scene); })) return 0;
  fuzz::read_or_input_error([&] { (void)parse_scene(written); });
  return 0;
}
