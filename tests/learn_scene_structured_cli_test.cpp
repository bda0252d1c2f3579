// `lcprelax learn scene --learn ...,gap,residual` (docs/cli.md): the structured nonphysical
// kinds on the command line.
// - a scene file whose bodies carry "gap_offset" generates data with it; --learn mu,mass,gap
//   lists "class<c>.gap" in true / initial / learned / relative_error like the other
//   parameters (true = the file's offset; relative error |Δ|/class radius), and a short run
//   exits 0;
// - without gap in --learn no gap parameter appears (the default output is unchanged);
// - the offsets are recovered: data of the convex model with the penalty softening (which
//   pushes back from a negative gap at velocity level) and a 4 mm offset, learned from the
//   default 25% start (8.8 cm off) by LM on the convex loss in 20 steps' data, to 1e-6 class
//   radius (measured 2.6e-12);
// - "velocity_residual" likewise: --learn mu,residual lists the 12 entries per class,
//   true = the file's W, relative error |Δ| (0.1·F from --perturb F);
// - --learn block_tied / block (the lcp model's per-contact LCP correction) lists its 7 / 20
//   entries (true 0) and trains with --method hard;
// - --learn softness lists "compliance" and "erp" (true = the scene file's friction table)
//   and trains with every --method (a scene of the convex model with it simulates);
// - an unknown --learn entry, gap, residual, block or softness for learn polygon, block with a
//   method other than hard, and both block forms at once, exit 2 naming the entry.
#include "cli_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>

namespace lcprelax {
namespace {

using namespace testing_support;

const std::string kStack = std::string(LCPRELAX_TEST_DATA_DIR) + "/scenes/box_stack.json";

// box_stack.json with every body's "gap_offset" set to `offset`, written to a temporary file.
std::string stack_with_offset(double offset, const std::string& model = "lcp") {
  std::ifstream in(kStack);
  nlohmann::json j = nlohmann::json::parse(in);
  for (auto& body : j["bodies"]) body["gap_offset"] = offset;
  j["model"] = model;
  const std::string path = temp_path("stack_gap.json");
  std::ofstream(path) << j.dump();
  return path;
}

TEST(CliLearnSceneStructured, GapIsListedLikeTheOtherParameters) {
  const std::string scene = stack_with_offset(4e-3);
  const std::string common = "learn scene --scene '" + scene + "' --steps 20 --learn mu,mass,gap --json";
  const CliRun r = run_cli(common + " --epochs 0");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["true"].contains("class0.gap")) << j.dump();
  EXPECT_EQ(j["true"]["class0.gap"].get<double>(), 4e-3);
  EXPECT_NE(j["initial"]["class0.gap"].get<double>(), 4e-3) << "--perturb moves the offset";
  EXPECT_EQ(j["learned"].size(), j["relative_error"].size());
  // --perturb 0.25 (default) moves it by 0.25/2 of its class radius: relative error 0.125.
  EXPECT_NEAR(j["relative_error"].value("class0.gap", -1.0), 0.125, 1e-12) << j["relative_error"].dump();

  // The convex loss: with the LCP model (hard, relaxed) a negative effective gap has no
  // velocity-level term (max(φ, 0)/Δt) and, at this initial offset, no gradient.
  const CliRun trained = run_cli(common + " --epochs 2 --method convex");
  ASSERT_EQ(trained.exit_code, 0) << trained.err << trained.out;
  const auto t = nlohmann::json::parse(trained.out);
  EXPECT_TRUE(t["learned"].contains("class0.gap"));
  EXPECT_NE(t["learned"]["class0.gap"], t["initial"]["class0.gap"]) << "training moves the offset";
  EXPECT_EQ(t["failed"], 0);

