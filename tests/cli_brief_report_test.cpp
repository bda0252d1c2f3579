// One human output style for every subcommand (docs/cli.md, "Human output"): a brief report
// of aligned `name  value unit` lines, `status` first (qp printed a table while lcp, fc2d
// and pile printed `key: "json"` lines and the learn commands one long sentence). And the
// --json output is unchanged by it: the same keys in the same order (scripts parse it).
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

using namespace testing_support;
using Json = nlohmann::ordered_json;

const std::string kLcp = "lcp '" + kData + "/siconos/lcp/lcp_mmc.dat'";
const std::string kFc2d = "fc2d '" + kData + "/siconos/fc2d/FrictionContactProblem00071.dat'";
const std::string kQp = "qp '" + kData + "/maros_meszaros/HS21.qps'";
const std::string kPile = "pile --bodies 10 --steps 20";
const std::string kBlock = "learn block --samples 20 --epochs 3";
const std::string kPolygon = "learn polygon --samples 20 --epochs 1";
const std::string kScene = "learn scene --scene '" + kData + "/scenes/box_stack.json' --steps 10 --learn mu --epochs 1";

class CliBriefReport : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (kCli.empty() || !fs::exists(kCli)) GTEST_FAIL() << "lcprelax executable not built";
  }
};

// Column (in code points) where the value of each report line starts.
std::vector<std::size_t> value_columns(const std::string& out) {
  std::vector<std::size_t> columns;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    const std::size_t gap = line.find("  ");
    const std::size_t value = gap == std::string::npos ? gap : line.find_first_not_of(' ', gap);
    std::size_t n = 0;
    for (std::size_t i = 0; i < value && i < line.size(); ++i)
      if ((static_cast<unsigned char>(line[i]) & 0xC0) != 0x80) ++n;
    columns.push_back(value == std::string::npos ? std::string::npos : n);
  }
  return columns;
}

TEST_P(CliBriefReport, AlignedLinesStatusFirst) {
  const CliRun r = run_cli(GetParam());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = report_lines(r.out);
  ASSERT_GE(lines.size(), 4u) << "not a brief report:\n" << r.out;
  EXPECT_EQ(lines.front().first, "status") << r.out;
  const std::vector<std::size_t> columns = value_columns(r.out);
  for (std::size_t c : columns) EXPECT_EQ(c, columns.front()) << "values not aligned:\n" << r.out;
  EXPECT_EQ(r.out.find(": \""), std::string::npos) << "JSON-like line:\n" << r.out;
  EXPECT_NE(report_value(r.out, "time").find(" s"), std::string::npos) << r.out;
}

INSTANTIATE_TEST_SUITE_P(EveryCommand, CliBriefReport,
                         ::testing::Values(kQp, kLcp, kFc2d, kPile, kBlock, kPolygon, kScene));

TEST(CliBriefReportValues, StatusAndNumbersWithUnits) {
  CliRun r = run_cli(kQp);
  EXPECT_EQ(report_value(r.out, "status"), "solved") << r.out;
  EXPECT_EQ(report_value(r.out, "problem"), "HS21") << r.out;
  EXPECT_EQ(report_value(r.out, "objective"), "-99.96") << r.out;
  r = run_cli(kLcp);
  EXPECT_EQ(report_value(r.out, "status"), "solved") << r.out;
  EXPECT_EQ(report_value(r.out, "size"), "26 unknowns") << r.out;
  r = run_cli("lcp '" + kData + "/siconos/lcp/lcp_CPS_3.dat'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(report_value(r.out, "status"), "ray_termination") << r.out;
  EXPECT_EQ(report_value(r.out, "Siconos error"), "n/a") << r.out;
  EXPECT_NE(report_value(r.out, "message"), "(no line message)") << r.out;
  // fc2d from the purified start (the default): FrictionContactProblem00071 needs no pivot
  // after its purification steps (185 measured); with --crash pgs the line has none.
  r = run_cli(kFc2d);
  const std::string start = report_value(r.out, "start");
  EXPECT_EQ(start.rfind("guess (50 Gauss-Seidel sweeps, ", 0), 0u) << r.out;
  EXPECT_NE(start.find(" purification steps, 0 pivots from their basis)"), std::string::npos) << r.out;
  r = run_cli(kFc2d + " --crash pgs");
  EXPECT_EQ(report_value(r.out, "start").find("purification"), std::string::npos) << r.out;
  r = run_cli(kPile);
  EXPECT_EQ(report_value(r.out, "status"), "ok") << r.out;
  EXPECT_EQ(report_value(r.out, "bodies"), "10") << r.out;
  EXPECT_EQ(report_value(r.out, "max penetration").substr(report_value(r.out, "max penetration").size() - 2), " m")
      << r.out;
  r = run_cli("learn block --samples 20 --epochs 0");
  EXPECT_EQ(report_value(r.out, "status"), "evaluated") << r.out;
  EXPECT_NE(report_value(r.out, "mu").find("(initial 1, true 0.1)"), std::string::npos) << r.out;
}

// The keys (and their order) of each --json object, as before the human output changed.
TEST(CliBriefReportValues, JsonKeysAreUnchanged) {
  const auto keys = [](const std::string& args) {
    const CliRun r = run_cli(args + " --json");
    const Json j = Json::parse(r.out);
    std::string list;
    for (auto it = j.begin(); it != j.end(); ++it) list += it.key() + " ";
    return list;
  };
  EXPECT_EQ(keys(kQp), "status objective iterations primal_residual dual_residual duality_gap seconds ");
  EXPECT_EQ(keys(kLcp), "status n error pivots seconds ");
  EXPECT_EQ(keys(kFc2d), "status contacts error seconds pivots crash_sweeps crash_pivots purification_steps start ");
  EXPECT_EQ(keys(kPile),
            "bodies contacts_max steps seconds_per_step max_penetration max_residual max_energy_gain model softening "
            "failed_islands inaccurate_islands seconds ");
  EXPECT_EQ(keys(kBlock),
            "method param true initial learned learned_groups final_loss epochs stop_reason converged seconds "
            "samples failed ");
  EXPECT_EQ(keys(kPolygon),
            "method true initial learned final_loss epochs stop_reason converged seconds samples validation_loss "
            "relative_error failed ");
}

}  // namespace
}  // namespace lcprelax
