#pragma once
// Multi-start training over a portfolio of recipes: each recipe is a sequence of training
// stages (train(), trainer.hpp) started from the same initial θ, stage k + 1 from the θ that
// stage k ended at; the recipe whose final θ has the lowest mean TRAINING loss under
// `selection` (typically the data loss, without a prior's term) is kept. Nothing but the
// training data decides: no truth, no validation set (that stays held out).
//
// Why: on nonconvex losses no single optimizer wins on every problem, and a stalled run
// looks like a converged one from the inside (a kink, a flat valley). Measured on the
// convex loss of the learning pile (learn scene, 25% perturbation, bench/results/
// learn_scene_recovery.csv): Levenberg–Marquardt alone recovers the 30-body seeds 1, 2 and 5
// and stops at kinks on seed 3 and on the 20-body seed 4; 300 epochs of Adam then LM
// recovers the 20-body seed 4; LM on a smoothed loss first, then on the unbiased one,
// recovers seed 3 to 2.7%. In each case the recipe with the smallest parameter error had the
// lowest training loss. The price is the sum of the recipes' run times.
//
// Every recipe starts from the same θ and the same state of `objective` (Objective::save_state
// before the first recipe, load_state before each later one: warm starts, proximal centres).
// A stage may train another objective (TrainStage::objective): a continuation that starts on
// a smoothed loss and ends on the one `selection` scores (graduated non-convexity, Blake &
// Zisserman, "Visual Reconstruction", 1987).
// Ties keep the earlier recipe. A recipe whose final evaluation has failed samples loses
// to one without. Checkpoints and CSV logs (TrainSettings::checkpoint, resume, log_csv) are
// refused in a portfolio (the stages would overwrite one file); InputError names the recipe
// and stage.
#include <lcprelax/learn/trainer.hpp>

#include <string>
#include <vector>

namespace lcprelax::learn {

/// One stage of a recipe: its settings and, optionally, its own loss (e.g. a smoothed one
/// that a continuation starts on; nullptr: the portfolio's `objective`).
struct TrainStage {
  TrainSettings settings;
  Objective* objective = nullptr;
};

struct TrainRecipe {
  std::string name;               ///< e.g. "lm", "adam+lm"
  std::vector<TrainStage> stages;  ///< at least one
};

struct RecipeOutcome {
  std::string name;
  double final_loss = 0.0;  ///< mean training loss of `selection` at the recipe's final θ
  int failed = 0;           ///< failed samples in that evaluation
  int epochs = 0;           ///< over all stages
  double seconds = 0.0;     ///< training and the final evaluation
  std::string stop_reason;  ///< of the last stage
  bool converged = false;   ///< of the last stage
};

struct PortfolioResult {
  std::vector<RecipeOutcome> outcomes;  ///< one per recipe, in order
  std::size_t chosen = 0;               ///< index of the kept recipe
  /// The kept recipe's training: its stages' histories one after the other (epochs numbered
  /// on, seconds from the recipe's start), failures summed, stop reason and convergence of
  /// its last stage.
  TrainResult result;
};

/// Runs every recipe from `theta` and leaves `theta` at the chosen recipe's final values and
/// `objective` in the state it had there (so a later evaluation at θ gives its final loss,
/// for an objective whose evaluations do not change its state: the relaxed scene loss
/// advances its proximal centres by one step per evaluation, so its next evaluation at θ
/// differs, e.g. 0.0296 against 0.0302 on a short 8-body run).
/// `objective` is trained (where a stage names no objective of its own), `selection` scores
/// the final θ of each recipe on `training` (pass the same object for both when there is no
/// prior). Throws InputError on an empty portfolio, a recipe without stages or a stage with
/// a checkpoint, resume or log file, and whatever train() throws.
PortfolioResult train_portfolio(Objective& objective, Objective& selection, ParameterSet& theta,
                                const std::vector<Index>& training, const std::vector<Index>& validation,
                                const std::vector<TrainRecipe>& recipes);

}  // namespace lcprelax::learn
