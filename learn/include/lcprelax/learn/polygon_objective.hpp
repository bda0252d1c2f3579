#pragma once
// The polygon learning problem as a learn::Objective (trainer.hpp): the scene path's
// SceneObjective (scene_objective.hpp) on the one-body scene of polygon_scene.hpp. One
// sample per transition of a PolygonDataset; θ has the polygon's layout
// (make_polygon_parameters, polygon_params.hpp) and is mapped onto the scene's θ before each
// evaluation (polygon_to_scene_values), the gradient back (polygon_gradient_from_scene).
// Everything else is the scene path's: contacts found as the Simulator finds them
// (find_step_contacts), the island's ContactSystem from models/contact_system, the step
// losses (step_loss_hard.hpp, step_loss_relaxed.hpp, step_loss_convex.hpp), their pullback
// (models/contact_system_gradient.hpp, SceneParameterMap::gradient), the relaxed loss's
// per-transition proximal centres (saved in checkpoints), 1 vs N threads bitwise identical.
//
// The target is the sample's NEXT VELOCITY v̄ = v_{k+1} (the simulator post-stabilizes
// positions, so v_{k+1} = v⁺ exactly while q_{k+1} = q_k + Δt v⁺ only up to the projection).
//
// Polygon defaults (PolygonLossSettings, in addition to SceneLossSettings'):
// - candidate_margin = 0.05 m widens the contact margin of learning (not of the data): with
//   the simulator's margin alone, vertices displaced by a perturbed geometry (25%: ±0.05 m
//   per coordinate on the CLI's polygon) miss contacts the data show, and mass and inertia
//   absorb the missing impulses (bench/README.md). The narrow phase keeps at most the two
//   deepest vertices within the margin (contact/narrow_phase.hpp).
// - relaxed: SceneLossSettings' (a1 = 1, a2 = 0.1, ε = 1e-6, lifted form with the
//   per-contact shift and proximal centres, step_loss_relaxed.hpp).
// - convex: dual formulation (W of at most 2 × 2 contacts) with phase1_regularization = 0
//   (the library's convex model exactly) and deviation weight w = 1 (step_loss_convex.hpp).
#include <lcprelax/learn/polygon_dataset.hpp>
#include <lcprelax/learn/polygon_scene.hpp>
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <memory>
#include <string>
#include <vector>

namespace lcprelax::learn {

/// The polygon's methods are the scene path's step losses.
using PolygonMethod = LossMethod;
/// parse_loss_method (step_loss.hpp): "hard", "relaxed" or "convex".
inline PolygonMethod parse_polygon_method(const std::string& s) { return parse_loss_method(s); }

struct PolygonLossSettings : SceneLossSettings {
  double candidate_margin = 0.05;  ///< m, ≥ 0 (above)
  PolygonLossSettings();           ///< the polygon's convex defaults (above)
  std::string validation_error() const;  ///< empty if valid
};

/// Seconds spent in each part (SceneObjectiveStats: collision and assembly, loss, pullback).
struct PolygonLossTimes {
  double assembly = 0.0, solve = 0.0, backward = 0.0;
  long samples = 0;
};

class PolygonObjective : public Objective {
 public:
  /// Keeps a reference to `data` (must outlive the objective). `model` fixes the layout (its
  /// vertex count); the values always come from θ. Throws InputError on invalid settings or
  /// model, or an empty dataset.
  PolygonObjective(const PolygonDataset& data, const PolygonModel& model, PolygonLossSettings settings);
  ~PolygonObjective() override;

  Index num_samples() const override { return scene_->num_samples(); }
  void prepare(const ParameterSet& theta, int threads) override;
  SampleResult evaluate(Index sample, const ParameterSet& theta, int thread) override;
  void save_state(StateWriter& out) const override { scene_->save_state(out); }
  void load_state(StateReader& in) override { scene_->load_state(in); }
  std::string residuals_unavailable() const override { return scene_->residuals_unavailable(); }
  ResidualResult evaluate_residuals(Index sample, const ParameterSet& theta, int thread) override;

  const PolygonLossSettings& settings() const { return settings_; }
  /// The scene path's counters (islands, contacts, failures, proximal solves, times).
  SceneObjectiveStats stats() const { return scene_->stats(); }
  /// Time split summed over threads since construction or reset_times().
  PolygonLossTimes times() const;
  void reset_times() { scene_->reset_stats(); }
  /// Forgets the relaxed method's proximal centres (the next evaluations start at 0).
  void reset_warm_starts() { scene_->reset_centers(); }

 private:
  const ParameterSet& scene_theta(const ParameterSet& theta) const;
  PolygonLossSettings settings_;
  SceneDataset scene_data_;
  std::unique_ptr<SceneParameterMap> map_;
  ParameterSet scene_theta_;  // the scene's θ for the polygon θ of the last prepare()
  Vector prepared_;           // that polygon θ
  std::unique_ptr<SceneObjective> scene_;
};

}  // namespace lcprelax::learn
