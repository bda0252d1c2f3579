// `lcprelax --help` and every subcommand's --help are written for a user (issue "A Python
// package ... and a README written for users", "What a newcomer could not find"):
// - each lists the exit codes 0, 1 and 2 with their meaning (they were only in docs/cli.md);
// - none names an internal symbol (`QpSettings::dense_max_kkt`, "the seeds' 1-D block",
//   "Wnn_ii lambda_i^2", "OpenMP threads (0: default)");
// - `learn block --a1` ... `--a5` say which term of the relaxed loss each weighs (they read
//   "relaxed weight a1");
// - every --threads defaults to 0 and says that 0 means all cores.
#include "cli_support.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

using namespace testing_support;

const std::vector<std::string> kCommands = {"",      "qp",          "lcp",           "fc2d",       "pile",
                                            "learn", "learn block", "learn polygon", "learn scene"};

// The help line (with its continuation lines) of `option` in `help`, or "".
std::string option_help(const std::string& help, const std::string& option) {
  std::istringstream in(help);
  std::string line, found;
  bool inside = false;
  while (std::getline(in, line)) {
    const std::size_t first = line.find_first_not_of(' ');
    const bool starts_option = first != std::string::npos && line.compare(first, 2, "--") == 0;
    if (starts_option) inside = line.compare(first, option.size() + 1, option + " ") == 0;
    if (inside) found += line + "\n";
  }
  return found;
}

class CliHelp : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (kCli.empty() || !fs::exists(kCli)) GTEST_FAIL() << "lcprelax executable not built";
  }
};

TEST_P(CliHelp, ListsTheExitCodes) {
  const CliRun r = run_cli(GetParam() + " --help");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Exit codes:"), std::string::npos) << r.out;
  for (const char* code : {"\n  0  ", "\n  1  ", "\n  2  bad input"})
    EXPECT_NE(r.out.find(code), std::string::npos) << "'" << code << "' in:\n" << r.out;
}

TEST_P(CliHelp, NamesNoInternalSymbol) {
  const CliRun r = run_cli(GetParam() + " --help");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* internal : {"::", "seeds'", "Settings", "Wnn", "phase 1's", "(0: default)", ".hpp", "z'w", "v*"})
    EXPECT_EQ(r.out.find(internal), std::string::npos) << "'" << internal << "' in:\n" << r.out;
}

INSTANTIATE_TEST_SUITE_P(EveryCommand, CliHelp, ::testing::ValuesIn(kCommands),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           std::string name = p.param.empty() ? "top_level" : p.param;
                           for (char& c : name)
                             if (c == ' ') c = '_';
                           return name;
                         });

TEST(CliHelpText, RelaxedWeightsSayWhatTheyWeigh) {
  const CliRun r = run_cli("learn block --help");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::pair<std::string, std::string>> terms = {{"--a1", "prediction error"},
                                                                  {"--a2", "complementarity"},
                                                                  {"--a3", "--soft-nonnegativity"},
                                                                  {"--a4", "--soft-lambdas"},
                                                                  {"--a5", "maximum-dissipation"}};
  for (const auto& [option, term] : terms) {
    const std::string help = option_help(r.out, option);
    ASSERT_FALSE(help.empty()) << option << " missing from:\n" << r.out;
    EXPECT_NE(help.find(term), std::string::npos) << option << ": " << help;
    EXPECT_NE(help.find("weight"), std::string::npos) << option << ": " << help;
  }
}

TEST(CliHelpText, EveryThreadsOptionDefaultsToAllCores) {
  for (const std::string command : {"pile", "learn block", "learn polygon", "learn scene"}) {
    const CliRun r = run_cli(command + " --help");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string help = option_help(r.out, "--threads");
    EXPECT_NE(help.find("--threads INT=0"), std::string::npos) << command << ": " << help;
    EXPECT_NE(help.find("0: all cores"), std::string::npos) << command << ": " << help;
  }
}

TEST(CliHelpText, PileHelpStatesTheNewPhysicsOptionsWithUnits) {
  const CliRun r = run_cli("pile --help");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(option_help(r.out, "--dt").find("seconds"), std::string::npos) << r.out;
  EXPECT_NE(option_help(r.out, "--gravity").find("m/s²"), std::string::npos) << r.out;
  EXPECT_FALSE(option_help(r.out, "--qp-eps").empty()) << r.out;
  EXPECT_FALSE(option_help(r.out, "--lemke-tol").empty()) << r.out;
}

}  // namespace
}  // namespace lcprelax
