// `lcprelax qp` end to end (docs/cli.md): runs the built executable on HS21 and on bad input,
// parses its JSON, and checks exit codes (0 solved, 2 bad input with only the invalid_input object on stdout).
#include "cli_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

namespace {

using namespace lcprelax::testing_support;

const std::string kHs21 = kData + "/maros_meszaros/HS21.qps";

class CliQp : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kCli.empty() || !fs::exists(kCli)) GTEST_FAIL() << "lcprelax executable not built";
  }
};

TEST_F(CliQp, Hs21JsonReport) {
  const CliRun r = run_cli("qp '" + kHs21 + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);  // exactly one JSON object
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.at("status"), "solved");
  const double objective = j.at("objective").get<double>();
  EXPECT_NEAR(objective, -99.96, 1e-6 * 99.96);
  EXPECT_GT(j.at("iterations").get<int>(), 0);
  for (const char* key : {"primal_residual", "dual_residual", "duality_gap"}) {
    ASSERT_TRUE(j.at(key).is_number()) << key;
    EXPECT_LE(std::abs(j.at(key).get<double>()), 1e-6) << key;
  }
  EXPECT_GE(j.at("seconds").get<double>(), 0.0);
  EXPECT_EQ(j.size(), 7u);
}

TEST_F(CliQp, Hs21SolutionFile) {
  const std::string out = temp_path("solution.json");
  const CliRun r = run_cli("qp '" + kHs21 + "' --eps 1e-8 --max-iter 100 --json --solution '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json s = nlohmann::json::parse(slurp(out));
  fs::remove(out);
  ASSERT_EQ(s.at("x").size(), 2u);
  ASSERT_EQ(s.at("y_rows").size(), 1u);
  ASSERT_EQ(s.at("y_bounds").size(), 2u);
  // Optimum x = (2, 0): the lower bound of x0 is active (y_bounds[0] < 0), the row is not.
  EXPECT_NEAR(s["x"][0].get<double>(), 2.0, 1e-6);
  EXPECT_NEAR(s["x"][1].get<double>(), 0.0, 1e-6);
  EXPECT_LT(s["y_bounds"][0].get<double>(), 0.0);
  // Stationarity Px + q + Gᵀy_rows + y_bounds = 0 with P = diag(0.02, 2), G = [10, −1].
  const double x0 = s["x"][0], x1 = s["x"][1], y = s["y_rows"][0];
  EXPECT_NEAR(0.02 * x0 + 10.0 * y + s["y_bounds"][0].get<double>(), 0.0, 1e-6);
  EXPECT_NEAR(2.0 * x1 - 1.0 * y + s["y_bounds"][1].get<double>(), 0.0, 1e-6);
}

TEST_F(CliQp, HumanReadableReport) {
  const CliRun r = run_cli("qp '" + kHs21 + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("solved"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("HS21"), std::string::npos) << r.out;
}

TEST_F(CliQp, MalformedFileIsBadInput) {
  const std::string bad = kData + "/qps/malformed/unknown_row.qps";
  const CliRun r = run_cli("qp '" + bad + "' --json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(invalid_input_json(r.out)) << r.out;
  EXPECT_NE(r.err.find(bad + ":8:"), std::string::npos) << r.err;
}

TEST_F(CliQp, MissingFileIsBadInput) {
  const CliRun r = run_cli("qp '" + kData + "/qps/no_such_file.qps' --json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(invalid_input_json(r.out)) << r.out;
  EXPECT_NE(r.err.find("cannot open"), std::string::npos) << r.err;
}

TEST_F(CliQp, BadOptionsAreBadInput) {
  for (const std::string options : {"--eps -1", "--eps abc", "--eps nan", "--max-iter 0", "--max-iter 2.5", "--bogus"}) {
    const CliRun r = run_cli("qp '" + kHs21 + "' --json " + options);
    EXPECT_EQ(r.exit_code, 2) << options;
    EXPECT_TRUE(invalid_input_json(r.out)) << options;
    EXPECT_FALSE(r.err.empty()) << options;
  }
  EXPECT_EQ(run_cli("").exit_code, 2);  // no subcommand
}

TEST_F(CliQp, IterationLimitIsSolveFailure) {
  const CliRun r = run_cli("qp '" + kData + "/maros_meszaros/QAFIRO.qps' --max-iter 1 --json");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_NE(j.at("status"), "solved");
  EXPECT_TRUE(j.at("objective").is_number() || j.at("objective").is_null());
}

}  // namespace
