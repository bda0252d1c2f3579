// `lcprelax learn block` ends a run when it has converged (learn::train, trainer.hpp):
// - the default relaxed run from 10× the truth, `learn block --method relaxed --init-mu 1
//   --json`, ends within 1e-3 of μ = 0.1 with converged true, before the default cap of
//   1000 epochs, and the JSON carries epochs (run), stop_reason and converged;
// - --patience 0 runs exactly --epochs and reports the cap; --rel-loss-tol, --grad-tol and
//   --patience reject bad values with exit 2.
#include "cli_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace lcprelax {
namespace {

using namespace testing_support;

TEST(CliLearnBlockConvergence, DefaultRelaxedRunConvergesToTheTruth) {
  const CliRun r = run_cli("learn block --method relaxed --init-mu 1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["converged"].get<bool>()) << r.out;
  EXPECT_EQ(j["stop_reason"].get<std::string>().rfind("converged", 0), 0u) << r.out;
  EXPECT_LT(j["epochs"].get<int>(), 1000);
  EXPECT_GT(j["epochs"].get<int>(), 100);
  EXPECT_NEAR(j["learned"]["mu"].get<double>(), 0.1, 1e-3) << r.out;
  std::printf("%s\n", r.out.c_str());
}

TEST(CliLearnBlockConvergence, PatienceZeroRunsTheCap) {
  const CliRun r = run_cli("learn block --init-mu 1 --epochs 7 --patience 0 --samples 30 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["epochs"], 7);
  EXPECT_FALSE(j["converged"].get<bool>());
  EXPECT_EQ(j["stop_reason"], "epoch cap reached (7 epochs, convergence test off)");
}

TEST(CliLearnBlockConvergence, BadTolerancesExitTwo) {
  for (const std::string args : {"--rel-loss-tol -1", "--grad-tol nan", "--patience -3"}) {
    const CliRun r = run_cli("learn block " + args + " --epochs 1 --samples 10 --json");
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.out;
    EXPECT_TRUE(invalid_input_json(r.out)) << args;
    EXPECT_FALSE(r.err.empty()) << args;
  }
}

}  // namespace
}  // namespace lcprelax
