#pragma once
// Narrow phase: contact manifolds (at most two points) between world-frame convex shapes.
//
// Conventions (models/world.hpp): the manifold normal is a unit vector from b to a (the
// second argument to the first); each point's gap φ is the signed distance between the
// surfaces along the normal (m), negative when they overlap; the point is midway between
// the two surfaces. Only points with φ ≤ margin are returned (margin ≥ 0, m). All points
// of one manifold share its normal.
//
// Polygon–polygon (and polygon–segment: a segment is a two-vertex ConvexShape) uses the
// separating axis theorem over the edge normals of both shapes (Gottschalk, Lin & Manocha,
// "OBBTree", SIGGRAPH 1996; Ericson, "Real-Time Collision Detection", 2005, §4.4, §5.2.1):
// the face of maximum separation s = max_i min_j n_i·(w_j − v_i) on either shape is the
// reference face; when the two shapes' best separations are within
// kReferenceFaceTolerance·min(radius_a, radius_b) of each other the choice is made by a
// rule that depends only on the geometry (the face whose outward normal is smaller in
// (n_y, n_x) order), so collide(a, b) and collide(b, a) give the same points with
// opposite normals, and a box resting on a box always uses the upper box's bottom face.
// The incident edge of the other shape (the edge most anti-parallel to the reference
// normal) is clipped to the slab of the reference face (Sutherland & Hodgman, CACM 1974;
// Catto, "Contact manifolds", GDC 2007); each clipped point with s = n·(p − r) ≤ margin
// becomes a contact. If the incident edge misses the slab: separated shapes get one point
// from their exact closest features (vertex–edge distance, so shapes farther apart than
// the margin never give contacts); overlapping shapes get the deepest vertex of the
// incident shape. Two points closer than 1e-9·min(radius) are merged into the deeper one.
// Each point records its features (Contact::Feature: reference face, incident vertex or
// clipped incident edge, deepest vertex, closest vertex–edge pair, half-plane vertex), from
// which contact/contact_features.hpp recomputes it.
//
// Polygon–half-plane: the vertices with φ_i = n·v_i − offset ≤ margin; at most the two
// deepest (a flat-lying face gives its two end vertices); normal = the plane's normal.
#include <lcprelax/contact/convex_shape.hpp>
#include <lcprelax/world/world.hpp>

#include <array>

namespace lcprelax {

/// Relative band within which two candidate reference faces count as a tie.
constexpr double kReferenceFaceTolerance = 1e-4;

struct ManifoldPoint {
  Vec2 point = Vec2::Zero();  ///< world, midway between the surfaces (m)
  double gap = 0.0;           ///< φ (m), negative when overlapping
  Contact::Feature feature;   ///< the features of a and b that give the point (world.hpp)
};

struct Manifold {
  Vec2 normal{0.0, 1.0};  ///< unit, from b to a
  int count = 0;          ///< 0, 1 or 2 points
  std::array<ManifoldPoint, 2> points{};
};

/// Contacts between convex shapes a and b (polygons or segments) with φ ≤ margin.
Manifold collide(const ConvexShape& a, const ConvexShape& b, double margin);

/// Contacts between convex shape a and a half-plane (b) with φ ≤ margin. The plane's
/// normal must be a unit vector.
Manifold collide(const ConvexShape& a, const HalfPlane& plane, double margin);

}  // namespace lcprelax
