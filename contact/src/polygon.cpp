// Polygon validation and mass properties (see contact/polygon.hpp for the formulas).
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/math_constants.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lcprelax {
namespace {

constexpr double kRelativeTolerance = 1e-9;
constexpr double kCentredTolerance = 1e-12;  // recentre(): |C| ≤ 1e-12·L counts as 0

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

void require_valid(const Polygon& polygon) {
  const std::string error = polygon_validation_error(polygon);
  if (!error.empty()) throw InputError("invalid polygon: " + error);
}

}  // namespace

std::string polygon_validation_error(const Polygon& polygon) {
  const std::vector<Vec2>& v = polygon.vertices;
  const int n = static_cast<int>(v.size());
  std::ostringstream os;
  if (n < kMinPolygonVertices) {
    os << "polygon has " << n << " vertices, at least " << kMinPolygonVertices << " are needed";
    return os.str();
  }
  if (n > kMaxPolygonVertices) {
    os << "polygon has " << n << " vertices, at most " << kMaxPolygonVertices << " are allowed";
    return os.str();
  }
  for (int i = 0; i < n; ++i)
    if (!v[i].allFinite()) {
      os << "vertex " << i << " is not finite";
      return os.str();
    }

  for (int i = 0; i < n; ++i)
    if (v[i].cwiseAbs().maxCoeff() > kMaxPolygonCoordinate) {
      os << "vertex " << i << " = (" << v[i].x() << ", " << v[i].y() << ") is outside ±" << kMaxPolygonCoordinate
         << " m";
      return os.str();
    }
  double size = 0.0;  // L: largest distance from the first vertex (hypot: no underflow)
  for (int i = 1; i < n; ++i) size = std::max(size, std::hypot(v[i].x() - v[0].x(), v[i].y() - v[0].y()));
  if (!(size > 0.0)) return "all vertices coincide";
  if (size < kMinPolygonSize) {
    os << "polygon is " << size << " m across, smaller than " << kMinPolygonSize << " m";
    return os.str();
  }

  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    if ((v[j] - v[i]).norm() <= kRelativeTolerance * size) {
      os << "vertices " << i << " and " << j << " coincide";
      return os.str();
    }
  }

  double twice_area = 0.0;
  for (int i = 1; i + 1 < n; ++i) twice_area += cross(v[i] - v[0], v[i + 1] - v[0]);
  if (std::abs(0.5 * twice_area) <= kRelativeTolerance * size * size) return "polygon has zero area";
  if (twice_area < 0.0) return "vertices are clockwise";

  double turning = 0.0;  // total exterior angle: 2π for a simple convex polygon
  for (int k = 0; k < n; ++k) {
    const Vec2 e_in = v[k] - v[(k + n - 1) % n];
    const Vec2 e_out = v[(k + 1) % n] - v[k];
    const double c = cross(e_in, e_out);
    if (!(c > kRelativeTolerance * e_in.norm() * e_out.norm())) {
      os << "vertex " << k << " makes the polygon non-convex";
      return os.str();
    }
    turning += std::atan2(c, e_in.dot(e_out));
  }
  if (turning > 3.0 * kPi) return "polygon winds more than once (self-intersecting)";
  return {};
}

MassProperties mass_properties(const Polygon& polygon, double density) {
  require_valid(polygon);
  if (!(density > 0.0) || !std::isfinite(density)) {
    std::ostringstream os;
    os << "density = " << density << " must be finite and > 0";
    throw InputError(os.str());
  }
  const std::vector<Vec2>& v = polygon.vertices;
  const int n = static_cast<int>(v.size());
  // Sums over the fan (v0, v_i, v_{i+1}) in coordinates relative to v0 (p_0 = 0, so the
  // two fan triangles touching v0 with a zero edge contribute nothing).
  double twice_area = 0.0, j_sum = 0.0;
  Vec2 c_sum = Vec2::Zero();
  for (int i = 0; i < n; ++i) {
    const Vec2 p = v[i] - v[0];
    const Vec2 q = v[(i + 1) % n] - v[0];
    const double c = cross(p, q);
    twice_area += c;
    c_sum += c * (p + q);
    j_sum += c * (p.dot(p) + p.dot(q) + q.dot(q));
  }
  MassProperties m;
  m.area = 0.5 * twice_area;
  const Vec2 centroid_rel = c_sum / (6.0 * m.area);
  m.centroid = v[0] + centroid_rel;
  m.mass = density * m.area;
  const double polar_about_v0 = density * j_sum / 12.0;
  m.inertia = polar_about_v0 - m.mass * centroid_rel.squaredNorm();
  if (!std::isfinite(m.mass) || !std::isfinite(m.inertia) || !(m.mass > 0.0) || !(m.inertia > 0.0)) {
    std::ostringstream os;
    os << "density = " << density << " gives mass " << m.mass << " and inertia " << m.inertia
       << " (area " << m.area << " m²): outside the range of doubles";
    throw InputError(os.str());
  }
  return m;
}

Vec2 recentre(Polygon& polygon) {
  const Vec2 c = mass_properties(polygon, 1.0).centroid;
  std::vector<Vec2>& v = polygon.vertices;
  double size = 0.0;  // L, as in polygon_validation_error
  for (const Vec2& p : v) size = std::max(size, (p - v[0]).norm());
  if (c.norm() <= kCentredTolerance * size) return Vec2::Zero();
  for (Vec2& p : v) p -= c;
  return c;
}

Polygon recentred(const Polygon& polygon) {
  Polygon out = polygon;
  recentre(out);
  return out;
}

RigidBody make_body(const Polygon& polygon, double density, const Vec3& pose) {
  RigidBody body;
  const MassProperties m = mass_properties(polygon, density);
  body.shape = polygon;
  recentre(body.shape);
  body.mass = m.mass;
  body.inertia = m.inertia;
  body.pose = pose;
  return body;
}

std::vector<Vec2> world_vertices(const RigidBody& body) {
  const double c = std::cos(body.pose.z()), s = std::sin(body.pose.z());
  const Vec2 t = body.pose.head<2>();
  std::vector<Vec2> out;
  out.reserve(body.shape.vertices.size());
  for (const Vec2& p : body.shape.vertices) out.emplace_back(t.x() + c * p.x() - s * p.y(), t.y() + s * p.x() + c * p.y());
  return out;
}

}  // namespace lcprelax
