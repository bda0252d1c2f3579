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

// A point of the clipped incident edge (k, k+1) with its origin: label 0 or 1 is the
// edge's vertex k or k+1, label 2 + side the cut by the side line through the reference
// face's vertex i + side.
struct ClipPoint {
  Vec2 p = Vec2::Zero();
  int label = 0;
};

// Keeps the part of segment [in[0], in[1]] with dir·p ≤ bound; returns the number of
// output points (0 or 2; Sutherland–Hodgman on one edge). A cut point gets `cut_label`.
int clip(const ClipPoint in[2], ClipPoint out[2], const Vec2& dir, double bound, int cut_label) {
  const double d0 = dir.dot(in[0].p) - bound, d1 = dir.dot(in[1].p) - bound;
  int k = 0;
  if (d0 <= 0.0) out[k++] = in[0];
  if (d1 <= 0.0) out[k++] = in[1];
  if (d0 * d1 < 0.0) out[k++] = ClipPoint{in[0].p + (d0 / (d0 - d1)) * (in[1].p - in[0].p), cut_label};
  return k;
}

// Closest point of segment [q1, q2] to p; side: −1 interior, 0 / 1 clamped to q1 / q2.
Vec2 closest_on_segment(const Vec2& p, const Vec2& q1, const Vec2& q2, int& side) {
  const Vec2 e = q2 - q1;
  const double raw = (p - q1).dot(e) / e.squaredNorm();
  side = raw <= 0.0 ? 0 : (raw >= 1.0 ? 1 : -1);
  const double t = std::clamp(raw, 0.0, 1.0);
  return q1 + t * e;
}

// Exact closest points of two disjoint convex shapes by brute force over vertex–edge
// pairs (O(n·m), at most 12·12): in 2-D the distance is attained at a vertex of one shape
// and an edge of the other. Returns the distance; pa on a, pb on b; `feature` names the
// vertex and the edge (Kind::closest).
double closest_points(const ConvexShape& a, const ConvexShape& b, Vec2& pa, Vec2& pb, Contact::Feature& feature) {
  double best = std::numeric_limits<double>::infinity();
  int side = -1;
  for (int i = 0; i < a.count; ++i)
    for (int j = 0; j < b.count; ++j) {
      const Vec2 q = closest_on_segment(a.vertices[i], b.vertices[j], b.vertices[(j + 1) % b.count], side);
      const double d = (a.vertices[i] - q).norm();
      if (d < best) {
        best = d, pa = a.vertices[i], pb = q;
        feature.face_on_a = false, feature.edge = j, feature.vertex = i, feature.side = side;
      }
    }
  for (int j = 0; j < b.count; ++j)
    for (int i = 0; i < a.count; ++i) {
      const Vec2 q = closest_on_segment(b.vertices[j], a.vertices[i], a.vertices[(i + 1) % a.count], side);
      const double d = (b.vertices[j] - q).norm();
      if (d < best) {
        best = d, pa = q, pb = b.vertices[j];
        feature.face_on_a = true, feature.edge = i, feature.vertex = j, feature.side = side;
      }
    }
  feature.kind = Contact::Feature::Kind::closest;
  return best;
}

void add_point(Manifold& m, const Vec2& point, double gap, const Contact::Feature& feature) {
  m.points[m.count].point = point;
  m.points[m.count].gap = gap;
  m.points[m.count].feature = feature;
  ++m.count;
}

Contact::Feature make_feature(Contact::Feature::Kind kind, bool face_on_a, int edge, int vertex, int side) {
  Contact::Feature f;
  f.kind = kind;
  f.face_on_a = face_on_a;
  f.edge = edge;
  f.vertex = vertex;
  f.side = side;
  return f;
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
  const ClipPoint edge[2] = {ClipPoint{inc.vertices[k], 0}, ClipPoint{inc.vertices[(k + 1) % inc.count], 1}};

  // Clip to the slab t·r1 ≤ t·p ≤ t·r2 of the reference face.
  const Vec2 t = (r2 - r1).normalized();
  ClipPoint once[2], twice[2];
  int clipped = clip(edge, once, -t, -t.dot(r1), 2);
  if (clipped == 2) clipped = clip(once, twice, t, t.dot(r2), 3);

  using Kind = Contact::Feature::Kind;
  if (clipped == 2) {
    for (const ClipPoint& c : twice) {
      const double s = n.dot(c.p - r1);
      const Contact::Feature f =
          c.label < 2 ? make_feature(Kind::incident_vertex, ref_is_a, i, (k + c.label) % inc.count, -1)
                      : make_feature(Kind::clipped_edge, ref_is_a, i, k, c.label - 2);
      if (s <= margin) add_point(m, c.p - 0.5 * s * n, s, f);
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
    Contact::Feature f;
    const double d = closest_points(a, b, pa, pb, f);
    if (d > margin) return m;
    if (d > 0.0) m.normal = (pa - pb) / d;
    add_point(m, 0.5 * (pa + pb), d, f);
    return m;
  }
  int deepest = 0;
  for (int j = 1; j < inc.count; ++j)
    if (n.dot(inc.vertices[j]) < n.dot(inc.vertices[deepest])) deepest = j;
  const double s = n.dot(inc.vertices[deepest] - r1);
  add_point(m, inc.vertices[deepest] - 0.5 * s * n, s, make_feature(Kind::deepest_vertex, ref_is_a, i, deepest, -1));
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
  using Kind = Contact::Feature::Kind;
  if (first >= 0)
    add_point(m, a.vertices[first] - 0.5 * g_first * plane.normal, g_first, make_feature(Kind::plane_vertex, false, -1, first, -1));
  if (second >= 0)
    add_point(m, a.vertices[second] - 0.5 * g_second * plane.normal, g_second,
              make_feature(Kind::plane_vertex, false, -1, second, -1));
  return m;
}

}  // namespace lcprelax
