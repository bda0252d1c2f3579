#include "learn_scene_portfolio.hpp"

namespace lcprelax::cli {

ScenePortfolio make_scene_portfolio(const learn::SceneDataset& data, const learn::SceneParameterMap& map,
                                    const learn::SceneLossSettings& ls, const learn::TrainSettings& t,
                                    const ScenePortfolioOptions& o) {
  ScenePortfolio p;
  learn::TrainSettings adam = t;
  adam.epochs = o.adam_epochs;
  adam.optimizer.kind = learn::OptimizerKind::adam;
  adam.optimizer.lm_geodesic_acceleration = false;
  p.recipes = {{o.optimizer, {{t}}}, {"adam+" + o.optimizer, {{adam}, {t}}}};

  learn::SceneLossSettings first_settings = ls;
  std::string name;
  if (ls.method == learn::LossMethod::convex) {
    first_settings.convex = learn::ConvexStepLossSettings{};
    first_settings.convex.softening = ls.convex.softening;
    name = "smooth+";
  } else if (ls.method == learn::LossMethod::relaxed && ls.relaxed_warm_center) {
    first_settings.relaxed_warm_center = false;
    name = "biased+";
  } else {
    return p;
  }
  p.first_stage_objective = std::make_unique<learn::SceneObjective>(data, map, first_settings);
  learn::TrainSettings first = t;
  first.epochs = o.smooth_epochs;
  p.recipes.push_back({name + o.optimizer, {{first, p.first_stage_objective.get()}, {t}}});
  return p;
}

}  // namespace lcprelax::cli
