#pragma once
// A contact point recomputed from its recorded features (Contact::Feature, world.hpp): the
// narrow phase's formulas (narrow_phase.hpp) with the choice of features held fixed, as
// functions of the world-frame vertices of the two shapes, so that they can be evaluated
// at perturbed geometry and differentiated (the Scalar may be an automatic-differentiation
// type such as Eigen's AutoDiffScalar).
//
// Conventions (world.hpp, convex_shape.hpp): shape a's and shape b's vertex loops are
// counter-clockwise (a segment is the two-vertex loop (a, b)); edge e runs from v_e to
// v_{e+1 mod count} with outward normal n_e = (e_y, −e_x)/|e|. The contact normal points
// from b to a; the gap φ is the signed distance along it (m); the point lies midway between
// the surfaces. With r1, r2 the reference face's vertices (edge `edge` of the face shape),
// n its outward normal and n_c = −n when the face is a's, else n:
//   incident_vertex, deepest_vertex (w = vertex `vertex` of the other shape):
//       φ = n·(w − r1),  p = w − ½ φ n,  normal n_c;
//   clipped_edge (incident edge w0 = v_vertex, w1 = v_vertex+1; side line through
//       r = r1 (side 0, kept half t·(r1 − p) ≤ 0) or r = r2 (side 1, t·(p − r2) ≤ 0),
//       t = (r2 − r1)/|r2 − r1|): w = w0 + d0/(d0 − d1) (w1 − w0) with d0, d1 the signed
//       distances of w0, w1 to that line; then as incident_vertex;
//   closest (separated; q = vertex `vertex` of the non-face shape, c its closest point on
//       edge (q1, q2) = `edge` of the face shape: q1 + τ (q2 − q1), τ = (q − q1)·e/|e|²
//       for side −1, q1 for side 0, q2 for side 1): with pa on a and pb on b,
//       φ = |pa − pb|,  normal (pa − pb)/φ,  p = ½ (pa + pb);
//   plane_vertex (half-plane with normal m and offset o, w = vertex of a):
//       φ = m·w − o,  p = w − ½ φ m,  normal m.
// The half-plane normal is used as given (not normalized), so that derivatives with respect
// to its two components are those of these formulas. Evaluated in the narrow phase's order
// of operations: at the geometry the narrow phase saw, the values agree with it to rounding
// (a clipped_edge cut on side 1 of an edge already cut on side 0 is interpolated along the
// whole edge here, along the cut part there).
#include <lcprelax/world/world.hpp>

#include <Eigen/Core>

#include <cmath>
#include <string>
#include <vector>

