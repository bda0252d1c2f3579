// `lcprelax learn block --param` (docs/cli.md, learn/block_param.hpp): each nonphysical
// parameterization trains (a few small Adam steps; larger L-BFGS steps on the elementwise
// one reach M whose relaxed QP is infeasible: exit 1) and reports its learned values per
// group (learned_groups), with
// the truth in that parameterization's terms; --epochs 0 reports the gradient per
// parameter; a bad --param value, --param with --method convex, --learn-mass or
// --landscape: exit 2, the invalid_input object on stdout and a message naming --param on
// stderr.
#include "cli_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <map>

namespace lcprelax {
namespace {

using namespace testing_support;

TEST(CliLearnParam, EachParameterizationReportsItsGroups) {
  const std::map<std::string, std::vector<std::string>> groups = {
      {"pair", {"friction", "compliance", "offset"}}, {"residual", {"friction", "residual"}}, {"elementwise", {"M", "q"}}};
  for (const auto& [param, names] : groups) {
    const CliRun r = run_cli("learn block --param " + param +
                             " --init-mu 0.2 --true-mu 0.1 --samples 40 --optimizer adam --lr 0.01 --epochs 10 --json");
    ASSERT_EQ(r.exit_code, 0) << param << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["param"], param);
    for (const std::string& g : names) EXPECT_TRUE(j["learned_groups"].contains(g)) << param << " " << g;
    EXPECT_EQ(j["learned"].size(), j["true"].size()) << param;
    EXPECT_EQ(j["failed"], 0) << param;
    EXPECT_NE(j["learned"], j["initial"]) << param;
  }
  // pair: the two directions' friction move from 0.2 towards the truth 0.1
  const CliRun r = run_cli("learn block --param pair --init-mu 0.2 --true-mu 0.1 --samples 60 --optimizer lbfgs --lr 1 --epochs 100 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["true"]["mu_pos"], 0.1);
  for (const char* name : {"mu_pos", "mu_neg"}) EXPECT_NEAR(j["learned_groups"]["friction"][name].get<double>(), 0.1, 0.02) << name;
}

TEST(CliLearnParam, EpochsZeroReportsTheGradientPerParameter) {
  const CliRun r = run_cli("learn block --param residual --method hard --init-mu 0.3 --true-mu 0.1 --samples 40 --epochs 0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* name : {"mu", "residual.v", "residual.u", "residual.1"}) EXPECT_TRUE(j["gradient"][name].is_number()) << name;
  EXPECT_GT(j["gradient"]["mu"].get<double>(), 0.0);  // μ above the truth: the loss grows with μ
}

TEST(CliLearnParam, BadParamExitsTwoWithAClearMessage) {
  for (const std::string& args : std::vector<std::string>{"--param elementwize", "--param ''", "--param pair --method convex",
                                                          "--param residual --learn-mass", "--param elementwise --landscape /tmp/x"}) {
    const CliRun r = run_cli("learn block " + args + " --epochs 0 --samples 10 --json");
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.out;
    EXPECT_TRUE(invalid_input_json(r.out)) << args;
    EXPECT_NE(r.err.find("--param"), std::string::npos) << args << ": " << r.err;
  }
  const CliRun r = run_cli("learn block --param elementwize --epochs 0");
  EXPECT_NE(r.err.find("physical, pair, elementwise or residual"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace lcprelax
