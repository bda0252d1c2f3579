// `lcprelax lcp` and `lcprelax fc2d` end to end (docs/cli.md): JSON fields, Siconos errors,
// solution files, and exit codes 0 (solved), 1 (ray termination), 2 (bad input).
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lcprelax {
namespace {

using namespace testing_support;
using Json = nlohmann::json;


class CliLcp : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kCli.empty() || !fs::exists(kCli)) GTEST_FAIL() << "lcprelax executable not built";
  }
};

TEST_F(CliLcp, SolvesASiconosLcpWithLemke) {
  const std::string out = temp_path("lcp_solution.json");
  const CliRun r = run_cli("lcp '" + kData + "/siconos/lcp/lcp_mmc.dat' --json --solution '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["status"], "solved");
  EXPECT_EQ(j["n"], 26);
  EXPECT_LE(j["error"].get<double>(), 1e-10);
  EXPECT_GT(j["pivots"].get<long>(), 0);
  EXPECT_TRUE(j.contains("seconds"));
  const Json s = Json::parse(slurp(out));
  EXPECT_EQ(s["z"].size(), 26u);
  EXPECT_EQ(s["w"].size(), 26u);
  fs::remove(out);
}

TEST_F(CliLcp, InteriorPointOnAMonotoneLcp) {
  const CliRun r = run_cli("lcp '" + kData + "/siconos/lcp/lcp_deudeu.dat' --solver ipm --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["status"], "solved");
  EXPECT_LE(j["error"].get<double>(), 1e-10);
  EXPECT_TRUE(j.contains("iterations"));
}

TEST_F(CliLcp, RayTerminationExitsWithOne) {
  const CliRun r = run_cli("lcp '" + kData + "/siconos/lcp/lcp_CPS_3.dat' --json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(Json::parse(r.out)["status"], "ray_termination");
}

TEST_F(CliLcp, SolvesAnFc2dProblem) {
  const std::string out = temp_path("fc2d_solution.json");
  const CliRun r = run_cli("fc2d '" + kData + "/siconos/fc2d/FrictionContactProblem00071.dat' --json --solution '" +
                           out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["status"], "solved");
  EXPECT_EQ(j["contacts"], 89);
  EXPECT_LE(j["error"].get<double>(), 1e-10);
  const Json s = Json::parse(slurp(out));
  EXPECT_EQ(s["r"].size(), 178u);
  EXPECT_EQ(s["u"].size(), 178u);
  fs::remove(out);
}

TEST_F(CliLcp, BadInputExitsWithTwo) {
  for (const std::string& args : std::vector<std::string>
       {"lcp '" + kData + "/siconos/malformed/lcp_truncated.dat' --json",
        "lcp '" + kData + "/siconos/malformed/lcp_nan_entry.dat' --json", std::string("lcp /nonexistent/file.dat --json"),
        "fc2d '" + kData + "/siconos/malformed/fc2d_dim3.dat' --json",
        "lcp '" + kData + "/siconos/lcp/lcp_mmc.dat' --solver foo"}) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    if (args.find("--json") != std::string::npos) {
      EXPECT_TRUE(invalid_input_json(r.out)) << args << ": " << r.out;
    } else {
      EXPECT_TRUE(r.out.empty()) << args;
    }
    EXPECT_FALSE(r.err.empty()) << args;
  }
}

}  // namespace
}  // namespace lcprelax
