// Narrow phase: separating axes + reference/incident edge clipping (see
// contact/narrow_phase.hpp for the method, conventions and tolerances).
#include <lcprelax/contact/narrow_phase.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcprelax {
namespace {

constexpr double kMergeTolerance = 1e-9;  // relative distance below which two points merge

struct Axis {
  double separation = -std::numeric_limits<double>::infinity();
  int edge = 0;
};

// Largest separation of `other` from the faces of `ref`: max_i min_j n_i·(w_j − v_i).
// Stops early once a face separates by more than the margin (no contacts then).
Axis max_separation(const ConvexShape& ref, const ConvexShape& other, double margin) {
  Axis best;
  for (int i = 0; i < ref.count; ++i) {
    const Vec2& n = ref.normals[i];
    const double offset = n.dot(ref.vertices[i]);
    double s = std::numeric_limits<double>::infinity();
    for (int j = 0; j < other.count; ++j) s = std::min(s, n.dot(other.vertices[j]) - offset);
    if (s > best.separation) {
      best.separation = s;
      best.edge = i;
      if (s > margin) break;
    }
  }
  return best;
}

// Geometry-only tie-break between two candidate reference faces: true when face (na, pa)
// comes first in the order (n_y, n_x, p_x, p_y).
bool face_precedes(const Vec2& na, const Vec2& pa, const Vec2& nb, const Vec2& pb) {
  if (na.y() != nb.y()) return na.y() < nb.y();
  if (na.x() != nb.x()) return na.x() < nb.x();
  if (pa.x() != pb.x()) return pa.x() < pb.x();
  return pa.y() <= pb.y();
}

// Keeps the part of segment [in[0], in[1]] with dir·p ≤ bound; returns the number of
// output points (0 or 2; Sutherland–Hodgman on one edge).
int clip(const Vec2 in[2], Vec2 out[2], const Vec2& dir, double bound) {
  const double d0 = dir.dot(in[0]) - bound, d1 = dir.dot(in[1]) - bound;
  int k = 0;
  if (d0 <= 0.0) out[k++] = in[0];
  if (d1 <= 0.0) out[k++] = in[1];
  if (d0 * d1 < 0.0) out[k++] = in[0] + (d0 / (d0 - d1)) * (in[1] - in[0]);
  return k;
}

// Closest point of segment [q1, q2] to p.
Vec2 closest_on_segment(const Vec2& p, const Vec2& q1, const Vec2& q2) {
  const Vec2 e = q2 - q1;
  const double t = std::clamp((p - q1).dot(e) / e.squaredNorm(), 0.0, 1.0);
  return q1 + t * e;
}

// Exact closest points of two disjoint convex shapes by brute force over vertex–edge
// pairs (O(n·m), at most 12·12): in 2-D the distance is attained at a vertex of one shape
// and an edge of the other. Returns the distance; pa on a, pb on b.
double closest_points(const ConvexShape& a, const ConvexShape& b, Vec2& pa, Vec2& pb) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < a.count; ++i)
    for (int j = 0; j < b.count; ++j) {
      const Vec2 q = closest_on_segment(a.vertices[i], b.vertices[j], b.vertices[(j + 1) % b.count]);
      const double d = (a.vertices[i] - q).norm();
      if (d < best) best = d, pa = a.vertices[i], pb = q;
    }
  for (int j = 0; j < b.count; ++j)
    for (int i = 0; i < a.count; ++i) {
      const Vec2 q = closest_on_segment(b.vertices[j], a.vertices[i], a.vertices[(i + 1) % a.count]);
      const double d = (b.vertices[j] - q).norm();
      if (d < best) best = d, pa = q, pb = b.vertices[j];
    }
  return best;
}

void add_point(Manifold& m, const Vec2& point, double gap) {
  m.points[m.count].point = point;
  m.points[m.count].gap = gap;
  ++m.count;
}

}  // namespace