  const CliRun plain = run_cli("learn scene --scene '" + scene + "' --steps 20 --learn mu,mass --epochs 0 --json");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(plain.out.find(".gap"), std::string::npos) << "gap not learned: not listed";
  std::filesystem::remove(scene);
}

TEST(CliLearnSceneStructured, LevenbergMarquardtRecoversTheOffsets) {
  const std::string scene = stack_with_offset(4e-3, "convex");
  const CliRun r = run_cli("learn scene --scene '" + scene +
                           "' --steps 20 --learn gap --method convex --softening penalty --optimizer lm --epochs 40 "
                           "--threads 1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["relative_error"].size(), 2u) << j.dump();
  for (const auto& [name, error] : j["relative_error"].items()) {
    EXPECT_GT(std::abs(j["initial"][name].get<double>() - 4e-3), 0.05) << name << ": the start is far off";
    EXPECT_LT(error.get<double>(), 1e-6) << name << " learned " << j["learned"][name];
  }
  std::filesystem::remove(scene);
}

TEST(CliLearnSceneStructured, ResidualIsListedLikeTheOtherParameters) {
  std::ifstream in(kStack);
  nlohmann::json j = nlohmann::json::parse(in);
  for (auto& body : j["bodies"]) body["velocity_residual"] = {{-0.01, 0, 0, 0.002}, {0, 0, 0, 0}, {0, 0, -0.02, 0}};
  const std::string scene = temp_path("stack_residual.json");
  std::ofstream(scene) << j.dump();
  const CliRun r = run_cli("learn scene --scene '" + scene + "' --steps 20 --learn mu,residual --epochs 0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const auto out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out["true"]["class0.residual03"].get<double>(), 0.002);
  EXPECT_EQ(out["true"]["class0.residual22"].get<double>(), -0.02);
  EXPECT_EQ(out["true"]["class0.residual11"].get<double>(), 0.0);
  EXPECT_NEAR(out["relative_error"].value("class0.residual03", -1.0), 0.025, 1e-12) << "0.1 * 0.25, absolute";
  EXPECT_EQ(out["learned"].size(), out["relative_error"].size());
  EXPECT_EQ(out["learned"].size() % 12, 1u) << "mu and 12 entries per class";
  std::filesystem::remove(scene);
}

void expect_bad_input(const std::string& args, const std::string& needle) {
  const CliRun r = run_cli(args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err << r.out;
  EXPECT_TRUE(invalid_input_json(r.out)) << r.out;
  EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err << " (expected '" << needle << "')";
}

TEST(CliLearnSceneStructured, UnknownOrMisplacedKindsExitTwo) {
  expect_bad_input("learn scene --learn mu,gaps --json", "'gaps'");
  expect_bad_input("learn scene --learn gap,gap --json", "twice");
  expect_bad_input("learn polygon --learn mu,gap --json", "learn scene");
  expect_bad_input("learn polygon --learn residual --json", "learn scene");
  expect_bad_input("learn scene --learn mu,residuals --json", "'residuals'");
  expect_bad_input("learn scene --learn mu,block --json", "--method hard");
  expect_bad_input("learn scene --learn mu,block_tied --method convex --json", "--method hard");
  expect_bad_input("learn scene --learn block,block_tied --method hard --json", "block_tied");
  expect_bad_input("learn polygon --learn mu,block --json", "learn scene");
  expect_bad_input("learn polygon --learn mu,softness --json", "learn scene");
}

// The lcp model's per-contact LCP block: listed with its entries, learned by the hard loss.
TEST(CliLearnSceneStructured, LcpBlockIsLearnedByTheHardLoss) {
  const std::string common = "learn scene --scene '" + kStack + "' --steps 20 --method hard --json";
  const CliRun tied = run_cli(common + " --learn mu,block_tied --epochs 3");
  ASSERT_EQ(tied.exit_code, 0) << tied.err << tied.out;
  const auto t = nlohmann::json::parse(tied.out);
  for (const char* name : {"lcp_block.Wnn", "lcp_block.Wnt", "lcp_block.Wtn", "lcp_block.Wtt", "lcp_block.mu",
                           "lcp_block.qn", "lcp_block.qt"}) {
    ASSERT_TRUE(t["learned"].contains(name)) << name << " in " << t["learned"].dump();
    EXPECT_EQ(t["true"][name].get<double>(), 0.0) << name;
  }
  EXPECT_EQ(t["learned"].size(), 8u) << "mu and the 7 tied entries";
  const CliRun free_block = run_cli(common + " --learn block --epochs 0");
  ASSERT_EQ(free_block.exit_code, 0) << free_block.err << free_block.out;
  const auto f = nlohmann::json::parse(free_block.out);
  EXPECT_EQ(f["learned"].size(), 20u);
  EXPECT_TRUE(f["learned"].contains("lcp_block.M33"));
  EXPECT_TRUE(f["learned"].contains("lcp_block.q1"));
}

// The friction table's normal softness: listed with the file's values, learned by every loss.
TEST(CliLearnSceneStructured, SoftnessIsLearnedByEveryLoss) {
  std::ifstream in(kStack);
  const nlohmann::json base = nlohmann::json::parse(in);
  for (const std::string method : {"relaxed", "hard", "convex"}) {
    nlohmann::json j = base;
    j["model"] = method == "convex" ? "convex" : "lcp";  // the data's simulator takes the softness too
    j["friction"]["compliance"] = 0.01;
    j["friction"]["erp"] = 0.2;
    const std::string path = temp_path("stack_soft_" + method + ".json");
    std::ofstream(path) << j.dump();
    const CliRun r = run_cli("learn scene --scene '" + path + "' --steps 20 --method " + method +
                             " --learn mu,softness --epochs 3 --json");
    ASSERT_EQ(r.exit_code, 0) << method << ": " << r.err << r.out;
    const auto out = nlohmann::json::parse(r.out);
    EXPECT_EQ(out["learned"].size(), 3u) << out["learned"].dump();
    EXPECT_EQ(out["true"]["compliance"].get<double>(), 0.01);
    EXPECT_EQ(out["true"]["erp"].get<double>(), 0.2);
    EXPECT_TRUE(std::isfinite(out["learned"]["erp"].get<double>()));
  }
}

}  // namespace
}  // namespace lcprelax
