#pragma once
// Shared fixture of the polygon assembly and loss-gradient tests: a quadrilateral on a
// ground raised by 5 cm and tilted by 0.12 rad (not the CLI's reference model: a tilted,
// raised ground exercises the ground-height and ground-angle derivatives).
#include <lcprelax/learn/polygon_params.hpp>

namespace lcprelax::learn::test {

inline PolygonModel quad_model() {
  PolygonModel m;
  m.shape.vertices = {Vec2(-0.3, -0.2), Vec2(0.35, -0.22), Vec2(0.28, 0.25), Vec2(-0.32, 0.18)};
  m.mu = 0.4;
  m.mass = 1.7;
  m.inertia = 0.09;
  m.ground_height = 0.05;
  m.ground_angle = 0.12;
  return m;
}

}  // namespace lcprelax::learn::test
