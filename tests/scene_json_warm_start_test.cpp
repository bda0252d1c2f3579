// A scene file's "warm_start" list (scene_json.hpp, docs/formats.md). Expected:
// - write_scene writes the scene's warm-start records as 7-integer arrays, 8 for a
//   regularized record (its 8th integer 1), and parse_scene reads them back equal (an 8th
//   integer 0 is read as not regularized); a scene without records writes no "warm_start" key;
// - make_simulator hands them to the simulator (Simulator::warm_start_state);
// - entries that are not 7 or 8 integers in their ranges are InputErrors naming the entry, and
//   write_scene refuses a code that is not an integer of its range.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/scenes/scene_json.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lcprelax {
namespace {

const char* kTwoBoxes = R"({"bodies": [
  {"vertices": [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]], "density": 1, "position": [0, 0.5]},
  {"vertices": [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]], "density": 1, "position": [0, 1.5]}],
  "half_planes": [{"normal": [0, 1]}])";

std::string with_warm_start(const std::string& entries) {
  return std::string(kTwoBoxes) + ", \"warm_start\": [" + entries + "]}";
}

void expect_input_error(const std::string& text, const std::string& part) {
  try {
    parse_scene(text);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(SceneJsonWarmStart, WrittenAndReadBackEqual) {
  Scene s = parse_scene(
      with_warm_start("[0, -1, 1, 0, 0, 1, 6], [0, -1, 1, 0, 1, 1, 2, 1], [1, 0, 0, -1, 0, 0, 0, 0]"));
  ASSERT_EQ(s.warm_start.size(), 3u);
  EXPECT_EQ(s.warm_start[1].key, (ContactKey{0, -1, 1, 0, 1}));
  EXPECT_EQ(s.warm_start[1].normal, 1.0);
  EXPECT_EQ(s.warm_start[1].friction, 2.0);
  EXPECT_FALSE(s.warm_start[0].regularized);
  EXPECT_TRUE(s.warm_start[1].regularized);
  EXPECT_FALSE(s.warm_start[2].regularized);
  const std::string text = write_scene(s);
  EXPECT_NE(text.find("\"warm_start\""), std::string::npos);
  EXPECT_NE(text.find("[0, -1, 1, 0, 1, 1, 2, 1]"), std::string::npos) << "the regularized record's 8th integer: " << text;
  EXPECT_NE(text.find("[1, 0, 0, -1, 0, 0, 0]"), std::string::npos) << "7 integers when not regularized: " << text;
  const Scene t = parse_scene(text);
  ASSERT_EQ(t.warm_start.size(), s.warm_start.size());
  for (std::size_t i = 0; i < s.warm_start.size(); ++i) {
    EXPECT_EQ(t.warm_start[i].key, s.warm_start[i].key);
    EXPECT_EQ(t.warm_start[i].normal, s.warm_start[i].normal);
    EXPECT_EQ(t.warm_start[i].friction, s.warm_start[i].friction);
    EXPECT_EQ(t.warm_start[i].regularized, s.warm_start[i].regularized);
  }
  s.warm_start.clear();
  EXPECT_EQ(write_scene(s).find("warm_start"), std::string::npos);
}

TEST(SceneJsonWarmStart, TheSimulatorStartsFromThem) {
  const Scene s = parse_scene(with_warm_start("[1, 0, 0, -1, 0, 1, 0], [0, -1, 1, 0, 0, 1, 0]"));
  const Simulator sim = make_simulator(s);
  const std::vector<ContactWarmRecord> state = sim.warm_start_state();
  ASSERT_EQ(state.size(), 2u);
  EXPECT_EQ(state[0].key, (ContactKey{0, -1, 1, 0, 0}));  // key order
  EXPECT_EQ(state[1].key, (ContactKey{1, 0, 0, -1, 0}));
  EXPECT_TRUE(make_simulator(parse_scene(std::string(kTwoBoxes) + "}")).warm_start_state().empty());
}

TEST(SceneJsonWarmStart, BadEntriesNameTheEntry) {
  expect_input_error(with_warm_start("[0, -1, 1, 0, 0, 1]"), "warm_start[0]: expected 7 or 8 integers");
  expect_input_error(with_warm_start("[0, -1, 1, 0, 0, 1, 0, 1, 0]"), "warm_start[0]: expected 7 or 8 integers");
  expect_input_error(with_warm_start("[0, -1, 1, 0, 0, 1, 0, 2]"), "warm_start[0][7]: must be in [0, 1], got 2");
  expect_input_error(with_warm_start("[0, -1, 1, 0, 0, 1, 0], 3"), "warm_start[1]: expected an array");
  expect_input_error(with_warm_start("[2, -1, 1, 0, 0, 1, 0]"), "warm_start[0][0]: must be in [0, 1], got 2");
  expect_input_error(with_warm_start("[0, -2, 1, 0, 0, 1, 0]"), "warm_start[0][1]: must be in [-1, 1]");
  expect_input_error(with_warm_start("[0, -1, 3, 0, 0, 1, 0]"), "warm_start[0][2]: must be in [0, 2]");
  expect_input_error(with_warm_start("[0, -1, 1, 0, -1, 1, 0]"), "warm_start[0][4]");
  expect_input_error(with_warm_start("[0, -1, 1, 0, 0, 2, 0]"), "warm_start[0][5]: must be in [0, 1], got 2");
  expect_input_error(with_warm_start("[0, -1, 1, 0, 0, 1, 8]"), "warm_start[0][6]: must be in [0, 7], got 8");
  expect_input_error(with_warm_start("[0, -1, 1, 0, 0, 1, 0.5]"), "warm_start[0][6]: expected an integer");
  expect_input_error(R"({"warm_start": [[0, -1, 1, 0, 0, 1, 0]]})", "warm_start[0][0]");  // no bodies
  expect_input_error(R"({"warm_start": {"a": 1}})", "warm_start: expected an array");
}

TEST(SceneJsonWarmStart, WriteRefusesCodesThatAreNotIntegers) {
  Scene s = parse_scene(std::string(kTwoBoxes) + "}");
  s.warm_start.push_back({{0, -1, 1, 0, 0}, 1.0, 0.5});
  try {
    write_scene(s);
    ADD_FAILURE() << "a friction code of 0.5 was written";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("warm_start[0]"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lcprelax
