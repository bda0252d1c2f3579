// `lcprelax pile` (docs/cli.md): the JSON contract on a small pile with both contact models,
// a picture file, the fc2d export, a scene file, --softening reaching the simulator, and bad
// input (exit 2, only the invalid_input object on stdout).
#include "cli_support.hpp"

#include <lcprelax/io/siconos_reader.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace lcprelax {
namespace {

using namespace testing_support;

class CliPile : public ::testing::TestWithParam<std::string> {};

// 20 polygons dropped for 60 steps: contacts appear, no solve fails, the energy never
// rises by more than 1e-6 of the initial total in one step (dissipative scheme), and the
// penetration stays below 2 cm (a few slops at the 1 cm margin).
TEST_P(CliPile, SmallPileReportsTheContractFields) {
  const std::string picture = temp_path("pile.svg");
  const CliRun r = run_cli("pile --bodies 20 --steps 60 --model " + GetParam() + " --json --picture '" + picture + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"bodies", "contacts_max", "steps", "seconds_per_step", "max_penetration", "max_residual",
                          "max_energy_gain"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["bodies"], 20);
  EXPECT_EQ(j["steps"], 60);
  EXPECT_GT(j["contacts_max"].get<int>(), 0);
  EXPECT_EQ(j["failed_islands"], 0);
  EXPECT_LE(j["max_energy_gain"].get<double>(), 1e-6);
  EXPECT_LT(j["max_penetration"].get<double>(), 2e-2);
  EXPECT_LT(j["max_residual"].get<double>(), 1e-6);
  EXPECT_NE(slurp(picture).find("<svg"), std::string::npos);
  std::filesystem::remove(picture);
}

INSTANTIATE_TEST_SUITE_P(Models, CliPile, ::testing::Values("convex", "lcp"));

TEST(CliPileExport, LastStepContactProblemIsAReadableFc2dFile) {
  const std::string file = temp_path("pile.dat");
  const CliRun r = run_cli("pile --bodies 20 --steps 60 --json --export-fc2d '" + file + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::Fc2dData d = io::read_siconos_fc2d(file);
  EXPECT_GT(d.contacts, 0);
  const CliRun solved = run_cli("fc2d '" + file + "' --json");
  EXPECT_EQ(solved.exit_code, 0) << solved.out;
  EXPECT_LE(nlohmann::json::parse(solved.out)["error"].get<double>(), 1e-10);
  std::filesystem::remove(file);
}

TEST(CliPileScene, RunsASceneFile) {
  const CliRun r = run_cli("pile --scene '" + kData + "/scenes/box_stack.json' --steps 50 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["contacts_max"].get<int>(), 0);
}

// --softening reaches the convex model: the JSON names the method, and the three methods give
// three different penetrations on the same pile (a setting that was dropped would give the
// default's numbers three times).
TEST(CliPileSoftening, EachMethodReachesTheSimulator) {
  std::vector<double> penetration;
  for (const auto& [flag, name] : std::vector<std::pair<std::string, std::string>>{
           {"", "exp_phi"}, {"penalty", "linear_penalty"}, {"impedance", "mujoco_impedance"}}) {
    const CliRun r = run_cli("pile --bodies 20 --steps 60 --json" + (flag.empty() ? "" : " --softening " + flag));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["softening"], name);
    penetration.push_back(j["max_penetration"].get<double>());
  }
  EXPECT_NE(penetration[0], penetration[1]);
  EXPECT_NE(penetration[0], penetration[2]);
  EXPECT_NE(penetration[1], penetration[2]);
  // The lcp model has no softening: no field, and the flag is an error (below).
  const CliRun lcp = run_cli("pile --bodies 5 --steps 2 --model lcp --json");
  ASSERT_EQ(lcp.exit_code, 0) << lcp.err;
  EXPECT_FALSE(nlohmann::json::parse(lcp.out).contains("softening"));
}

TEST(CliPileBadInput, SofteningErrorsNameTheOption) {
  for (const std::string args : {"pile --steps 1 --softening soft", "pile --steps 1 --model lcp --softening exp"}) {
    const CliRun r = run_cli(args + " --json");
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_TRUE(invalid_input_json(r.out)) << args << ": " << r.out;
    EXPECT_NE(r.err.find("--softening"), std::string::npos) << args << ": " << r.err;
  }
}

TEST(CliPileBadInput, ExitTwoWithAMessage) {
  for (const std::string args : {"pile --bodies 0", "pile --model foo", "pile --scene /nonexistent.json",
                                 "pile --steps 5 --picture /tmp/x.bmp"}) {
    const CliRun r = run_cli(args + " --json");
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_TRUE(invalid_input_json(r.out)) << args << ": " << r.out;
    EXPECT_FALSE(r.err.empty()) << args;
  }
}

}  // namespace
}  // namespace lcprelax
