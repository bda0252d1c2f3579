// Multi-start training over a portfolio of recipes (portfolio.hpp).
#include <lcprelax/learn/portfolio.hpp>

#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/state_stream.hpp>
#include <lcprelax/core/stopwatch.hpp>

#include <cmath>

namespace lcprelax::learn {
namespace {

void validate(const std::vector<TrainRecipe>& recipes) {
  if (recipes.empty()) throw InputError("train_portfolio: no recipe");
  for (const TrainRecipe& r : recipes) {
    if (r.stages.empty()) throw InputError("train_portfolio: recipe '" + r.name + "' has no stage");
    for (std::size_t s = 0; s < r.stages.size(); ++s)
      if (const TrainSettings& t = r.stages[s].settings; !t.checkpoint.empty() || !t.resume.empty() || !t.log_csv.empty())
        throw InputError("train_portfolio: recipe '" + r.name + "' stage " + std::to_string(s + 1) +
                         " has a checkpoint, resume or log file (not supported in a portfolio)");
  }
}

// Appends one stage's result to the recipe's running result.
void append_stage(TrainResult& total, TrainResult&& stage, double offset_seconds) {
  const int first_epoch = total.history.empty() ? 0 : total.history.back().epoch;
  for (EpochRecord& rec : stage.history) {
    rec.epoch += first_epoch;
    rec.seconds += offset_seconds;
    total.history.push_back(std::move(rec));
  }
  total.failed += stage.failed;
  if (total.first_failure.empty()) total.first_failure = stage.first_failure;
  total.converged = stage.converged;
  total.stop_reason = std::move(stage.stop_reason);
}

// Whether outcome a is better than b: fewer failed samples, then a lower loss (NaN loses).
bool better(const RecipeOutcome& a, const RecipeOutcome& b) {
  if ((a.failed > 0) != (b.failed > 0)) return a.failed == 0;
  if (std::isnan(a.final_loss)) return false;
  if (std::isnan(b.final_loss)) return true;
  return a.final_loss < b.final_loss;
}

}  // namespace

PortfolioResult train_portfolio(Objective& objective, Objective& selection, ParameterSet& theta,
                                const std::vector<Index>& training, const std::vector<Index>& validation,
                                const std::vector<TrainRecipe>& recipes) {
  validate(recipes);
  const ParameterSet start = theta;
  // The objective's state that later evaluations depend on (warm starts, proximal centres):
  // every recipe starts from the state the first one found.
  StateWriter saved;
  objective.save_state(saved);
  const std::string start_state = saved.take();
  PortfolioResult out;
  ParameterSet best = theta;
  std::string best_state;
  for (std::size_t k = 0; k < recipes.size(); ++k) {
    const TrainRecipe& recipe = recipes[k];
    ParameterSet at = start;
    if (k > 0) {
      StateReader in(start_state, "train_portfolio: the objective's saved state");
      objective.load_state(in);
    }
    const auto t0 = SteadyClock::now();
    TrainResult total;
    for (const TrainStage& stage : recipe.stages) {
      const double offset = seconds_since(t0);
      Objective& trained = stage.objective ? *stage.objective : objective;
      append_stage(total, train(trained, at, training, validation, stage.settings), offset);
    }
    const TrainSettings& last = recipe.stages.back().settings;
    const BatchResult eval = evaluate_mean(selection, at, training, last.threads, last.distributed);
    RecipeOutcome o;
    o.name = recipe.name;
    o.final_loss = eval.loss;
    o.failed = eval.failed;
    o.epochs = total.history.empty() ? 0 : total.history.back().epoch;
    o.seconds = seconds_since(t0);
    o.stop_reason = total.stop_reason;
    o.converged = total.converged;
    total.seconds = o.seconds;
    if (k == 0 || better(o, out.outcomes[out.chosen])) {
      out.chosen = k;
      best = at;
      out.result = std::move(total);
      StateWriter w;  // the state the kept θ was scored with (e.g. relaxed proximal centres)
      objective.save_state(w);
      best_state = w.take();
    }
    out.outcomes.push_back(std::move(o));
  }
  if (out.chosen + 1 != recipes.size()) {
    StateReader in(best_state, "train_portfolio: the kept recipe's objective state");
    objective.load_state(in);
  }
  theta = best;
  return out;
}

}  // namespace lcprelax::learn
