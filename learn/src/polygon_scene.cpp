// The polygon on the ground as a one-body scene (polygon_scene.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/core/math_constants.hpp>
#include <lcprelax/learn/polygon_scene.hpp>

#include <cmath>

namespace lcprelax::learn {
Scene polygon_scene(const PolygonModel& model, double dt, const Vec2& gravity, double margin) {
  Scene scene;
  RigidBody body;
  body.shape = model.shape;
  body.mass = model.mass;
  body.inertia = model.inertia;
  scene.world.bodies.push_back(body);
  scene.world.half_planes.push_back(ground_half_plane(model.ground_height, model.ground_angle));
  scene.world.gravity = gravity;
  scene.world.friction.default_mu = model.mu;
  scene.settings.dt = dt;
  scene.settings.margin = margin;
  return scene;
}

SceneDataset polygon_scene_dataset(const PolygonModel& model, const PolygonDataset& data, double extra_margin) {
  if (!(std::isfinite(extra_margin) && extra_margin >= 0)) throw InputError("extra_margin: must be finite and >= 0");
  SceneDataset out;
  out.scene = polygon_scene(model, data.dt, data.gravity, data.margin + extra_margin);
  out.scene.steps = std::max<int>(1, static_cast<int>(data.transitions.size()));
  out.shape_class = scene_shape_classes(out.scene.world);
  out.transitions.reserve(data.transitions.size());
  for (std::size_t i = 0; i < data.transitions.size(); ++i) {
    const PolygonTransition& p = data.transitions[i];
    SceneTransition t;
    t.step = static_cast<int>(i);
    t.pose = {p.q};
    t.velocity = {p.v};
    t.applied = {p.u};
    t.next_pose = {p.q_next};
    t.next_velocity = {p.v_next};
    out.transitions.push_back(std::move(t));
  }
  return out;
}

void polygon_to_scene_values(const ParameterSet& polygon_theta, ParameterSet& scene_theta) {
  const Index n = polygon_theta.size();
  if (scene_theta.size() != n) throw InputError("polygon parameters: θ does not have the one-body scene's layout");
  const PolygonLayout layout{(n - PolygonLayout::kFirstVertex - 2) / 2};
  Vector v = polygon_theta.values();
  const double h = v(layout.ground_height()), alpha = v(layout.ground_angle());
  v(n - 2) = alpha + kHalfPi;       // ψ: normal (cos ψ, sin ψ) = (−sin α, cos α)
  v(n - 1) = h * std::cos(alpha);   // offset
  scene_theta.set_values(v);
}

Vector polygon_gradient_from_scene(const ParameterSet& polygon_theta, const Vector& scene_gradient) {
  const Index n = polygon_theta.size();
  const PolygonLayout layout{(n - PolygonLayout::kFirstVertex - 2) / 2};
  const double h = polygon_theta[layout.ground_height()].value, alpha = polygon_theta[layout.ground_angle()].value;
  const double g_psi = scene_gradient(n - 2), g_offset = scene_gradient(n - 1);
  Vector g = scene_gradient;
  g(layout.ground_height()) = std::cos(alpha) * g_offset;
  g(layout.ground_angle()) = g_psi - h * std::sin(alpha) * g_offset;
  return g;
}

}  // namespace lcprelax::learn
