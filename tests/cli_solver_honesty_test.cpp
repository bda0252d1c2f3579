// The command line never reports a wrong answer as right (issue 19), end to end:
// - `qp` with an indefinite P (P = [1 3; 3 1] on the box [−1, 1]²) is bad input (exit 2)
//   naming P and nonconvexity, not `solved` at the saddle x = 0;
// - `lcp` whose solution overflows (q = (1e308, −1e308), M = [1 1; 1 1]: w₁ = ∞) is not
//   `solved` (exit 1, status numerical_error with a message), and --solution is not written;
// - `lcp --solver ipm` on a non-monotone M is bad input (exit 2) in the LCP's terms (M, not P);
// - `fc2d` that fails (W = 0, q_n = −1: infeasible) writes no --solution (it wrote r = [4e7, 0])
//   and says so on stderr; its JSON has a "message".
#include "cli_support.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace lcprelax {
namespace {

using namespace testing_support;
using Json = nlohmann::json;

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

class CliSolverHonesty : public ::testing::Test {
 protected:
  void SetUp() override {
    if (kCli.empty() || !fs::exists(kCli)) GTEST_FAIL() << "lcprelax executable not built";
  }
};

TEST_F(CliSolverHonesty, IndefiniteQpIsBadInputNamingP) {
  const std::string qps = write_file("indefinite.qps",
                                     "NAME INDEF\nROWS\n N obj\nCOLUMNS\n x1 obj 0.0\n x2 obj 0.0\nRHS\nBOUNDS\n"
                                     " LO bnd x1 -1\n UP bnd x1 1\n LO bnd x2 -1\n UP bnd x2 1\nQUADOBJ\n"
                                     " x1 x1 1.0\n x1 x2 3.0\n x2 x2 1.0\nENDATA\n");
  const CliRun r = run_cli("qp '" + qps + "' --json");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.err.find("P is not positive semidefinite"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("nonconvex"), std::string::npos) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["status"], "invalid_input");
  EXPECT_NE(j["message"].get<std::string>().find("nonconvex"), std::string::npos);
  fs::remove(qps);
}

TEST_F(CliSolverHonesty, OverflowingLcpIsNotSolvedAndWritesNoSolution) {
  const std::string dat = write_file("overflow.dat", "2\n0\n2\n2\n2\t2\n1 1\n1 1\n1e308 -1e308\n");
  const std::string out = temp_path("overflow_solution.json");
  fs::remove(out);
  const CliRun r = run_cli("lcp '" + dat + "' --json --solution '" + out + "'");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["status"], "numerical_error");
  EXPECT_TRUE(j["error"].is_null());
  EXPECT_NE(j["message"].get<std::string>().find("non-finite"), std::string::npos) << j.dump();
  EXPECT_FALSE(fs::exists(out));
  EXPECT_NE(r.err.find("not written"), std::string::npos) << r.err;
  fs::remove(dat);
}

TEST_F(CliSolverHonesty, NonMonotoneLcpWithTheInteriorPointIsBadInputInLcpTerms) {
  const std::string dat = write_file("nonmonotone.dat", "2\n0\n2\n2\n2\t2\n1 3\n3 1\n-1 -1\n");
  const CliRun r = run_cli("lcp '" + dat + "' --solver ipm --json");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("M is not monotone"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("P "), std::string::npos) << r.err;  // the user gave no P
  EXPECT_EQ(r.err.find("QP"), std::string::npos) << r.err;
  EXPECT_EQ(Json::parse(r.out)["status"], "invalid_input");
  // Lemke solves it.
  EXPECT_EQ(run_cli("lcp '" + dat + "' --json").exit_code, 0);
  fs::remove(dat);
}

TEST_F(CliSolverHonesty, FailedFc2dWritesNoSolutionAndSaysSo) {
  const std::string dat = write_file("infeasible_fc2d.dat", "2\n1\n0\n2\n2\n2\t2\n0 0\n0 0\n-1 0\n0.5\n");
  const std::string out = temp_path("fc2d_failed_solution.json");
  fs::remove(out);
  const CliRun r = run_cli("fc2d '" + dat + "' --json --solution '" + out + "'");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_NE(j["status"], "solved");
  EXPECT_FALSE(j["message"].get<std::string>().empty());
  EXPECT_FALSE(fs::exists(out)) << slurp(out);
  EXPECT_NE(r.err.find("not written"), std::string::npos) << r.err;
  fs::remove(dat);
}

TEST_F(CliSolverHonesty, DenseBackendOnALargeProblemIsBadInputWithTheLimit) {
  const CliRun r = run_cli("qp '" + kData + "/maros_meszaros/AUG2D.qps' --kkt-backend dense --json");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("at most 4096"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace lcprelax
