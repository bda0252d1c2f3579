// Example: build a 2-D world in code and simulate it with lcprelax::Simulator.
//
// A container (the ground half-plane y ≥ 0 and two wall segments) and four convex polygons
// dropped into it: a box, a triangle, a hexagon and a plank falling on top of them, one of
// them on a low-friction material. 100 steps of 10 ms with the LCP contact model; every 20
// steps the contacts and the deepest penetration are printed, and at the end the contacts
// of the final state.
//
// Units and signs (docs/conventions.md, world/world.hpp): SI throughout (m, kg, s, N,
// N·s; angles in rad, counter-clockwise). A body's pose is (x, y, θ) of its centre of mass;
// polygon vertices are in the body frame, counter-clockwise (make_body() recentres them on
// the centroid and computes mass and inertia from an area density in kg/m²). A contact's
// normal points from body b to body a, and its gap φ is negative when the shapes overlap.
//
// Exit status 1 if an island's contact solve fails, a body leaves the container, or the
// penetration exceeds 1 mm (post-stabilization keeps it near the 0.1 mm slop).
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/math_constants.hpp>
#include <lcprelax/models/simulator.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace lcprelax;

namespace {

// A regular n-gon of circumradius r (m), counter-clockwise.
Polygon regular_polygon(int n, double r) {
  Polygon p;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * kPi * k / n;
    p.vertices.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return p;
}

// A w × h rectangle (m) about the origin, counter-clockwise.
Polygon rectangle(double w, double h) {
  return Polygon{{{-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}}};
}

World make_world() {
  World world;  // gravity (0, −9.81) m/s² by default
  const double width = 1.0, height = 1.0;
  world.half_planes.push_back(HalfPlane{Vec2(0.0, 1.0), 0.0, 0});         // ground: free space y ≥ 0
  world.segments.push_back(Segment{Vec2(0.0, 0.0), Vec2(0.0, height), 0});    // left wall x = 0
  world.segments.push_back(Segment{Vec2(width, 0.0), Vec2(width, height), 0});  // right wall x = 1

  // Friction: μ = 0.5 for every pair of materials, except 0.1 between material 1 and 0.
  world.friction.default_mu = 0.5;
  world.friction.pairs.push_back(FrictionTable::Pair{1, 0, 0.1});

  const double density = 500.0;  // kg/m² (a lamina: mass = density · area)
  // make_body(shape, density, pose (x, y, θ)): a dynamic body at rest.
  world.bodies.push_back(make_body(rectangle(0.2, 0.2), density, Vec3(0.25, 0.15, 0.0)));
  world.bodies.push_back(make_body(Polygon{{{-0.1, -0.08}, {0.1, -0.08}, {0.0, 0.12}}}, density,
                                   Vec3(0.5, 0.12, 0.3)));  // a triangle, tilted by 0.3 rad
  RigidBody hexagon = make_body(regular_polygon(6, 0.1), density, Vec3(0.75, 0.2, 0.0));
  hexagon.velocity = Vec3(-0.5, 0.0, 2.0);  // (vx, vy) in m/s, ω in rad/s (counter-clockwise)
  hexagon.material = 1;                     // μ = 0.1 against everything else
  world.bodies.push_back(hexagon);
  world.bodies.push_back(make_body(rectangle(0.7, 0.05), density, Vec3(0.5, 0.5, 0.05)));  // plank
  return world;
}

}  // namespace

int main() {
  SimulatorSettings settings;
  settings.dt = 0.01;                   // s
  settings.model = ContactModel::lcp;   // Stewart–Trinkle LCP by Lemke (or ContactModel::convex)
  Simulator sim(make_world(), settings);  // copies the world; sim.world() is the current state

  // Applied generalized forces (fx, fy, τ) per body, N and N·m, constant over a step: push
  // the 20 kg box to the right for the first 0.3 s (150 N against 98 N of friction at μ 0.5).
  std::vector<Vec3> push(sim.world().bodies.size(), Vec3::Zero());
  push[0] = Vec3(150.0, 0.0, 0.0);

  const double e0 = sim.total_energy();  // J (kinetic + gravitational)
  double max_penetration = 0.0;
  int failed = 0;
  for (int k = 1; k <= 100; ++k) {
    const StepStats st = sim.step(k <= 30 ? push : std::vector<Vec3>{});
    max_penetration = std::max(max_penetration, st.max_penetration);
    failed += st.failed_islands;
    if (st.failed_islands > 0) std::printf("step %d: failed island: %s\n", k, st.first_failure.c_str());
    if (k % 20 == 0)
      std::printf("t = %.2f s: %d contacts in %d islands, penetration %.2e m, energy %.4f J\n", sim.time(),
                  st.contacts, st.islands, st.max_penetration, sim.total_energy());
  }

  // Contacts found at the start of the last step: body a against body b (≥ 0) or a static
  // shape (b = −1: the ground half-plane or a wall segment).
  for (const Contact& c : sim.contacts()) {
    const char* other = c.body_b >= 0 ? "body" : c.static_kind == Contact::StaticKind::half_plane ? "ground" : "wall";
    std::printf("  body %d on %s %d: point (%.3f, %.3f) m, normal (%.2f, %.2f), gap %.1e m, mu %.1f\n", c.body_a,
                other, c.body_b >= 0 ? c.body_b : c.static_index, c.point.x(), c.point.y(), c.normal.x(),
                c.normal.y(), c.gap, c.mu);
  }
  bool inside = true;
  for (const RigidBody& b : sim.world().bodies) {
    std::printf("  body at (%.3f, %.3f) m, angle %.3f rad, speed %.3f m/s\n", b.pose.x(), b.pose.y(), b.pose.z(),
                b.velocity.head<2>().norm());
    inside = inside && b.pose.x() > 0.0 && b.pose.x() < 1.0 && b.pose.y() > 0.0 && b.pose.y() < 1.0;
  }
  std::printf("energy %.4f J -> %.4f J, max penetration %.2e m, failed islands %d\n", e0, sim.total_energy(),
              max_penetration, failed);
  const bool ok = failed == 0 && inside && max_penetration < 1e-3;
  std::printf("%s\n", ok ? "OK" : "FAILED");
  return ok ? 0 : 1;
}
