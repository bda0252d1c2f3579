#pragma once
// World-frame convex shapes, the input of the narrow phase.
//
// A ConvexShape is either a polygon (3..12 vertices, counter-clockwise, strictly convex) or
// a segment seen as a degenerate two-vertex polygon (edges a→b and b→a with opposite
// normals, zero thickness, two-sided). Fixed-size storage: no allocation per shape.
//
// Edge i runs from vertex i to vertex i+1 (mod count); normals[i] is its outward unit
// normal, (e_y, −e_x)/|e| for the edge vector e (right-hand perpendicular, outward for a
// counter-clockwise polygon). Units: metres.
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/world/world.hpp>

#include <array>

namespace lcprelax {

struct ConvexShape {
  int count = 0;                                       ///< 2 (segment) or 3..12 (polygon)
  std::array<Vec2, kMaxPolygonVertices> vertices{};    ///< world frame (m)
  std::array<Vec2, kMaxPolygonVertices> normals{};     ///< outward unit edge normals
  Vec2 centre = Vec2::Zero();  ///< body position, or a segment's midpoint (m)
  double radius = 0.0;         ///< largest vertex distance from centre (m): size scale
};

/// The body's polygon placed at its pose. Requires 3..12 vertices (throws InputError
/// otherwise); convexity and orientation are the caller's responsibility
/// (polygon_validation_error).
ConvexShape make_shape(const RigidBody& body);

/// A segment as a two-vertex shape. Throws InputError for a zero-length or non-finite
/// segment.
ConvexShape make_shape(const Segment& segment);

}  // namespace lcprelax
