#pragma once
// An lcprelax Scene simulated by Box2D 2.4 (peer engine of bench/run_pile_peers.cpp).
// Only this header's implementation, box2d_runner.cpp, includes Box2D.
//
// Conversion (SI units: m, kg, s, rad; Box2D computes in float):
// - every RigidBody becomes a b2Body (dynamic, or static when is_static) at the same pose
//   (x, y, θ) and velocity (vx, vy, ω), with exactly lcprelax's mass and inertia about
//   the centre of mass (b2Body::SetMassData, centre (0, 0): vertices are centroid-centred);
//   linear/angular damping 0, restitution 0, friction = world.friction.default_mu on every
//   fixture (Box2D mixes two fixtures' friction as √(μa·μb) = μ; material pair tables are
//   rejected);
// - Box2D polygons carry a skin of radius b2_polygonRadius = 0.01 m (2·b2_linearSlop)
//   around the polygon, and at most b2_maxPolygonVertices = 8 vertices (more: InputError).
//   With `shrink_by_skin` (the default) each polygon is offset inwards by that radius
//   (every edge moved 0.01 m along its inward normal), so that Box2D's rounded shape has
//   the original polygon's edges (its corners are rounded off by 0.01 m); a polygon whose
//   offset would lose an edge or make an edge shorter than 3 mm (Box2D welds vertices
//   closer than 2.5 mm) keeps its original vertices and is counted in unshrunk_polygons();
// - a half-plane {p : n·p ≥ c} becomes a two-sided static edge 2L long (L = 10·(scene
//   extent + 10 m)) on the line n·p = c − 0.01 m (so its skin's surface is the plane);
// - a segment becomes a two-sided static edge with the same end points (its skin makes a
//   wall 0.01 m thicker on each side; noted in bench/README.md).
// Stepping: b2World::Step(dt, velocity_iterations, position_iterations) with Box2D's
// defaults 8 and 3 unless changed; sleeping off by default (lcprelax never sleeps, and a
// sleeping settled pile would cost nothing); continuous collision at its default (on).
#include <lcprelax/scenes/scene.hpp>

#include <memory>

namespace lcprelax::bench {

struct Box2dSettings {
  int velocity_iterations = 8;  ///< Box2D's recommended default
  int position_iterations = 3;  ///< Box2D's recommended default
  bool allow_sleep = false;
  bool shrink_by_skin = true;
};

class Box2dWorld {
 public:
  /// Builds the Box2D world of `scene` (conversion above). Throws InputError for a polygon
  /// of more than 8 vertices or a friction table with material pairs.
  explicit Box2dWorld(const Scene& scene, Box2dSettings settings = {});
  ~Box2dWorld();
  Box2dWorld(const Box2dWorld&) = delete;
  Box2dWorld& operator=(const Box2dWorld&) = delete;

  /// One b2World::Step of the scene's dt.
  void step();

  /// The scene's world with Box2D's current poses and velocities (same shapes).
  World world() const;

  /// Largest overlap (m, ≥ 0) of Box2D's own collision shapes (polygons with their skin)
  /// over the manifold points of touching contacts: max −b2WorldManifold::separations.
  double max_penetration() const;

  /// Manifold points of the touching contacts.
  int contact_points() const;

  /// Polygons that kept their original vertices (see shrink_by_skin above).
  int unshrunk_polygons() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lcprelax::bench
