// Multi-start training over recipes (learn/portfolio.hpp) on a double well of one parameter,
// ℓ(x) = (x² − 1)² + ¼(x − 1)² as residuals r = (x² − 1, ½(x − 1)): global minimum ℓ = 0 at
// x = 1, a local one (ℓ ≈ 0.93) near x = −0.85, a barrier (ℓ(0) = 1.25) between them.
// From x₀ = −1.5:
// - "lm" (Levenberg–Marquardt, 50 epochs) ends in the local minimum;
// - "sgd+lm" (one full-batch gradient step of α = 0.35, which jumps the barrier to
//   x = −1.5 + 0.35·8.75 = 1.5625, then LM) ends at x = 1.
// Expected: the portfolio keeps the recipe with the lower training loss in either order and
// leaves θ at its result (1e-8); each recipe starts from x₀ (its outcome equals a train() of
// its own from x₀, bitwise); the kept result's history numbers its stages' epochs on; a tie
// keeps the earlier recipe; the selection objective, not the trained one, decides; a stage
// with its own objective trains that one (a continuation); the objective's state (warm
// starts) ends as the kept recipe left it; an empty
// portfolio, a recipe without stages and a stage with a checkpoint are refused.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/portfolio.hpp>

#include "lm_test_problems.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

namespace lcprelax::learn {
namespace {

class DoubleWell : public lm_test::SumOfSquares {
 public:
  Index num_samples() const override { return 4; }
  ResidualResult evaluate_residuals(Index, const ParameterSet& theta, int) override {
    const double x = theta[0].value;
    ResidualResult r;
    r.residual = Vector(2);
    r.residual << x * x - 1.0, 0.5 * (x - 1.0);
    r.jacobian = DenseMatrix(2, 1);
    r.jacobian << 2.0 * x, 0.5;
    return r;
  }
};

// ℓ = (x − c)²: a selection objective that prefers the basin near c.
class Near : public lm_test::SumOfSquares {
 public:
  explicit Near(double c) : c_(c) {}
  Index num_samples() const override { return 4; }
  ResidualResult evaluate_residuals(Index, const ParameterSet& theta, int) override {
    ResidualResult r;
    r.residual = Vector::Constant(1, theta[0].value - c_);
    r.jacobian = DenseMatrix::Constant(1, 1, 1.0);
    return r;
  }

