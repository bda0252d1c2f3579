// `lcprelax pile --save-scene FILE`: the final state as a scene file that `--scene`
// continues from. Checked: the file is a scene with every body; reloading it and saving
// again after 0 steps gives the same scene but for its "steps" (the saved state is exactly
// what --scene loads); a free fall split in two runs (10 + 10 steps through the file) ends
// where 20 steps end (velocities are saved, not only poses); an lcp pile split in two
// runs through the file ends where the uninterrupted run ends, bit for bit, and with the same
// warm-start state (the file carries the bases the next step starts from); the human report
// names the file; an unwritable path is exit 2 before any step.
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace lcprelax {
namespace {

using namespace testing_support;
using Json = nlohmann::json;

class CliPileSaveScene : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kCli.empty() || !fs::exists(kCli)) GTEST_FAIL() << "lcprelax executable not built";
  }
};

TEST_F(CliPileSaveScene, SavedPileReloadsToTheSameState) {
  const std::string a = temp_path("saved_pile_a.json"), b = temp_path("saved_pile_b.json");
  fs::remove(a);
  fs::remove(b);
  CliRun r = run_cli("pile --bodies 6 --steps 30 --model lcp --save-scene '" + a + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json::parse(r.out)["saved_scene"], a);
  const Json scene = Json::parse(slurp(a));
  EXPECT_EQ(scene["bodies"].size(), 6u);
  EXPECT_EQ(scene["model"], "lcp");
  r = run_cli("pile --scene '" + a + "' --steps 0 --save-scene '" + b + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Everything but "steps" (the run's, here 30 and 0) is the same, number for number.
  Json ja = Json::parse(slurp(a)), jb = Json::parse(slurp(b));
  EXPECT_EQ(ja["steps"], 30);
  EXPECT_EQ(jb["steps"], 0);
  ja.erase("steps");
  jb.erase("steps");
  EXPECT_EQ(ja, jb);
}

TEST_F(CliPileSaveScene, AFreeFallContinuesFromTheFile) {
  // One box high above the ground: no contact within 20 steps of 0.01 s (it falls 0.2 m).
  const std::string scene = temp_path("save_scene_fall.json");
  std::ofstream(scene) << R"({"dt": 0.01, "model": "convex", "steps": 10, "bodies": [{"vertices": )"
                       << R"([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]], "density": 1, )"
                       << R"("position": [0, 10], "velocity": [1, 0], "angular_velocity": 0.5}],)"
                       << R"( "half_planes": [{"normal": [0, 1], "offset": 0}]})";
  const std::string half = temp_path("save_scene_half.json"), two = temp_path("save_scene_two.json"),
                    whole = temp_path("save_scene_whole.json");
  ASSERT_EQ(run_cli("pile --scene '" + scene + "' --steps 10 --save-scene '" + half + "' --json").exit_code, 0);
  ASSERT_EQ(run_cli("pile --scene '" + half + "' --steps 10 --save-scene '" + two + "' --json").exit_code, 0);
  ASSERT_EQ(run_cli("pile --scene '" + scene + "' --steps 20 --save-scene '" + whole + "' --json").exit_code, 0);
  const Json h = Json::parse(slurp(half))["bodies"][0], t = Json::parse(slurp(two))["bodies"][0],
             w = Json::parse(slurp(whole))["bodies"][0];
  EXPECT_NEAR(h["velocity"][1].get<double>(), -0.981, 1e-9);  // −g·10·Δt: the saved velocity
  EXPECT_LT(h["position"][1].get<double>(), 10.0);
  for (const char* key : {"position", "velocity"})
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(t[key][k].get<double>(), w[key][k].get<double>(), 1e-12) << key << k;
  EXPECT_NEAR(t["angle"].get<double>(), w["angle"].get<double>(), 1e-12);
  EXPECT_NEAR(t["angular_velocity"].get<double>(), w["angular_velocity"].get<double>(), 1e-12);
}

TEST_F(CliPileSaveScene, AnLcpPileContinuesFromTheFileAsUninterrupted) {
  const std::string half = temp_path("save_scene_lcp_half.json"), two = temp_path("save_scene_lcp_two.json"),
                    whole = temp_path("save_scene_lcp_whole.json");
  const std::string pile = "pile --bodies 20 --seed 3 --model lcp --json ";
  ASSERT_EQ(run_cli(pile + "--steps 60 --save-scene '" + half + "'").exit_code, 0);
  ASSERT_EQ(run_cli("pile --scene '" + half + "' --steps 25 --save-scene '" + two + "' --json").exit_code, 0);
  ASSERT_EQ(run_cli(pile + "--steps 85 --save-scene '" + whole + "'").exit_code, 0);
  const Json h = Json::parse(slurp(half)), t = Json::parse(slurp(two)), w = Json::parse(slurp(whole));
  ASSERT_TRUE(h.contains("warm_start"));
  EXPECT_GT(h["warm_start"].size(), 20u);
  EXPECT_EQ(t["bodies"], w["bodies"]);  // poses and velocities, number for number
  EXPECT_EQ(t["warm_start"], w["warm_start"]);
}

TEST_F(CliPileSaveScene, TheReportNamesTheFile) {
  const std::string path = temp_path("saved_pile_report.json");
  fs::remove(path);
  const CliRun r = run_cli("pile --bodies 3 --steps 5 --save-scene '" + path + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(report_value(r.out, "saved scene"), path) << r.out;
  EXPECT_TRUE(fs::exists(path));
}

TEST_F(CliPileSaveScene, UnwritablePathIsRefusedBeforeTheRun) {
  const CliRun r = run_cli("pile --bodies 3 --steps 100000 --save-scene /nonexistent_dir/x.json --json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--save-scene"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace lcprelax
