#pragma once
// Axis-aligned bounding boxes of bodies and static shapes (broad-phase input).
//
// Conventions: world frame, metres. A box is [lower, upper] (closed); `margin` (≥ 0, m)
// expands it on every side. Half-planes are unbounded and have no box: a body box is
// tested against a half-plane directly (box_near_half_plane). Boxes that touch count as
// overlapping, so a pair at exactly the margin is still a candidate.
#include <lcprelax/world/world.hpp>

namespace lcprelax {

struct Aabb {
  Vec2 lower = Vec2::Zero();  ///< (min x, min y), m
  Vec2 upper = Vec2::Zero();  ///< (max x, max y), m

  Vec2 extent() const { return upper - lower; }
  bool is_finite() const { return lower.allFinite() && upper.allFinite(); }
};

/// True when the closed boxes intersect.
inline bool overlaps(const Aabb& a, const Aabb& b) {
  return a.lower.x() <= b.upper.x() && b.lower.x() <= a.upper.x() && a.lower.y() <= b.upper.y() &&
         b.lower.y() <= a.upper.y();
}

/// Box of `count` points, expanded by `margin`.
Aabb aabb_of_points(const Vec2* points, int count, double margin);

/// Box of a body's world vertices, expanded by `margin`.
Aabb aabb(const RigidBody& body, double margin);

/// Box of a segment, expanded by `margin`.
Aabb aabb(const Segment& segment, double margin);

/// True when some point of `box` lies within `margin` of the solid side of `plane`, i.e.
/// min over the box corners of normal·p − offset ≤ margin (conservative for any shape
/// inside the box).
bool box_near_half_plane(const Aabb& box, const HalfPlane& plane, double margin);

}  // namespace lcprelax
