// Convex-polygon validation and mass properties (scenes/polygon.hpp).
#include <lcprelax/scenes/polygon.hpp>
#include <lcprelax/sparse/errors.hpp>

#include <cmath>
#include <string>

namespace lcprelax {
namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

constexpr double kPi = 3.14159265358979323846;

}  // namespace

PolygonProperties polygon_properties(const std::vector<Vec2>& vertices) {
  PolygonProperties p;
  const std::size_t n = vertices.size();
  if (n < 3) return p;
  // Work relative to the vertex mean o: C = o + C', J is translation-invariant about C.
  Vec2 o = Vec2::Zero();
  for (const Vec2& v : vertices) o += v;
  o /= static_cast<double>(n);
  double twice_area = 0.0, j0 = 0.0;
  Vec2 c6 = Vec2::Zero();  // 6·A·C'
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = vertices[i] - o, b = vertices[(i + 1) % n] - o;
    const double ci = cross(a, b);  // twice the signed area of triangle (o, a, b)
    twice_area += ci;
    c6 += ci * (a + b);
    j0 += ci * (a.squaredNorm() + a.dot(b) + b.squaredNorm());
  }
  p.area = 0.5 * twice_area;
  if (p.area == 0.0) return p;
  const Vec2 c_rel = c6 / (3.0 * twice_area);  // C' = Σ c_i (a + b) / (6A)
  p.centroid = o + c_rel;
  p.polar_moment = j0 / 12.0 - p.area * c_rel.squaredNorm();  // parallel-axis theorem
  return p;
}

void check_convex_polygon(const std::vector<Vec2>& vertices, const std::string& field) {
  const std::size_t n = vertices.size();
  if (n < 3 || n > 12)
    throw InputError(field + ": a polygon needs 3 to 12 vertices, got " + std::to_string(n));
  for (std::size_t i = 0; i < n; ++i)
    if (!vertices[i].allFinite())
      throw InputError(field + "[" + std::to_string(i) + "]: not finite");
  int left = 0, right = 0;
  double turning = 0.0;  // total exterior angle: 2π for a convex polygon, more for a star
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e0 = vertices[(i + 1) % n] - vertices[i];
    const Vec2 e1 = vertices[(i + 2) % n] - vertices[(i + 1) % n];
    const double c = cross(e0, e1);
    if (!(std::abs(c) > 1e-12 * e0.norm() * e1.norm()))
      throw InputError(field + ": collinear or repeated vertices at index " +
                       std::to_string((i + 1) % n) + " (polygon must be strictly convex)");
    (c > 0.0 ? left : right) += 1;
    turning += std::atan2(c, e0.dot(e1));
  }
  if (left > 0 && right > 0) throw InputError(field + ": polygon is not convex");
  if (std::abs(std::abs(turning) - 2.0 * kPi) > 1e-6)
    throw InputError(field + ": polygon is not convex (it winds around more than once)");
  if (right > 0) throw InputError(field + ": polygon is clockwise (vertices must be counter-clockwise)");
}

Vec2 recentre_polygon(std::vector<Vec2>& vertices) {
  const Vec2 c = polygon_properties(vertices).centroid;
  double size = 0.0;
  for (const Vec2& v : vertices) size = std::max(size, v.lpNorm<Eigen::Infinity>());
  if (c.lpNorm<Eigen::Infinity>() <= 1e-12 * size) return Vec2::Zero();
  for (Vec2& v : vertices) v -= c;
  return c;
}

RigidBody polygon_body(const std::vector<Vec2>& vertices, double density, const Vec3& pose) {
  check_convex_polygon(vertices, "vertices");
  if (!std::isfinite(density) || !(density > 0.0))
    throw InputError("density: must be finite and > 0");
  if (!pose.allFinite()) throw InputError("pose: not finite");
  RigidBody body;
  body.shape.vertices = vertices;
  const PolygonProperties p = polygon_properties(vertices);  // before recentring: J about C
  const Vec2 c = recentre_polygon(body.shape.vertices);
  const double cs = std::cos(pose.z()), sn = std::sin(pose.z());
  body.pose = Vec3(pose.x() + cs * c.x() - sn * c.y(), pose.y() + sn * c.x() + cs * c.y(), pose.z());
  body.mass = density * p.area;
  body.inertia = density * p.polar_moment;
  return body;
}

}  // namespace lcprelax
