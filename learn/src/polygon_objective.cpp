// The polygon learning Objective: the scene path on a one-body scene (polygon_objective.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/polygon_objective.hpp>

#include <cmath>
#include <stdexcept>

namespace lcprelax::learn {

PolygonLossSettings::PolygonLossSettings() {
  convex.formulation = ConvexFormulation::dual;  // W of 2 to 8 rows: the dense dual QPs
  convex.phase1_regularization = 0.0;            // the library's convex model exactly
}

std::string PolygonLossSettings::validation_error() const {
  if (!(std::isfinite(candidate_margin) && candidate_margin >= 0)) return "candidate_margin: must be finite and >= 0";
  return SceneLossSettings::validation_error();
}

namespace {

const PolygonLossSettings& checked(const PolygonLossSettings& s) {
  const std::string e = s.validation_error();
  if (!e.empty()) throw InputError("polygon loss settings: " + e);
  return s;
}

}  // namespace

PolygonObjective::PolygonObjective(const PolygonDataset& data, const PolygonModel& model, PolygonLossSettings settings)
    : settings_(checked(settings)), scene_data_(polygon_scene_dataset(model, data, settings_.candidate_margin)) {
  const std::string e = model.validation_error();
  if (!e.empty()) throw InputError("polygon model: " + e);
  if (data.transitions.empty()) throw InputError("polygon dataset: no transitions");
  SceneParameterSettings ps;
  ps.learn = SceneLearnFlags{true, true, true, true, true};
  map_ = std::make_unique<SceneParameterMap>(scene_data_.scene.world, ps);
  scene_theta_ = map_->parameters(scene_data_.scene.world);
  scene_ = std::make_unique<SceneObjective>(scene_data_, *map_, settings_);
}

PolygonObjective::~PolygonObjective() = default;

void PolygonObjective::prepare(const ParameterSet& theta, int threads) {
  polygon_to_scene_values(theta, scene_theta_);
  prepared_ = theta.values();
  scene_->prepare(scene_theta_, resolve_threads(threads));
}

const ParameterSet& PolygonObjective::scene_theta(const ParameterSet& theta) const {
  if (prepared_.size() != theta.size() || prepared_ != theta.values())
    throw std::logic_error("PolygonObjective: prepare() was not called with this θ");
  return scene_theta_;
}

SampleResult PolygonObjective::evaluate(Index sample, const ParameterSet& theta, int thread) {
  SampleResult r = scene_->evaluate(sample, scene_theta(theta), thread);
  if (r.gradient.size() == theta.size()) r.gradient = polygon_gradient_from_scene(theta, r.gradient);
  return r;
}

ResidualResult PolygonObjective::evaluate_residuals(Index sample, const ParameterSet& theta, int thread) {
  ResidualResult r = scene_->evaluate_residuals(sample, scene_theta(theta), thread);
  if (r.jacobian.cols() == theta.size())
    for (Index i = 0; i < r.jacobian.rows(); ++i)
      r.jacobian.row(i) = polygon_gradient_from_scene(theta, r.jacobian.row(i).transpose()).transpose();
  return r;
}

PolygonLossTimes PolygonObjective::times() const {
  const SceneObjectiveStats s = scene_->stats();
  PolygonLossTimes t;
  t.assembly = s.seconds_collision;
  t.solve = s.seconds_loss;
  t.backward = s.seconds_pullback;
  t.samples = s.transitions;
  return t;
}

}  // namespace lcprelax::learn
