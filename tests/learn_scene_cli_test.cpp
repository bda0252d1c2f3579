// `lcprelax learn scene` (docs/cli.md). Expected behaviour:
// - a short run of every method on a generated 10-body learning pile exits 0 and prints one
//   JSON object with the contract fields (method, true, initial, learned, relative_error,
//   final_loss, epochs, stop_reason, seconds, transitions, failed_islands); the CSV log has a
//   header and one row per epoch; --learn selects the kinds (mu alone: one learned name);
// - --scene FILE.json generates the data from the file's scene;
// - --softening (convex) names its method in the JSON and changes the loss; so does
//   --release-open-contacts;
// - bad input exits 2 with a message on stderr naming the option, file line or field, and
//   only the invalid_input object on stdout: an unknown --learn kind, an unknown method, --data without --scene,
//   a trajectory whose frames have another number of bodies than the scene, a NaN in the
//   trajectory, a step gap.
#include "cli_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace lcprelax {
namespace {

using namespace testing_support;

const std::string kStack = std::string(LCPRELAX_TEST_DATA_DIR) + "/scenes/box_stack.json";

class CliLearnScene : public ::testing::TestWithParam<std::string> {};

TEST_P(CliLearnScene, ShortRunReportsTheContractFields) {
  const std::string log = temp_path("scene_" + GetParam() + ".csv");
  const CliRun r = run_cli("learn scene --bodies 10 --steps 30 --method " + GetParam() +
                           " --epochs 3 --threads 2 --json --log '" + log + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"method", "true", "initial", "learned", "relative_error", "final_loss", "epochs",
                          "stop_reason", "seconds", "transitions", "failed_islands"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["method"], GetParam());
  EXPECT_EQ(j["epochs"], 3);
  EXPECT_DOUBLE_EQ(j["true"]["mu"].get<double>(), 0.5);
  EXPECT_NE(j["initial"]["mu"].get<double>(), 0.5);
  EXPECT_EQ(j["learned"].size(), j["relative_error"].size());
  EXPECT_TRUE(j["learned"].contains("class0.vertex0.x"));
  EXPECT_EQ(j["failed_islands"], 0);
  const std::string csv = slurp(log);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4) << csv;
  std::filesystem::remove(log);
}

INSTANTIATE_TEST_SUITE_P(Methods, CliLearnScene, ::testing::Values("hard", "relaxed", "convex"));

