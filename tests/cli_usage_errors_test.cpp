// Usage errors of the command line are clear and early (issue 19), end to end:
// - an unknown subcommand is named with the valid ones (not "A subcommand is required");
// - with --json, bad input still prints one object: {"status": "invalid_input", "message"};
// - --threads above 1024 and `learn block --samples` above 10⁷ are exit 2 stating the limit
//   (100,000 threads segfaulted, 10⁸ samples reached 5 GB and bad_alloc);
// - unwritable --picture, --frames, --plot, --solution and --log paths are exit 2 naming the
//   path before any work (--plot failed only after the whole training, "internal error").
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

using namespace testing_support;
using Json = nlohmann::json;

class CliUsageErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kCli.empty() || !fs::exists(kCli)) GTEST_FAIL() << "lcprelax executable not built";
  }
};

TEST_F(CliUsageErrors, UnknownSubcommandIsNamedWithTheValidOnes) {
  CliRun r = run_cli("frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown subcommand 'frobnicate'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("qp, lcp, fc2d, pile, learn"), std::string::npos) << r.err;
  r = run_cli("learn frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown subcommand 'frobnicate'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("block"), std::string::npos) << r.err;
}

TEST_F(CliUsageErrors, JsonBadInputIsOneObjectWithAMessage) {
  for (const std::string& args : std::vector<std::string>{"lcp /nonexistent/file.dat --json", "frobnicate --json",
                                                         "lcp '" + kData + "/siconos/lcp/lcp_mmc.dat' --solver foo --json"}) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    const Json j = Json::parse(r.out);
    EXPECT_EQ(j["status"], "invalid_input") << args;
    EXPECT_FALSE(j["message"].get<std::string>().empty()) << args;
    EXPECT_FALSE(r.err.empty()) << args;
  }
}

TEST_F(CliUsageErrors, ThreadAndSampleCapsAreStated) {
  for (const std::string args : {"learn block --threads 100000", "learn polygon --threads 100000",
                                 "learn scene --threads 100000", "pile --threads 100000"}) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find("1024"), std::string::npos) << args << ": " << r.err;
  }
  const CliRun r = run_cli("learn block --samples 100000000");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("10000000"), std::string::npos) << r.err;
}

TEST_F(CliUsageErrors, UnwritableOutputPathsFailBeforeTheWork) {
  const std::string bad = "/nonexistent-dir-lcprelax/out";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"pile --bodies 5 --steps 100000 --picture " + bad + ".png", "--picture"},
      {"pile --bodies 5 --steps 100000 --frames /proc/lcprelax-frames", "--frames"},
      {"learn polygon --epochs 300 --plot " + bad + ".png", "--plot"},
      {"learn scene --epochs 300 --plot " + bad + ".png", "--plot"},
      {"learn block --epochs 1000 --log " + bad + ".csv", "--log"},
      {"qp '" + kData + "/maros_meszaros/QAFIRO.qps' --solution " + bad + ".json", "--solution"},
  };
  for (const auto& [args, option] : cases) {
    const auto t0 = std::chrono::steady_clock::now();
    const CliRun r = run_cli(args);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(option + ": cannot write"), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << args;
    EXPECT_LT(s, 5.0) << args << ": the check must come before the work";
  }
}

}  // namespace
}  // namespace lcprelax
