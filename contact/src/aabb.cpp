// Axis-aligned bounding boxes (see contact/aabb.hpp).
#include <lcprelax/contact/aabb.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcprelax {

Aabb aabb_of_points(const Vec2* points, int count, double margin) {
  Aabb box;
  if (count <= 0) return box;
  box.lower = box.upper = points[0];
  for (int i = 1; i < count; ++i) {
    box.lower = box.lower.cwiseMin(points[i]);
    box.upper = box.upper.cwiseMax(points[i]);
  }
  box.lower.array() -= margin;
  box.upper.array() += margin;
  return box;
}

Aabb aabb(const RigidBody& body, double margin) {
  Aabb box;
  const std::vector<Vec2>& v = body.shape.vertices;
  if (v.empty()) return box;
  const double c = std::cos(body.pose.z()), s = std::sin(body.pose.z());
  bool finite = body.pose.allFinite();
  box.lower = Vec2::Constant(std::numeric_limits<double>::infinity());
  box.upper = -box.lower;
  for (const Vec2& p : v) {
    const Vec2 r(c * p.x() - s * p.y(), s * p.x() + c * p.y());  // R(θ) p
    box.lower = box.lower.cwiseMin(r);
    box.upper = box.upper.cwiseMax(r);
    finite = finite && p.allFinite();
  }
  // cwiseMin/cwiseMax may drop NaN operands: mark a non-finite body explicitly.
  if (!finite) box.lower.x() = std::numeric_limits<double>::quiet_NaN();
  box.lower += body.pose.head<2>() - Vec2::Constant(margin);
  box.upper += body.pose.head<2>() + Vec2::Constant(margin);
  return box;
}

Aabb aabb(const Segment& segment, double margin) {
  const Vec2 p[2] = {segment.a, segment.b};
  return aabb_of_points(p, 2, margin);
}

bool box_near_half_plane(const Aabb& box, const HalfPlane& plane, double margin) {
  // The corner minimizing normal·p takes, per axis, the lower bound where the normal
  // component is ≥ 0 and the upper bound otherwise.
  const double x = plane.normal.x() >= 0.0 ? box.lower.x() : box.upper.x();
  const double y = plane.normal.y() >= 0.0 ? box.lower.y() : box.upper.y();
  return plane.normal.x() * x + plane.normal.y() * y - plane.offset <= margin;
}

}  // namespace lcprelax