 private:
  double c_;
};

ParameterSet start() { return ParameterSet({Parameter{"x", -1.5}}); }

TrainRecipe lm_recipe() { return {"lm", {{lm_test::lm_settings(50)}}}; }

TrainRecipe sgd_lm_recipe() {
  TrainSettings sgd;
  sgd.epochs = 1;
  sgd.optimizer.kind = OptimizerKind::sgd;
  sgd.optimizer.learning_rate = 0.35;
  sgd.optimizer.momentum = 0.0;
  return {"sgd+lm", {{sgd}, {lm_test::lm_settings(50)}}};
}

TEST(LearnPortfolio, KeepsTheRecipeWithTheLowerTrainingLoss) {
  DoubleWell f;
  const std::vector<Index> samples = lm_test::all(4);
  for (bool lm_first : {true, false}) {
    SCOPED_TRACE(lm_first ? "lm first" : "sgd+lm first");
    const std::vector<TrainRecipe> recipes =
        lm_first ? std::vector<TrainRecipe>{lm_recipe(), sgd_lm_recipe()} : std::vector<TrainRecipe>{sgd_lm_recipe(), lm_recipe()};
    ParameterSet theta = start();
    const PortfolioResult p = train_portfolio(f, f, theta, samples, {}, recipes);
    ASSERT_EQ(p.outcomes.size(), 2u);
    const RecipeOutcome& lm = p.outcomes[lm_first ? 0 : 1];
    const RecipeOutcome& sgd_lm = p.outcomes[lm_first ? 1 : 0];
    std::printf("lm: loss %.3e after %d epochs; sgd+lm: loss %.3e after %d epochs\n", lm.final_loss, lm.epochs,
                sgd_lm.final_loss, sgd_lm.epochs);
    EXPECT_GT(lm.final_loss, 0.5) << "lm should stop in the local minimum";
    EXPECT_LT(sgd_lm.final_loss, 1e-12);
    EXPECT_EQ(p.outcomes[p.chosen].name, "sgd+lm");
    EXPECT_NEAR(theta[0].value, 1.0, 1e-8);
    // The kept history: the SGD epoch, then LM's epochs numbered on.
    ASSERT_EQ(static_cast<int>(p.result.history.size()), sgd_lm.epochs);
    for (std::size_t e = 0; e < p.result.history.size(); ++e) EXPECT_EQ(p.result.history[e].epoch, static_cast<int>(e) + 1);
    EXPECT_NEAR(p.result.history.back().theta(0), 1.0, 1e-8);
    EXPECT_EQ(p.result.stop_reason, sgd_lm.stop_reason);
  }
}

TEST(LearnPortfolio, EveryRecipeStartsFromTheInitialValues) {
  DoubleWell f;
  const std::vector<Index> samples = lm_test::all(4);
  ParameterSet theta = start();
  const PortfolioResult p = train_portfolio(f, f, theta, samples, {}, {sgd_lm_recipe(), lm_recipe()});
  ParameterSet alone = start();
  train(f, alone, samples, {}, lm_test::lm_settings(50));
  const BatchResult e = evaluate_mean(f, alone, samples, 1);
  EXPECT_EQ(p.outcomes[1].final_loss, e.loss);  // bitwise: the same run from x₀
  EXPECT_LT(alone[0].value, -0.5);
}

TEST(LearnPortfolio, TieKeepsTheEarlierRecipe) {
  DoubleWell f;
  ParameterSet theta = start();
  TrainRecipe a = lm_recipe(), b = lm_recipe();
  a.name = "first";
  b.name = "second";
  const PortfolioResult p = train_portfolio(f, f, theta, lm_test::all(4), {}, {a, b});
  EXPECT_EQ(p.outcomes[0].final_loss, p.outcomes[1].final_loss);
  EXPECT_EQ(p.chosen, 0u);
}

TEST(LearnPortfolio, TheSelectionObjectiveDecides) {
  DoubleWell f;
  Near local(-0.85);
  ParameterSet theta = start();
  const PortfolioResult p = train_portfolio(f, local, theta, lm_test::all(4), {}, {sgd_lm_recipe(), lm_recipe()});
  EXPECT_EQ(p.outcomes[p.chosen].name, "lm");
  EXPECT_LT(theta[0].value, -0.5);
}

// A continuation: LM on a convex stand-in ℓ = (x − 2)² first (its own objective), then LM
// on the double well from there, ends at the global minimum; the plain LM recipe does not.
TEST(LearnPortfolio, AStageTrainsItsOwnObjective) {
  DoubleWell f;
  Near smooth(2.0);
  ParameterSet theta = start();
  const TrainRecipe continuation{"smooth+lm", {{lm_test::lm_settings(50), &smooth}, {lm_test::lm_settings(50)}}};
  const PortfolioResult p = train_portfolio(f, f, theta, lm_test::all(4), {}, {lm_recipe(), continuation});
  EXPECT_EQ(p.outcomes[p.chosen].name, "smooth+lm");
  EXPECT_LT(p.outcomes[1].final_loss, 1e-12);
  EXPECT_NEAR(theta[0].value, 1.0, 1e-8);
}

// An objective with state (its evaluation count, saved and loaded like warm starts): after
// the portfolio it is in the state the kept recipe left it in, not the last recipe's.
class CountingWell : public DoubleWell {
 public:
  ResidualResult evaluate_residuals(Index i, const ParameterSet& theta, int t) override {
    ++calls;
    return DoubleWell::evaluate_residuals(i, theta, t);
  }
  void save_state(StateWriter& out) const override { out.put_i64(calls.load()); }
  void load_state(StateReader& in) override { calls = in.get_i64(); }
  std::atomic<long> calls{0};
};

TEST(LearnPortfolio, TheObjectiveEndsInTheKeptRecipesState) {
  CountingWell f, alone;
  ParameterSet theta = start(), theta_alone = start();
  const PortfolioResult p = train_portfolio(f, f, theta, lm_test::all(4), {}, {sgd_lm_recipe(), lm_recipe()});
  ASSERT_EQ(p.chosen, 0u);
  train_portfolio(alone, alone, theta_alone, lm_test::all(4), {}, {sgd_lm_recipe()});
  EXPECT_GT(alone.calls.load(), 0);
  EXPECT_EQ(f.calls.load(), alone.calls.load());
}

TEST(LearnPortfolio, Refusals) {
  DoubleWell f;
  ParameterSet theta = start();
  const std::vector<Index> s = lm_test::all(4);
  EXPECT_THROW(train_portfolio(f, f, theta, s, {}, {}), InputError);
  EXPECT_THROW(train_portfolio(f, f, theta, s, {}, {TrainRecipe{"empty", {}}}), InputError);
  TrainRecipe with_checkpoint = lm_recipe();
  with_checkpoint.stages[0].settings.checkpoint = "/tmp/portfolio.ckpt";
  try {
    train_portfolio(f, f, theta, s, {}, {lm_recipe(), with_checkpoint});
    ADD_FAILURE() << "a stage with a checkpoint was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("recipe 'lm' stage 1"), std::string::npos) << e.what();
  }
  EXPECT_EQ(theta[0].value, -1.5);  // refused before any training
}

}  // namespace
}  // namespace lcprelax::learn
