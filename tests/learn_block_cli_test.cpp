// `lcprelax learn block` (docs/cli.md): the JSON contract (method, true, initial, learned,
// final_loss, epochs, seconds), --epochs 0 with the gradient (exactly 0 for the hard loss at
// 10× the truth, positive for the relaxed one), a short training run that moves μ towards
// the truth, --data with a CSV file, --landscape writing the CSV (and plots with Cairo), and
// bad input: exit 2, only the invalid_input object on stdout, a message on stderr.
#include "cli_support.hpp"

#include <lcprelax/scenes/line_plot.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace lcprelax {
namespace {

using namespace testing_support;

TEST(CliLearnBlock, EpochsZeroReportsTheGradient) {
  for (const std::string method : {"hard", "relaxed", "convex"}) {
    const CliRun r = run_cli("learn block --method " + method + " --init-mu 1 --true-mu 0.1 --epochs 0 --samples 40 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"method", "true", "initial", "learned", "final_loss", "epochs", "seconds", "gradient"})
      EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["method"], method);
    EXPECT_EQ(j["true"]["mu"], 0.1);
    EXPECT_EQ(j["initial"]["mu"], 1.0);
    EXPECT_EQ(j["learned"]["mu"], 1.0);
    EXPECT_GT(j["final_loss"].get<double>(), 0.0);
    if (method == "hard") {
      EXPECT_EQ(j["gradient"].get<double>(), 0.0);
    } else if (method == "relaxed") {
      EXPECT_GT(j["gradient"].get<double>(), 0.0);
    }
  }
}

TEST(CliLearnBlock, TrainingMovesMuTowardsTheTruth) {
  const CliRun r = run_cli("learn block --init-mu 1 --true-mu 0.1 --epochs 60 --samples 30 --lr 0.2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j.contains("gradient"));
  EXPECT_LT(std::abs(j["learned"]["mu"].get<double>() - 0.1), 0.02);
}

TEST(CliLearnBlock, DataFileAndLandscape) {
  const std::string out = temp_path("landscape");
  const CliRun r = run_cli("learn block --data '" + kData + "/block/good.csv' --epochs 0 --json --landscape '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["true"]["mu"].is_null());
  EXPECT_EQ(j["samples"], 3);
  const std::string csv = slurp(out + ".csv");
  EXPECT_EQ(csv.rfind("mu,hard_loss,hard_gradient,relaxed_loss", 0), 0u) << csv.substr(0, 80);
  if (line_plot_available()) {
    EXPECT_TRUE(fs::exists(out + ".png"));
  } else {
    EXPECT_NE(r.err.find("no picture"), std::string::npos);
  }
  for (const std::string& f : {out + ".csv", out + ".png", out + "_gradient.png"}) fs::remove(f);
}

TEST(CliLearnBlock, BadInputExitsTwo) {
  for (const std::string& args : std::vector<std::string>{"--method foo", "--init-mu -1", "--epochs -2", "--samples 0", "--noise nan", "--max-dissipation sideways",
        "--a3 -5", "--optimizer newton", "--data /nonexistent.csv", "--data '" + kData + "/block/nan.csv'"}) {
    const CliRun r = run_cli("learn block " + args + " --epochs 0 --json");
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.out;
    EXPECT_TRUE(invalid_input_json(r.out)) << args;
    EXPECT_FALSE(r.err.empty()) << args;
  }
}

}  // namespace
}  // namespace lcprelax
