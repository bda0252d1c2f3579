// `--threads` has one default in every command: 0, all cores (`learn block` had 1 while
// `learn polygon` and `learn scene` had 0). That is safe because the learned parameters do
// not depend on the thread count: the batch sums are reduced in a fixed sample order
// (learn/batch.hpp). Expected: `learn block` (hard and relaxed, the losses with per-thread
// workspaces and per-sample warm starts) and `learn polygon` give byte-identical
// "learned" and "final_loss" with the default, --threads 1 and --threads 2; the default
// is recorded as 0 (the checkpoint's identity ignores --threads, so old runs still resume).
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <string>

namespace lcprelax {
namespace {

using namespace testing_support;
using Json = nlohmann::json;

class CliThreadsDefault : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kCli.empty() || !fs::exists(kCli)) GTEST_FAIL() << "lcprelax executable not built";
  }
};

// "learned" and "final_loss" of a run, as printed (the JSON text, compared byte for byte).
std::string result_of(const std::string& args) {
  const CliRun r = run_cli(args + " --json");
  EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
  const Json j = Json::parse(r.out, nullptr, false);
  if (!j.is_object()) return "not JSON: " + r.out;
  return j["learned"].dump() + " " + j["final_loss"].dump();
}

TEST_F(CliThreadsDefault, LearnBlockGivesTheSameBitsForEveryThreadCount) {
  for (const std::string method : {"hard", "relaxed"}) {
    const std::string args = "learn block --method " + method + " --init-mu 0.5 --samples 60 --epochs 20 --patience 0";
    const std::string by_default = result_of(args);
    EXPECT_EQ(result_of(args + " --threads 1"), by_default) << method;
    EXPECT_EQ(result_of(args + " --threads 2"), by_default) << method;
  }
}

TEST_F(CliThreadsDefault, LearnPolygonGivesTheSameBitsForEveryThreadCount) {
  const std::string args = "learn polygon --samples 30 --epochs 2 --patience 0";
  const std::string by_default = result_of(args);
  EXPECT_EQ(result_of(args + " --threads 1"), by_default);
  EXPECT_EQ(result_of(args + " --threads 2"), by_default);
}

TEST_F(CliThreadsDefault, EveryCommandDefaultsToZero) {
  for (const std::string command : {"pile", "learn block", "learn polygon", "learn scene"}) {
    const CliRun r = run_cli(command + " --help");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("--threads INT=0 "), std::string::npos) << command << ":\n" << r.out;
  }
}

}  // namespace
}  // namespace lcprelax
