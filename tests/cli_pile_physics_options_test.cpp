// `lcprelax pile --dt S --gravity G --qp-eps E --lemke-tol E` (docs/cli.md):
// - a non-positive, NaN or infinite time step, a negative or non-finite gravity, a
//   non-positive QP tolerance and a negative Lemke tolerance are bad input: exit 2, the
//   message on stderr names the flag and what it must be, --json prints the invalid_input
//   object (the flags did not exist: CLI11's "arguments were not expected" named none of this);
// - the values reach the simulation: the report prints the time step and gravity used, a
//   scene file keeps its gravity's direction (|(3, −4)| = 5 scaled to 10 gives (6, −8)),
//   and a pile without gravity makes fewer contacts than one with it;
// - the tolerances reach the solvers: a looser --qp-eps changes the convex model's results;
// - --post-stabilization-passes reaches the simulator: the default 5 passes leave a dropping
//   30-body pile (150 steps) less overlap than a single pass (6.6 mm → 0.1 mm measured).
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace lcprelax {
namespace {

using namespace testing_support;
using Json = nlohmann::json;

class CliPilePhysics : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kCli.empty() || !fs::exists(kCli)) GTEST_FAIL() << "lcprelax executable not built";
  }
};

TEST_F(CliPilePhysics, InvalidValuesAreBadInputNamingTheFlag) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--dt -1", "--dt: the time step must be a positive finite number of seconds, got -1"},
      {"--dt 0", "--dt: the time step must be a positive finite number of seconds, got 0"},
      {"--dt nan", "--dt: the time step must be a positive finite number of seconds, got nan"},
      {"--dt inf", "--dt: the time step must be a positive finite number of seconds, got inf"},
      {"--gravity -9.81", "--gravity: the magnitude of gravity must be a finite number of m/s²"},
      {"--gravity nan", "--gravity: the magnitude of gravity must be a finite number of m/s²"},
      {"--gravity 1e16", "--gravity: the magnitude of gravity must be a finite number of m/s²"},
      {"--qp-eps 0", "--qp-eps: must be a positive finite number"},
      {"--qp-eps nan", "--qp-eps: must be a positive finite number"},
      {"--lemke-tol -1e-9", "--lemke-tol: must be a finite number >= 0"},
      {"--post-stabilization-passes 0", "--post-stabilization-passes: must be >= 1, got 0"},
      {"--model lcp --release-open-contacts", "--release-open-contacts: applies to the convex model only"},
  };
  for (const auto& [flag, message] : cases) {
    CliRun r = run_cli("pile --bodies 3 --steps 2 " + flag);
    EXPECT_EQ(r.exit_code, 2) << flag;
    EXPECT_NE(r.err.find(message), std::string::npos) << flag << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << flag << ": " << r.out;
    r = run_cli("pile --bodies 3 --steps 2 --json " + flag);
    EXPECT_EQ(r.exit_code, 2) << flag;
    EXPECT_TRUE(invalid_input_json(r.out)) << flag << ": " << r.out;
  }
}

TEST_F(CliPilePhysics, TimeStepAndGravityReachTheSimulation) {
  const CliRun r = run_cli("pile --bodies 5 --steps 3 --dt 0.005 --gravity 20");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(report_value(r.out, "time step"), "0.005 s") << r.out;
  EXPECT_EQ(report_value(r.out, "gravity"), "(0, -20) m/s²") << r.out;

  // A scene's gravity keeps its direction; --dt overrides the file's "dt".
  const std::string scene = temp_path("tilted_gravity_scene.json");
  std::ofstream(scene) << R"({"dt": 0.01, "steps": 2, "gravity": [3, -4], "bodies": [{"vertices": )"
                       << R"([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]], "density": 1, "position": [0, 1]}],)"
                       << R"( "half_planes": [{"normal": [0, 1]}]})";
  const CliRun s = run_cli("pile --scene '" + scene + "' --gravity 10 --dt 0.02");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_EQ(report_value(s.out, "gravity"), "(6, -8) m/s²") << s.out;
  EXPECT_EQ(report_value(s.out, "time step"), "0.02 s") << s.out;
  fs::remove(scene);
}

TEST_F(CliPilePhysics, WithoutGravityThePileDoesNotSettle) {
  const auto contacts = [](const std::string& extra) {
    const CliRun r = run_cli("pile --bodies 20 --steps 60 --json" + extra);
    EXPECT_EQ(r.exit_code, 0) << extra << ": " << r.err;
    return Json::parse(r.out)["contacts_max"].get<int>();
  };
  const int falling = contacts("");
  EXPECT_GT(falling, 0);
  EXPECT_LT(contacts(" --gravity 0"), falling);
  EXPECT_EQ(contacts(" --gravity 9.81"), falling);  // the default, given explicitly
}

TEST_F(CliPilePhysics, QpToleranceReachesTheConvexModel) {
  const auto residual = [](const std::string& extra) {
    const CliRun r = run_cli("pile --bodies 20 --steps 60 --model convex --json" + extra);
    EXPECT_EQ(r.exit_code, 0) << extra << ": " << r.err;
    return Json::parse(r.out)["max_residual"].get<double>();
  };
  EXPECT_NE(residual(" --qp-eps 1e-3"), residual(""));
  EXPECT_EQ(residual(" --qp-eps 1e-8"), residual(""));  // the default, given explicitly
}

TEST_F(CliPilePhysics, ReleaseOpenContactsReachesTheConvexModel) {
  const auto run = [](const std::string& extra) {
    const CliRun r = run_cli("pile --bodies 20 --steps 60 --model convex --json" + extra);
    EXPECT_EQ(r.exit_code, 0) << extra << ": " << r.err;
    const Json j = Json::parse(r.out);
    return std::make_pair(j["max_residual"].get<double>(), j["max_energy_gain"].get<double>());
  };
  EXPECT_NE(run(" --release-open-contacts"), run(""));
}

TEST_F(CliPilePhysics, ProjectionPassesReachTheSimulator) {
  const auto penetration = [](const std::string& extra) {
    const CliRun r = run_cli("pile --bodies 30 --steps 150 --json" + extra);
    EXPECT_EQ(r.exit_code, 0) << extra << ": " << r.err;
    return Json::parse(r.out)["max_penetration"].get<double>();
  };
  const double five = penetration("");
  EXPECT_EQ(penetration(" --post-stabilization-passes 5"), five);  // the default, given explicitly
  EXPECT_LT(five, 0.5 * penetration(" --post-stabilization-passes 1"));
}

}  // namespace
}  // namespace lcprelax
