#pragma once
// Convex-polygon geometry for scenes: validation, mass properties, recentring.
//
// Conventions (SI units; models/world.hpp): vertices are counter-clockwise; a valid body
// polygon has 3 to 12 vertices and is strictly convex (every turn strictly to the left, total
// turning exactly one revolution, no repeated or collinear vertices).
// Mass properties of a uniform lamina of area density ρ (kg/m²) with vertices v_0..v_{n-1}
// (indices mod n), c_i = v_i × v_{i+1} = x_i y_{i+1} − x_{i+1} y_i:
//   area      A  = ½ Σ c_i
//   centroid  C  = (1 / 6A) Σ c_i (v_i + v_{i+1})
//   polar second moment about the origin
//             J₀ = (1/12) Σ c_i (x_i² + x_i x_{i+1} + x_{i+1}² + y_i² + y_i y_{i+1} + y_{i+1}²)
//   about the centroid (parallel-axis theorem)  J = J₀ − A |C|²
//   mass m = ρ A, inertia I = ρ J (kg·m²).
// The sums are evaluated relative to the vertex mean to limit cancellation far from the origin.
#include <lcprelax/models/world.hpp>

#include <string>
#include <vector>

namespace lcprelax {

/// Geometric properties of a polygon (per unit density).
struct PolygonProperties {
  double area = 0.0;               ///< A (m²), > 0 for counter-clockwise polygons
  Vec2 centroid = Vec2::Zero();    ///< C (m), in the frame the vertices are given in
  double polar_moment = 0.0;       ///< J (m⁴), about the centroid
};

/// Area, centroid and polar second moment of a simple polygon (any vertex count ≥ 3;
/// a clockwise polygon gives A < 0 and J < 0).
PolygonProperties polygon_properties(const std::vector<Vec2>& vertices);

/// Throws InputError "FIELD: ..." unless `vertices` is a valid body polygon: 3..12 finite
/// vertices, counter-clockwise ("polygon is clockwise"), strictly convex ("polygon is not
/// convex", "... collinear or repeated vertices").
void check_convex_polygon(const std::vector<Vec2>& vertices, const std::string& field);

/// A body whose polygon has the world shape p = (x, y) + R(θ) v_i for the given `vertices`
/// (relative to the reference point `pose` = (x, y, θ), any origin): the vertices are
/// recentred on their centroid C and the body's pose becomes (x, y) + R(θ) C, θ; mass ρA and
/// inertia ρJ. The velocity is zero. Throws InputError (field "vertices"/"density") for an
/// invalid polygon or ρ not finite and > 0.
RigidBody polygon_body(const std::vector<Vec2>& vertices, double density, const Vec3& pose);

/// Moves the origin of `vertices` to their centroid and returns the centroid (in the input
/// frame). A centroid within 1e-12 of the polygon's size from the origin counts as the
/// origin (nothing moves, zero is returned), so that already centred polygons are kept
/// bit for bit.
Vec2 recentre_polygon(std::vector<Vec2>& vertices);

}  // namespace lcprelax
