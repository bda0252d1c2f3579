#pragma once
// A polygon on the ground is a ONE-BODY SCENE: the constructors that make `learn polygon`
// an instance of the scene learning path (scene_dataset.hpp, scene_params.hpp,
// scene_objective.hpp), with no collision, assembly or loss of its own.
//
// - polygon_scene: world = one dynamic body (the model's shape, mass, inertia; material 0)
//   and one half-plane (the ground, ground_half_plane), friction table default μ = the
//   model's μ; the simulator settings dt, gravity, margin of the polygon dataset. The data
//   generator (polygon_dataset.cpp) simulates this scene.
// - polygon_scene_dataset: each PolygonTransition becomes a SceneTransition of that one body
//   (pose, velocity, applied force, next pose and velocity). A polygon dataset concatenates
//   several throws, so SceneTransition::step is the transition's index (steps must increase).
// - θ: the polygon's layout (polygon_params.hpp) and the one-body scene's
//   (SceneParameterMap: "mu", "class0.mass", "class0.inertia", "class0.vertex<i>.x|y",
//   "half_plane0.angle", "half_plane0.offset") agree entry by entry on μ, mass, inertia and
//   the vertices; the ground differs only in its coordinates: the polygon's (h, α), ground
//   line through (0, h) rising at α, are the half-plane's normal angle ψ = α + π/2 (normal
//   (cos ψ, sin ψ) = (−sin α, cos α)) and offset o = h cos α. So
//       ∂ℓ/∂h = cos α · ∂ℓ/∂o,     ∂ℓ/∂α = ∂ℓ/∂ψ − h sin α · ∂ℓ/∂o.
#include <lcprelax/learn/polygon_dataset.hpp>
#include <lcprelax/learn/polygon_params.hpp>
#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/learn/scene_params.hpp>

namespace lcprelax::learn {

/// The one-body scene of `model` with the settings of `data` (dt, gravity, margin); the
/// body rests at the origin (a dataset's transitions set its state).
Scene polygon_scene(const PolygonModel& model, double dt, const Vec2& gravity, double margin);

/// The polygon dataset as a dataset of polygon_scene(model, data.dt, data.gravity,
/// data.margin + extra_margin). extra_margin (m, ≥ 0) widens the contact margin of LEARNING
/// (contact candidates, PolygonLossSettings::candidate_margin); the transitions are unchanged.
SceneDataset polygon_scene_dataset(const PolygonModel& model, const PolygonDataset& data, double extra_margin = 0.0);

/// Sets the values of `scene_theta` (the layout of SceneParameterMap on polygon_scene) from
/// the polygon's θ (the layout of make_polygon_parameters, same vertex count).
void polygon_to_scene_values(const ParameterSet& polygon_theta, ParameterSet& scene_theta);

/// ∂ℓ/∂θ in the polygon's layout from ∂ℓ/∂θ in the scene's layout (formulas above).
Vector polygon_gradient_from_scene(const ParameterSet& polygon_theta, const Vector& scene_gradient);

}  // namespace lcprelax::learn
