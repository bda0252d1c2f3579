#pragma once
// Small scene builders and measurements for the dynamics tests (boxes, ground, inclines,
// stacks, pyramids, a closed pile of random polygons).
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

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

/// A simulator of make_pile_scene(bodies, seed) with `model` and `settings` as given.
inline Simulator pile_simulator(int bodies, std::uint64_t seed, ContactModel model, const SimulatorSettings& settings) {
  PileOptions options;
  options.bodies = bodies;
  options.seed = seed;
  options.model = model;
  return make_simulator(make_pile_scene(options), settings);
}

/// A simulator of make_pile_scene(bodies, seed) with `model`, one thread and
/// `passes` post-stabilization passes (the rest of SimulatorSettings at its defaults).
inline Simulator pile_simulator(int bodies, std::uint64_t seed, ContactModel model, int passes = 5) {
  SimulatorSettings settings;
  settings.threads = 1;
  settings.post_stabilization_passes = passes;
  return pile_simulator(bodies, seed, model, settings);
}

/// `count` unit boxes (1 m, 1 kg) stacked on the ground at x = 0, every gap 0.
/// The contact system of the island with the most contacts in sim's current state (at
/// sim's Δt; an empty system when no two bodies touch).
inline ContactSystem largest_island_system(const Simulator& sim, const CollisionSettings& collision = {}) {
  const World& world = sim.world();
  const std::vector<Contact> contacts = find_contacts(world, collision);
  const std::vector<Island> islands = find_islands(world, contacts);
  if (islands.empty()) return ContactSystem{};
  const Island& island = *std::max_element(islands.begin(), islands.end(), [](const Island& a, const Island& b) {
    return a.contacts.size() < b.contacts.size();
  });
  return assemble_contact_system(world, contacts, island, sim.settings().dt);
}

inline std::vector<RigidBody> box_stack(int count) {
  std::vector<RigidBody> bodies;
  for (int i = 0; i < count; ++i) bodies.push_back(box(1.0, 1.0, 1.0, Vec3(0.0, 0.5 + i, 0.0)));
  return bodies;
}

/// A pyramid of unit boxes (1 m, 1 kg) on the ground: row r has base − r boxes spaced
/// 1.1 m apart, each box above the ground resting on two boxes (0.45 m of its face on
/// each, gap 0) and clear of its row neighbours (0.1 m, beyond the 1 cm margin).
/// base(base + 1)/2 boxes; 2·base + 4·(base(base + 1)/2 − base) contacts.
inline std::vector<RigidBody> box_pyramid(int base) {
  std::vector<RigidBody> bodies;
  for (int r = 0; r < base; ++r)
    for (int i = 0; i < base - r; ++i) bodies.push_back(box(1.0, 1.0, 1.0, Vec3((i + 0.5 * r) * 1.1, 0.5 + r, 0.0)));
  return bodies;
}

constexpr double kPi = 3.14159265358979323846;

/// Uniform draw in [0, 1) from the top 53 bits (the same on every standard library).
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// A closed pile: `count` random convex polygons (3 to 8 vertices on a circle of radius
/// 0.1–0.2 m, density 100 kg/m², random angle) at rest on a grid of 0.5 m cells, the
/// lowest row 0.05–0.15 m above the ground, inside a container made of the ground
/// half-plane and two vertical wall segments x = 0 and x = width (8 cells), 10 m high.
/// Deterministic for `seed`.
inline Scene closed_pile(int count, std::uint64_t seed, ContactModel model = ContactModel::lcp, double mu = 0.5) {
  std::mt19937_64 rng(seed);
  const double cell = 0.5;
  const int columns = 8;
  Scene s = scene_with({}, mu, 1e-2, model);
  for (int k = 0; k < count; ++k) {
    const int n = 3 + static_cast<int>(uniform01(rng) * 6.0);
    const double radius = 0.1 + 0.1 * uniform01(rng);
    Polygon p;
    for (int j = 0; j < n; ++j) {
      const double a = 2.0 * kPi * (j + 0.3 * (uniform01(rng) - 0.5)) / n;
      p.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a));
    }
    const double x = cell * ((k % columns) + 0.5), y = 0.25 + cell * (k / columns);
    s.world.bodies.push_back(make_body(p, 100.0, Vec3(x, y, 2.0 * kPi * uniform01(rng))));
  }
  const double width = cell * columns;
  s.world.segments.push_back(Segment{Vec2(0.0, 0.0), Vec2(0.0, 10.0), 0});
  s.world.segments.push_back(Segment{Vec2(width, 0.0), Vec2(width, 10.0), 0});
  return s;
}

/// Largest distance of a body's centre from where it started (m).
inline double max_drift(const World& world, const std::vector<Vec3>& start) {
  double d = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i)
    d = std::max(d, (world.bodies[i].pose.head<2>() - start[i].head<2>()).norm());
  return d;
}

inline std::vector<Vec3> poses(const World& world) {
  std::vector<Vec3> p;
  for (const RigidBody& b : world.bodies) p.push_back(b.pose);
  return p;
}

/// Largest overlap −φ ≥ 0 over the contacts of the world (m).
inline double max_penetration(const World& world) {
  double p = 0.0;
  for (const Contact& c : find_contacts(world, CollisionSettings{0.0})) p = std::max(p, -c.gap);
  return p;
}

}  // namespace lcprelax::test
