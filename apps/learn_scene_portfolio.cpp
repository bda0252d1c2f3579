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

  if (ls.method != learn::LossMethod::convex) return p;
  learn::SceneLossSettings smooth_settings = ls;
  smooth_settings.convex = learn::ConvexStepLossSettings{};
  smooth_settings.convex.softening = ls.convex.softening;
  p.first_stage_objective = std::make_unique<learn::SceneObjective>(data, map, smooth_settings);
  learn::TrainSettings first = t;
  first.epochs = o.smooth_epochs;
  p.recipes.push_back({"smooth+" + o.optimizer, {{first, p.first_stage_objective.get()}, {t}}});
  return p;
}

}  // namespace lcprelax::cli