TEST(CliLearnSceneOptions, LearnSelectsKindsAndSceneFilesWork) {
  const CliRun r = run_cli("learn scene --scene '" + kStack + "' --steps 20 --learn mu --epochs 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["learned"].size(), 1u);
  EXPECT_EQ(j["bodies"], 3);
}

void expect_bad_input(const std::string& args, const std::string& needle) ;

TEST(CliLearnSceneOptions, InitFromContinuesAnEarlierRunWithLbfgs) {
  // The "learned" map of one run's JSON is the next run's "initial" map, bit for bit, and a
  // full-batch L-BFGS continuation of it does not raise the training loss. A run that learns
  // a subset holds the others at the file's values; one that learns more is refused.
  const std::string first = temp_path("scene_first.json");
  const CliRun a = run_cli("learn scene --scene '" + kStack + "' --steps 20 --learn mu,mass --epochs 3 --json");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  { std::ofstream(first) << a.out; }
  const CliRun b = run_cli("learn scene --scene '" + kStack + "' --steps 20 --learn mu,mass --epochs 5 --optimizer lbfgs" +
                           " --init-from '" + first + "' --json");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
  EXPECT_EQ(jb["initial"], ja["learned"]);
  EXPECT_LE(jb["final_loss"].get<double>(), ja["final_loss"].get<double>());
  // A subset of the file's parameters: the others are held at the file's values.
  const CliRun c = run_cli("learn scene --scene '" + kStack + "' --steps 20 --learn mu --epochs 0 --init-from '" +
                           first + "' --json");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(nlohmann::json::parse(c.out)["initial"]["mu"], ja["learned"]["mu"]);
  // A parameter learned by this run must be in the file.
  expect_bad_input("learn scene --scene '" + kStack + "' --steps 20 --learn mu,mass,inertia --epochs 1 --init-from '" +
                       first + "' --json",
                   "is missing");
  expect_bad_input("learn scene --scene '" + kStack + "' --init-from /nonexistent.json --json", "--init-from");
  // L-BFGS needs the whole training set per step.
  expect_bad_input("learn scene --scene '" + kStack + "' --steps 20 --optimizer lbfgs --batch 2 --json", "lbfgs");
  std::filesystem::remove(first);
}

// --optimizer lm (Levenberg–Marquardt) on the convex loss's residuals lowers the training
// loss at every epoch (it accepts only steps that do) and lowers it by 40% within 6 epochs; the
// hard and relaxed losses have no residuals (exit 2).
TEST(CliLearnSceneOptions, LevenbergMarquardtOnTheConvexLoss) {
  const std::string log = temp_path("scene_lm.csv");
  const std::string common = "learn scene --bodies 10 --steps 30 --method convex --phase1-deviation 0 "
                             "--phase1-regularization 1e-6 --threads 2 --json";
  const CliRun start = run_cli(common + " --epochs 0");
  const CliRun lm = run_cli(common + " --epochs 6 --optimizer lm --log '" + log + "'");
  ASSERT_EQ(start.exit_code, 0) << start.err;
  ASSERT_EQ(lm.exit_code, 0) << lm.err;
  const auto j0 = nlohmann::json::parse(start.out), j = nlohmann::json::parse(lm.out);
  EXPECT_LT(j["final_loss"].get<double>(), 0.6 * j0["final_loss"].get<double>()) << lm.out;
  std::ifstream in(log);
  std::string line;
  std::getline(in, line);  // header
  double previous = j0["final_loss"].get<double>() * (1.0 + 1e-12);
  int rows = 0;
  while (std::getline(in, line)) {
    const double loss = std::stod(line.substr(line.find(',') + 1));  // the epoch's loss, at its starting θ
    EXPECT_LE(loss, previous) << "epoch " << rows + 1;
    previous = loss;
    ++rows;
  }
  EXPECT_EQ(rows, j["epochs"].get<int>());
  std::filesystem::remove(log);
  expect_bad_input("learn scene --bodies 10 --steps 30 --method relaxed --optimizer lm --json", "least-squares");
  expect_bad_input("learn scene --bodies 10 --steps 30 --method convex --optimizer lm --batch 4 --json", "lm");
}

void expect_bad_input(const std::string& args, const std::string& needle) {
  const CliRun r = run_cli(args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err << r.out;
  EXPECT_TRUE(invalid_input_json(r.out)) << r.out;
  EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr: " << r.err << " (expected '" << needle << "')";
}

std::string write_trajectory(const std::string& name, int bodies, int frames, bool nan_in_frame_1, bool gap) {
  const std::string path = temp_path(name);
  std::ofstream out(path);
  out << "step,time,body,x,y,theta,vx,vy,omega\n";
  for (int f = 0; f < frames; ++f) {
    const int step = gap && f == frames - 1 ? f + 1 : f;
    for (int b = 0; b < bodies; ++b)
      out << step << ',' << 0.01 * step << ',' << b << ',' << 0.0 << ',' << 0.5 + b << ",0,"
          << ((nan_in_frame_1 && f == 1 && b == 1) ? "nan" : "0") << ",0,0\n";
  }
  return path;
}

// --portfolio (learn/portfolio.hpp): three recipes for the convex loss, lm alone (the same
// run as without --portfolio: equal final loss), adam then lm, and lm on the default convex
// loss then on this one; the kept one has the lowest training loss, and the reported
// final_loss is its loss. Refused with adam as the optimizer and with --log.
TEST(CliLearnSceneOptions, PortfolioKeepsTheRecipeWithTheLowestLoss) {
  const std::string common = "learn scene --bodies 6 --steps 16 --method convex --phase1-deviation 0 "
                             "--phase1-regularization 1e-6 --threads 2 --json --optimizer lm --epochs 3";
  const CliRun plain = run_cli(common);
  const CliRun all = run_cli(common + " --portfolio --portfolio-adam-epochs 2 --portfolio-smooth-epochs 2");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const auto jp = nlohmann::json::parse(plain.out), j = nlohmann::json::parse(all.out);
  ASSERT_EQ(j["portfolio"].size(), 3u) << all.out;
  EXPECT_EQ(j["portfolio"][0]["recipe"], "lm");
  EXPECT_EQ(j["portfolio"][1]["recipe"], "adam+lm");
  EXPECT_EQ(j["portfolio"][2]["recipe"], "smooth+lm");
  EXPECT_EQ(j["portfolio"][0]["final_loss"].get<double>(), jp["final_loss"].get<double>());
  std::size_t best = 0;
  for (std::size_t k = 1; k < 3; ++k)
    if (j["portfolio"][k]["final_loss"].get<double>() < j["portfolio"][best]["final_loss"].get<double>()) best = k;
  EXPECT_EQ(j["chosen_recipe"], j["portfolio"][best]["recipe"]);
  EXPECT_EQ(j["final_loss"].get<double>(), j["portfolio"][best]["final_loss"].get<double>());
  EXPECT_EQ(j["epochs"].get<int>(), j["portfolio"][best]["epochs"].get<int>());
  expect_bad_input("learn scene --bodies 10 --steps 30 --method convex --optimizer adam --portfolio --json", "--portfolio");
  expect_bad_input("learn scene --bodies 10 --steps 30 --method convex --optimizer lm --portfolio --log '" +
                       temp_path("portfolio.csv") + "' --json",
                   "--portfolio");
}

// The relaxed and hard losses' portfolios have two recipes, OPT and adam+OPT (no continuation);
// the kept one has the lowest training loss. The reported final_loss is evaluated after the
// portfolio: the hard loss's equals the kept recipe's; the relaxed loss's is one proximal step
// further (its centres advance per evaluation; learn/portfolio.hpp), close to it.
TEST(CliLearnSceneOptions, RelaxedAndHardPortfoliosHaveTwoRecipes) {
  const std::string common = "learn scene --bodies 6 --steps 12 --threads 2 --json --optimizer lbfgs --epochs 2 "
                             "--portfolio --portfolio-adam-epochs 2 --learn mu,mass";
  for (const char* method : {"relaxed", "hard"}) {
    const CliRun r = run_cli(common + " --method " + method);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["portfolio"].size(), 2u) << r.out;
    EXPECT_EQ(j["portfolio"][0]["recipe"], "lbfgs");
    EXPECT_EQ(j["portfolio"][1]["recipe"], "adam+lbfgs");
    const std::size_t best =
        j["portfolio"][1]["final_loss"].get<double>() < j["portfolio"][0]["final_loss"].get<double>() ? 1 : 0;
    EXPECT_EQ(j["chosen_recipe"], j["portfolio"][best]["recipe"]) << method;
    const double reported = j["final_loss"].get<double>(), kept = j["portfolio"][best]["final_loss"].get<double>();
    if (std::string(method) == "hard")
      EXPECT_EQ(reported, kept);
    else
      EXPECT_NEAR(reported, kept, 0.1 * kept);
  }
}

// --softening sets the convex loss's softening and the generated data's: the JSON names it,
// and the loss at the same initial values differs between methods.
TEST(CliLearnSceneOptions, SofteningReachesTheConvexLoss) {
  std::vector<double> loss;
  for (const auto& [flag, name] : std::vector<std::pair<std::string, std::string>>{
           {"exp", "exp_phi"}, {"penalty", "linear_penalty"}, {"impedance", "mujoco_impedance"}}) {
    const CliRun r = run_cli("learn scene --scene '" + kStack + "' --steps 20 --learn mu --method convex --softening " +
                             flag + " --epochs 0 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["softening"], name);
    loss.push_back(j["final_loss"].get<double>());
  }
  EXPECT_NE(loss[0], loss[1]);
  EXPECT_NE(loss[0], loss[2]);
  expect_bad_input("learn scene --scene '" + kStack + "' --method relaxed --softening exp --json", "--softening");
  expect_bad_input("learn scene --scene '" + kStack + "' --method convex --softening soft --json", "--softening");
}

// --release-open-contacts sets the convex loss's release and the generated data's: the JSON
// says so, and the loss at the same initial values differs from the held model's (a pile
// whose open contacts are released moves differently, and so does the loss's model).
TEST(CliLearnSceneOptions, ReleaseOfOpenContactsReachesTheConvexLoss) {
  std::vector<double> loss;
  for (const bool release : {false, true}) {
    const CliRun r = run_cli(std::string("learn scene --bodies 10 --steps 30 --learn mu --method convex --epochs 0 ") +
                             (release ? "--release-open-contacts " : "") + "--json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["release_open_contacts"], release);
    loss.push_back(j["final_loss"].get<double>());
  }
  EXPECT_NE(loss[0], loss[1]);
  expect_bad_input("learn scene --bodies 10 --steps 30 --method relaxed --release-open-contacts --json",
                   "--release-open-contacts");
}

// --mass-normalized and --complementarity-weight reach the relaxed loss (on the box stack,
// 1,000 kg boxes, each changes the loss at the initial parameters); both refuse other
// methods, and a negative weight is refused naming a2.
TEST(CliLearnSceneOptions, MassNormalizationReachesTheRelaxedLoss) {
  const std::string common = "learn scene --scene '" + kStack + "' --steps 20 --learn mu --method relaxed --epochs 0 --json";
  auto loss = [&](const std::string& extra) {
    const CliRun r = run_cli(common + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out)["final_loss"].get<double>();
  };
  const double plain = loss(""), heavier = loss(" --complementarity-weight 0.4");
  const double normalized = loss(" --mass-normalized true");
  EXPECT_NE(plain, heavier);
  EXPECT_NE(plain, normalized);
  expect_bad_input("learn scene --scene '" + kStack + "' --method convex --mass-normalized true --json", "--mass-normalized");
  expect_bad_input("learn scene --scene '" + kStack + "' --method hard --complementarity-weight 1 --json",
                   "--complementarity-weight");
  expect_bad_input("learn scene --scene '" + kStack + "' --complementarity-weight -1 --json", "a2");
}

// --robust-scale trains on Σ c log(1 + ℓᵢ/c): with c far below the stack's losses (~8e-8)
// each transition's pull is weighted by c/ℓᵢ, so two SGD epochs move the masses much less
// than the plain mean's; final_loss stays the plain mean data loss (equal at epochs 0); the
// scale is echoed, and a negative one is refused naming the option.
TEST(CliLearnSceneOptions, RobustScaleReachesTheTraining) {
  const std::string common = "learn scene --scene '" + kStack + "' --steps 20 --learn mu,mass --method relaxed --json";
  auto run = [&](const std::string& extra) {
    const CliRun r = run_cli(common + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  EXPECT_EQ(run(" --epochs 0")["final_loss"].get<double>(),
            run(" --epochs 0 --robust-scale 1e-9")["final_loss"].get<double>());
  const auto plain = run(" --epochs 2 --patience 0 --optimizer sgd");
  const auto robust = run(" --epochs 2 --patience 0 --optimizer sgd --robust-scale 1e-9");
  EXPECT_EQ(robust["robust_scale"].get<double>(), 1e-9);
  auto moved = [](const nlohmann::json& j) {
    return std::abs(j["learned"]["class0.mass"].get<double>() - j["initial"]["class0.mass"].get<double>());
  };
  EXPECT_GT(moved(plain), 0.0);
  EXPECT_LT(moved(robust), 0.2 * moved(plain));
  expect_bad_input("learn scene --scene '" + kStack + "' --robust-scale -1 --json", "--robust-scale");
}

TEST(CliLearnSceneBadInput, ExitsTwoNamingTheProblem) {
  expect_bad_input("learn scene --learn mu,friction --json", "friction");
  expect_bad_input("learn scene --method soft --json", "--method");
  expect_bad_input("learn scene --data x.csv --json", "--data");
  const std::string wrong_bodies = write_trajectory("scene_2_bodies.csv", 2, 3, false, false);
  expect_bad_input("learn scene --scene '" + kStack + "' --data '" + wrong_bodies + "' --json", ":2:");
  const std::string with_nan = write_trajectory("scene_nan.csv", 3, 3, true, false);
  expect_bad_input("learn scene --scene '" + kStack + "' --data '" + with_nan + "' --json", ":6:");
  const std::string with_gap = write_trajectory("scene_gap.csv", 3, 3, false, true);
  expect_bad_input("learn scene --scene '" + kStack + "' --data '" + with_gap + "' --json", "scene_gap.csv");
  std::filesystem::remove(wrong_bodies), std::filesystem::remove(with_nan), std::filesystem::remove(with_gap);
}

}  // namespace
}  // namespace lcprelax
