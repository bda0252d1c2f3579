#pragma once
// The recipes of `lcprelax learn scene --portfolio` (learn/portfolio.hpp; docs/cli.md), all
// from the same initial values, the lowest training loss kept:
//   <opt>           the run's optimizer alone;
//   adam+<opt>      Adam (--lr, --lr-decay) for --portfolio-adam-epochs, then the optimizer;
//   smooth+<opt>    (convex) the optimizer on the default convex loss (smoother and biased:
//                   deviation penalty in both phases) for --portfolio-smooth-epochs, then on
//                   the run's loss;
//   biased+<opt>    (relaxed) the optimizer on the relaxed loss WITHOUT proximal centres
//                   (every evaluation centred at 0: the convexity shift's bias stays, but the
//                   loss is a function of θ alone, so a line search compares like with like)
//                   for --portfolio-smooth-epochs, then on the run's loss (centres carried
//                   across evaluations: unbiased at convergence).
// Why the relaxed continuation: with carried centres the loss a trial point sees includes
// the shift's (b/2)‖x − c‖² for the centre c of the previous evaluation, which penalises
// every move of the solution; on the 30-body learning pile seed 3 L-BFGS stopped there with
// "no decrease along −gradient" at μ 51% off while the loss still fell by 0.09 along
// μ → truth (measured, bench/learn_scene_recovery.sh).
#include <lcprelax/learn/portfolio.hpp>
#include <lcprelax/learn/scene_objective.hpp>

#include <memory>
#include <string>
#include <vector>

namespace lcprelax::cli {

struct ScenePortfolioOptions {
  std::string optimizer;  ///< the run's optimizer's name (recipe names)
  int adam_epochs = 300;
  int smooth_epochs = 40;
};

/// The recipes and the objective of their continuation's first stage (kept alive beside
/// them; null without a continuation, e.g. for the hard loss).
struct ScenePortfolio {
  std::vector<learn::TrainRecipe> recipes;
  std::unique_ptr<learn::SceneObjective> first_stage_objective;
};

/// `t` are the run's training settings; `data` and `map` must outlive the result.
ScenePortfolio make_scene_portfolio(const learn::SceneDataset& data, const learn::SceneParameterMap& map,
                                    const learn::SceneLossSettings& ls, const learn::TrainSettings& t,
                                    const ScenePortfolioOptions& o);

}  // namespace lcprelax::cli
