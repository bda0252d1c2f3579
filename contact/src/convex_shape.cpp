// World-frame convex shapes (see contact/convex_shape.hpp).
#include <lcprelax/contact/convex_shape.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lcprelax {
namespace {

// Outward normals of the edges of a counter-clockwise vertex loop; radius about centre.
void finish(ConvexShape& s) {
  s.radius = 0.0;
  for (int i = 0; i < s.count; ++i) {
    const Vec2 e = s.vertices[(i + 1) % s.count] - s.vertices[i];
    s.normals[i] = Vec2(e.y(), -e.x()) / e.norm();
    s.radius = std::max(s.radius, (s.vertices[i] - s.centre).norm());
  }
}

}  // namespace

ConvexShape make_shape(const RigidBody& body) {
  const int n = static_cast<int>(body.shape.vertices.size());
  if (n < kMinPolygonVertices || n > kMaxPolygonVertices) {
    std::ostringstream os;
    os << "body polygon has " << n << " vertices, expected " << kMinPolygonVertices << ".."
       << kMaxPolygonVertices;
    throw InputError(os.str());
  }
  ConvexShape s;
  s.count = n;
  const double c = std::cos(body.pose.z()), sn = std::sin(body.pose.z());
  s.centre = body.pose.head<2>();
  for (int i = 0; i < n; ++i) {
    const Vec2& p = body.shape.vertices[i];
    s.vertices[i] = Vec2(s.centre.x() + c * p.x() - sn * p.y(), s.centre.y() + sn * p.x() + c * p.y());
  }
  finish(s);
  return s;
}

ConvexShape make_shape(const Segment& segment) {
  if (!segment.a.allFinite() || !segment.b.allFinite() || !((segment.b - segment.a).norm() > 0.0))
    throw InputError("segment must have finite, distinct end points");
  ConvexShape s;
  s.count = 2;
  s.vertices[0] = segment.a;
  s.vertices[1] = segment.b;
  s.centre = 0.5 * (segment.a + segment.b);
  finish(s);
  return s;
}

}  // namespace lcprelax
