#pragma once
// Convex polygon geometry: validation, mass properties, recentring, world vertices.
//
// Conventions (models/world.hpp): body-frame vertices, counter-clockwise, centroid at the
// origin; 3 to kMaxPolygonVertices vertices; SI units (m, kg/m², kg, kg·m²).
//
// Mass properties of a uniform lamina (area density ρ, kg/m²), from the triangle fan
// (0, v_i, v_{i+1}) with c_i = v_i × v_{i+1} (Bourke, "Calculating the area and centroid
// of a polygon", 1988; Hally, "Calculation of the moments of polygons", 1987):
//     A  = ½ Σ c_i,      C = (1 / 6A) Σ c_i (v_i + v_{i+1}),
//     J₀ = (ρ / 12) Σ c_i (v_i·v_i + v_i·v_{i+1} + v_{i+1}·v_{i+1})   (polar, about 0),
//     I  = J₀ − m |C|²   (parallel-axis theorem, about the centroid), m = ρ A.
// The sums are taken relative to the first vertex, which keeps them accurate for polygons
// far from the origin.
//
// Validation tolerances (relative, so they do not depend on the unit of length, with
// L = the largest vertex distance from the first vertex):
//   an edge shorter than 1e-9·L is degenerate, the area must exceed 1e-9·L², and every
//   vertex must turn left by more than sin⁻¹(1e-9) (strict convexity).
// Range (so that areas, L⁴ moments and contact margins stay far from overflow and
// underflow, and the tests above never blame a wrong cause): every coordinate within
// ±kMaxPolygonCoordinate and L ≥ kMinPolygonSize; outside it the message names the range.
#include <lcprelax/world/world.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace lcprelax {

/// Largest number of vertices of a polygon (the narrow phase uses fixed-size storage).
constexpr int kMaxPolygonVertices = 12;
/// Smallest number of vertices of a polygon.
constexpr int kMinPolygonVertices = 3;
/// Largest |coordinate| of a vertex (m): 1e15 m (a light-week), far beyond any scene.
constexpr double kMaxPolygonCoordinate = 1e15;
/// Smallest size L of a polygon (m): 1e-12 m (a picometre).
constexpr double kMinPolygonSize = 1e-12;

/// Empty when `polygon` is a valid shape (3..12 finite vertices, counter-clockwise,
/// strictly convex, simple, non-degenerate area); else a message naming the first problem,
/// e.g. "vertex 3 makes the polygon non-convex" or "vertices are clockwise".
/// Does not require the centroid at the origin (see recentred()).
std::string polygon_validation_error(const Polygon& polygon);

struct MassProperties {
  double area = 0.0;                 ///< m² (> 0 for a valid polygon)
  Vec2 centroid = Vec2::Zero();      ///< in the polygon's own frame (m)
  double mass = 0.0;                 ///< kg, density · area
  double inertia = 0.0;              ///< polar moment about the centroid (kg·m²)
};

/// Mass properties of a uniform polygon of area density `density` (kg/m²).
/// Throws InputError if the polygon is invalid (polygon_validation_error), density is not
/// finite and > 0, or the mass or inertia overflows (an extreme density).
MassProperties mass_properties(const Polygon& polygon, double density);

/// Shifts the vertices of `polygon` so that its centroid C is at the origin and returns the
/// shift C (in the polygon's former frame): a body whose vertices were given relative to a
/// reference pose (x, y, θ) keeps its world shape when its pose becomes
/// to_world((x, y, θ), C). A centroid within 1e-12·L of the origin (L as in the validation
/// tolerances) counts as the origin: nothing moves and exactly zero is returned, so an
/// already centred polygon is kept bit for bit (files round-trip exactly).
/// Throws InputError if the polygon is invalid.
Vec2 recentre(Polygon& polygon);

/// The same polygon recentred on its centroid (recentre() on a copy).
Polygon recentred(const Polygon& polygon);

/// A dynamic body with shape `polygon` (recentred on its centroid), mass and inertia from
/// `density` (kg/m²), and pose (x, y, θ) where (x, y) is the world position of the
/// centroid (where the vertices were relative to is discarded; see recentre() to keep a
/// world shape instead). Throws InputError for an invalid polygon or density.
RigidBody make_body(const Polygon& polygon, double density, const Vec3& pose);

/// World position of a body-frame point: (x, y) + R(θ) p.
inline Vec2 to_world(const Vec3& pose, const Vec2& p) {
  const double c = std::cos(pose.z()), s = std::sin(pose.z());
  return Vec2(pose.x() + c * p.x() - s * p.y(), pose.y() + s * p.x() + c * p.y());
}

/// World vertices of a body, in the body's (counter-clockwise) order.
std::vector<Vec2> world_vertices(const RigidBody& body);

}  // namespace lcprelax