Manifold collide(const ConvexShape& a, const ConvexShape& b, double margin) {
  Manifold m;
  const Axis axis_a = max_separation(a, b, margin);
  if (axis_a.separation > margin) return m;
  const Axis axis_b = max_separation(b, a, margin);
  if (axis_b.separation > margin) return m;

  const double scale = std::min(a.radius, b.radius);
  const double tie = kReferenceFaceTolerance * scale;
  bool ref_is_a;
  if (axis_a.separation > axis_b.separation + tie) ref_is_a = true;
  else if (axis_b.separation > axis_a.separation + tie) ref_is_a = false;
  else
    ref_is_a = face_precedes(a.normals[axis_a.edge], a.vertices[axis_a.edge], b.normals[axis_b.edge],
                             b.vertices[axis_b.edge]);

  const ConvexShape& ref = ref_is_a ? a : b;
  const ConvexShape& inc = ref_is_a ? b : a;
  const int i = ref_is_a ? axis_a.edge : axis_b.edge;
  const Vec2 n = ref.normals[i];  // out of the reference shape
  m.normal = ref_is_a ? Vec2(-n) : n;
  const Vec2 r1 = ref.vertices[i];
  const Vec2 r2 = ref.vertices[(i + 1) % ref.count];

  // Incident edge: the edge of `inc` whose normal is most anti-parallel to n.
  int k = 0;
  double most = std::numeric_limits<double>::infinity();
  for (int j = 0; j < inc.count; ++j) {
    const double d = inc.normals[j].dot(n);
    if (d < most) most = d, k = j;
  }
  const Vec2 edge[2] = {inc.vertices[k], inc.vertices[(k + 1) % inc.count]};

  // Clip to the slab t·r1 ≤ t·p ≤ t·r2 of the reference face.
  const Vec2 t = (r2 - r1).normalized();
  Vec2 once[2], twice[2];
  int clipped = clip(edge, once, -t, -t.dot(r1));
  if (clipped == 2) clipped = clip(once, twice, t, t.dot(r2));

  if (clipped == 2) {
    for (const Vec2& p : twice) {
      const double s = n.dot(p - r1);
      if (s <= margin) add_point(m, p - 0.5 * s * n, s);
    }
    if (m.count == 2 && (m.points[0].point - m.points[1].point).norm() <= kMergeTolerance * scale) {
      if (m.points[1].gap < m.points[0].gap) m.points[0] = m.points[1];
      m.count = 1;
    }
    return m;
  }

  // The incident edge misses the slab.
  const double separation = ref_is_a ? axis_a.separation : axis_b.separation;
  if (separation > 0.0) {
    Vec2 pa = Vec2::Zero(), pb = Vec2::Zero();
    const double d = closest_points(a, b, pa, pb);
    if (d > margin) return m;
    if (d > 0.0) m.normal = (pa - pb) / d;
    add_point(m, 0.5 * (pa + pb), d);
    return m;
  }
  int deepest = 0;
  for (int j = 1; j < inc.count; ++j)
    if (n.dot(inc.vertices[j]) < n.dot(inc.vertices[deepest])) deepest = j;
  const double s = n.dot(inc.vertices[deepest] - r1);
  add_point(m, inc.vertices[deepest] - 0.5 * s * n, s);
  return m;
}

Manifold collide(const ConvexShape& a, const HalfPlane& plane, double margin) {
  Manifold m;
  m.normal = plane.normal;
  int first = -1, second = -1;
  double g_first = 0.0, g_second = 0.0;
  for (int i = 0; i < a.count; ++i) {
    const double g = plane.normal.dot(a.vertices[i]) - plane.offset;
    if (g > margin) continue;
    if (first < 0 || g < g_first) {
      second = first, g_second = g_first;
      first = i, g_first = g;
    } else if (second < 0 || g < g_second) {
      second = i, g_second = g;
    }
  }
  if (first >= 0) add_point(m, a.vertices[first] - 0.5 * g_first * plane.normal, g_first);
  if (second >= 0) add_point(m, a.vertices[second] - 0.5 * g_second * plane.normal, g_second);
  return m;
}

}  // namespace lcprelax