namespace lcprelax {

template <class Scalar>
using Vec2Of = Eigen::Matrix<Scalar, 2, 1>;

template <class Scalar>
struct FeatureGeometry {
  Vec2Of<Scalar> point;   ///< world (m)
  Vec2Of<Scalar> normal;  ///< from b to a
  Scalar gap;             ///< φ (m)
};

namespace feature_detail {

template <class Scalar>
Scalar length(const Vec2Of<Scalar>& e) {
  using std::sqrt;
  return sqrt(e.x() * e.x() + e.y() * e.y());
}

// Outward unit normal of edge e of a loop of `count` vertices.
template <class Scalar>
Vec2Of<Scalar> edge_normal(const Vec2Of<Scalar>* v, int count, int e) {
  const Vec2Of<Scalar> d = v[(e + 1) % count] - v[e];
  const Scalar len = length<Scalar>(d);
  return Vec2Of<Scalar>(d.y() / len, -d.x() / len);
}

template <class Scalar>
FeatureGeometry<Scalar> below_face(const Vec2Of<Scalar>& w, const Vec2Of<Scalar>& r1, const Vec2Of<Scalar>& n,
                                   bool face_on_a) {
  FeatureGeometry<Scalar> g;
  g.gap = n.dot(w - r1);
  g.point = w - (0.5 * g.gap) * n;
  g.normal = face_on_a ? Vec2Of<Scalar>(-n) : n;
  return g;
}

}  // namespace feature_detail

/// (point, normal, gap) of a contact between two convex vertex loops a (count na) and b
/// (count nb) from its feature (formulas above). The feature must be a polygon–polygon or
/// polygon–segment kind with indices in range (refresh_contacts checks).
template <class Scalar>
FeatureGeometry<Scalar> feature_geometry(const Contact::Feature& f, const Vec2Of<Scalar>* a, int na,
                                         const Vec2Of<Scalar>* b, int nb) {
  using Kind = Contact::Feature::Kind;
  const Vec2Of<Scalar>* face = f.face_on_a ? a : b;
  const Vec2Of<Scalar>* other = f.face_on_a ? b : a;
  const int nf = f.face_on_a ? na : nb, no = f.face_on_a ? nb : na;
  const Vec2Of<Scalar>& r1 = face[f.edge];
  const Vec2Of<Scalar>& r2 = face[(f.edge + 1) % nf];
  if (f.kind == Kind::closest) {
    const Vec2Of<Scalar>& q = other[f.vertex];
    Vec2Of<Scalar> c;
    if (f.side == 0) {
      c = r1;
    } else if (f.side == 1) {
      c = r2;
    } else {
      const Vec2Of<Scalar> e = r2 - r1;
      const Scalar tau = (q - r1).dot(e) / e.squaredNorm();
      c = r1 + tau * e;
    }
    const Vec2Of<Scalar> pa = f.face_on_a ? c : q, pb = f.face_on_a ? q : c;
    FeatureGeometry<Scalar> g;
    g.gap = feature_detail::length<Scalar>(Vec2Of<Scalar>(q - c));
    g.normal = (pa - pb) / g.gap;
    g.point = 0.5 * (pa + pb);
    return g;
  }
  const Vec2Of<Scalar> n = feature_detail::edge_normal<Scalar>(face, nf, f.edge);
  if (f.kind == Kind::clipped_edge) {
    const Vec2Of<Scalar> e = r2 - r1;
    const Vec2Of<Scalar> t = e / feature_detail::length<Scalar>(e);
    const Vec2Of<Scalar>& w0 = other[f.vertex];
    const Vec2Of<Scalar>& w1 = other[(f.vertex + 1) % no];
    Scalar d0, d1;
    if (f.side == 0) {
      const Vec2Of<Scalar> dir = -t;
      const Scalar bound = -t.dot(r1);
      d0 = dir.dot(w0) - bound, d1 = dir.dot(w1) - bound;
    } else {
      const Scalar bound = t.dot(r2);
      d0 = t.dot(w0) - bound, d1 = t.dot(w1) - bound;
    }
    const Vec2Of<Scalar> w = w0 + (d0 / (d0 - d1)) * (w1 - w0);
    return feature_detail::below_face<Scalar>(w, r1, n, f.face_on_a);
  }
  return feature_detail::below_face<Scalar>(other[f.vertex], r1, n, f.face_on_a);
}

/// (point, normal, gap) of a plane_vertex contact of loop a with the half-plane
/// {p : m·p ≥ offset} (m used as given).
template <class Scalar>
FeatureGeometry<Scalar> feature_geometry(const Contact::Feature& f, const Vec2Of<Scalar>* a,
                                         const Vec2Of<Scalar>& plane_normal, const Scalar& offset) {
  const Vec2Of<Scalar>& w = a[f.vertex];
  FeatureGeometry<Scalar> g;
  g.gap = plane_normal.dot(w) - offset;
  g.point = w - (0.5 * g.gap) * plane_normal;
  g.normal = plane_normal;
  return g;
}

/// Empty when `contact`'s feature can be evaluated in `world`, else what is wrong (kind
/// none, a kind that does not fit its shapes, an index out of range, a body or static
/// shape that does not exist).
std::string contact_feature_error(const World& world, const Contact& contact);

/// "contacts[i]: ..." when contact i's feature cannot be evaluated in `world`
/// (kind none, a kind that does not fit its shapes, an index out of range, a body or
/// static shape that does not exist); empty when every contact can be recomputed.
std::string contact_features_error(const World& world, const std::vector<Contact>& contacts);

/// Recomputes point, normal and gap of every contact from its feature at the world's
/// current poses and shapes (μ and the rest are kept): the contact list of find_contacts
/// with the features held fixed. Throws InputError as contact_features_error describes.
void refresh_contacts(const World& world, std::vector<Contact>& contacts);

}  // namespace lcprelax
