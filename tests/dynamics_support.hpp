#pragma once
// Small scene builders for the dynamics tests (boxes, ground, inclines).
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/scenes/scene.hpp>

#include <cmath>

namespace lcprelax::test {

inline Polygon box_polygon(double width, double height) {
  const double w = 0.5 * width, h = 0.5 * height;
  return Polygon{{Vec2(-w, -h), Vec2(w, -h), Vec2(w, h), Vec2(-w, h)}};
}

/// A box of the given size and mass (inertia m(w²+h²)/12) at pose (x, y, θ).
inline RigidBody box(double width, double height, double mass, const Vec3& pose) {
  RigidBody b;
  b.shape = box_polygon(width, height);
  b.mass = mass;
  b.inertia = mass * (width * width + height * height) / 12.0;
  b.pose = pose;
  return b;
}

/// The plane y = x·tan α through the origin (ground for α = 0): normal (−sin α, cos α),
/// downhill direction (−cos α, −sin α).
inline HalfPlane plane(double angle) { return HalfPlane{Vec2(-std::sin(angle), std::cos(angle)), 0.0, 0}; }

inline Scene scene_with(std::vector<RigidBody> bodies, double mu, double dt, ContactModel model = ContactModel::lcp,
                        double angle = 0.0) {
  Scene s;
  s.world.bodies = std::move(bodies);
  s.world.half_planes.push_back(plane(angle));
  s.world.friction.default_mu = mu;
  s.settings.dt = dt;
  s.settings.model = model;
  s.settings.margin = 1e-2;
  return s;
}

/// A unit-mass 0.2 m box lying flat on the plane tilted by angle, at rest.
inline Scene incline_scene(double angle, double mu, double dt, ContactModel model) {
  const double h = 0.1;  // half height
  const Vec2 n(-std::sin(angle), std::cos(angle));
  const Vec2 c = h * n;
  return scene_with({box(0.2, 0.2, 1.0, Vec3(c.x(), c.y(), angle))}, mu, dt, model, angle);
}

}  // namespace lcprelax::test
