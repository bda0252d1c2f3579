// `lcprelax pile --scene FILE` (issue 19): the scene file's "model" and "steps" hold unless a
// flag names them (they were silently replaced by the CLI defaults), and extreme values of
// a scene file are blamed on the user's field, not on a derived one ("CollisionSettings:
// margin = inf") nor on a wrong cause ("vertices coincide" for vertices 2e200 apart).
// Coincident bodies (every pair overlapping: 100 boxes pose 9,900 contacts on 300 DOFs)
// run with bounded memory instead of stalling for minutes.
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

using namespace testing_support;
using Json = nlohmann::json;

const std::string kBox = "[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]";

// A scene of `bodies` (JSON objects) over a ground half-plane, with "model" and "steps".
std::string write_scene(const std::string& name, const std::string& model, int steps,
                        const std::vector<std::string>& bodies) {
  std::string list;
  for (const std::string& b : bodies) list += (list.empty() ? "" : ", ") + b;
  const std::string path = temp_path(name);
  std::ofstream(path) << R"({"dt": 0.01, "model": ")" << model << R"(", "steps": )" << steps << R"(, "bodies": [)"
                      << list << R"(], "half_planes": [{"normal": [0, 1], "offset": 0}]})";
  return path;
}

std::string box(const std::string& extra = "") {
  return R"({"vertices": )" + kBox + R"(, "density": 1, "position": [0, 1])" + extra + "}";
}

class CliPileSceneSettings : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kCli.empty() || !fs::exists(kCli)) GTEST_FAIL() << "lcprelax executable not built";
  }
};

TEST_F(CliPileSceneSettings, TheFilesModelAndStepsHoldUnlessAFlagNamesThem) {
  const std::string scene = write_scene("settings_scene.json", "lcp", 7, {box()});
  CliRun r = run_cli("pile --scene '" + scene + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Json j = Json::parse(r.out);
  EXPECT_EQ(j["model"], "lcp");
  EXPECT_EQ(j["steps"], 7);
  r = run_cli("pile --scene '" + scene + "' --steps 3 --model convex --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = Json::parse(r.out);
  EXPECT_EQ(j["model"], "convex");
  EXPECT_EQ(j["steps"], 3);
  // --bodies describes a random pile: with a scene it is an error, not ignored.
  EXPECT_EQ(run_cli("pile --scene '" + scene + "' --bodies 50").exit_code, 2);
  fs::remove(scene);
}

// The scene file's "softening" holds unless --softening names one; a bad value names the field.
TEST_F(CliPileSceneSettings, TheFilesSofteningHoldsUnlessTheFlagNamesIt) {
  const auto scene_with = [](const std::string& name, const std::string& softening) {
    const std::string path = temp_path(name);
    std::ofstream(path) << R"({"dt": 0.01, "model": "convex", "softening": ")" << softening
                        << R"(", "steps": 3, "bodies": [)" << box() << R"(], "half_planes": [{"normal": [0, 1]}]})";
    return path;
  };
  const std::string scene = scene_with("softening_scene.json", "penalty");
  CliRun r = run_cli("pile --scene '" + scene + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json::parse(r.out)["softening"], "linear_penalty");
  r = run_cli("pile --scene '" + scene + "' --softening impedance --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json::parse(r.out)["softening"], "mujoco_impedance");
  const std::string bad = scene_with("bad_softening_scene.json", "soft");
  r = run_cli("pile --scene '" + bad + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("softening: unknown softening 'soft'"), std::string::npos) << r.err;
  fs::remove(scene), fs::remove(bad);
}

TEST_F(CliPileSceneSettings, ExtremeValuesNameTheUsersField) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {box(R"(, "velocity": [1e308, 0])"), "bodies[0].velocity"},
      {box(R"(, "angular_velocity": 1e300)"), "bodies[0].angular_velocity"},
      {R"({"vertices": )" + kBox + R"(, "density": 1, "position": [1e300, 1]})", "bodies[0].position"},
      {R"({"vertices": )" + kBox + R"(, "density": 1e308, "position": [0, 1]})", "bodies[0].density"},
      {R"({"vertices": [[-1e200, -1e200], [1e200, -1e200], [1e200, 1e200], [-1e200, 1e200]], "density": 1})",
       "bodies[0].vertices: vertex 0"},
      {R"({"vertices": [[-1e-170, -1e-170], [1e-170, -1e-170], [1e-170, 1e-170], [-1e-170, 1e-170]], "density": 1})",
       "smaller than"},
  };
  for (const auto& [body, field] : cases) {
    const std::string scene = write_scene("extreme_scene.json", "convex", 2, {body});
    const CliRun r = run_cli("pile --scene '" + scene + "'");
    EXPECT_EQ(r.exit_code, 2) << body;
    EXPECT_NE(r.err.find(field), std::string::npos) << body << ": " << r.err;
    EXPECT_EQ(r.err.find("coincide"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("CollisionSettings"), std::string::npos) << r.err;
    fs::remove(scene);
  }
}

TEST_F(CliPileSceneSettings, CoincidentBoxesRunInBoundedTime) {
  // 100 boxes at one place (9,900 contacts): stalled for more than 60 s at 1 GB; now a
  // fraction of a second per step with both models.
  const std::vector<std::string> bodies(100, box());
  const std::string scene = write_scene("coincident_scene.json", "convex", 2, bodies);
  for (const char* model : {"convex", "lcp"}) {
    const CliRun r = run_cli("pile --scene '" + scene + "' --model " + model + " --json");
    ASSERT_FALSE(r.out.empty()) << model << ": " << r.err;
    const Json j = Json::parse(r.out);
    EXPECT_EQ(j["contacts_max"], 9900) << model;
    EXPECT_LT(j["seconds_per_step"].get<double>(), 10.0) << model;
  }
  fs::remove(scene);
}

}  // namespace
}  // namespace lcprelax
