// Narrow phase: box on half-plane (flat and tilted), box on box, a triangle corner into a
// box, separation around the margin, polygon vs segment from both sides, and random pairs
// checked against an independent separating-axis / distance computation.
#include <lcprelax/contact/convex_shape.hpp>
#include <lcprelax/contact/narrow_phase.hpp>
#include <lcprelax/contact/polygon.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace lcprelax {
namespace {

constexpr double kMargin = 1e-2;

RigidBody box(double hw, double hh, const Vec3& pose) {
  RigidBody b;
  b.shape.vertices = {{-hw, -hh}, {hw, -hh}, {hw, hh}, {-hw, hh}};
  b.pose = pose;
  return b;
}

// Points of a manifold sorted by x (then y), for order-independent comparisons.
std::vector<ManifoldPoint> sorted_points(const Manifold& m) {
  std::vector<ManifoldPoint> p(m.points.begin(), m.points.begin() + m.count);
  std::sort(p.begin(), p.end(), [](const ManifoldPoint& l, const ManifoldPoint& r) {
    return l.point.x() != r.point.x() ? l.point.x() < r.point.x() : l.point.y() < r.point.y();
  });
  return p;
}

TEST(ContactNarrowPhase, BoxOnHalfPlaneAtSmallGaps) {
  const HalfPlane ground;  // y ≥ 0
  for (double gap : {-2e-3, -1e-7, 0.0, 1e-9, 3e-3, 9.99e-3}) {
    const Manifold m = collide(make_shape(box(0.5, 0.25, Vec3(0.3, 0.25 + gap, 0.0))), ground, kMargin);
    ASSERT_EQ(m.count, 2) << "gap " << gap;
    EXPECT_EQ(m.normal, Vec2(0, 1));
    const auto p = sorted_points(m);
    for (const ManifoldPoint& c : p) {
      EXPECT_NEAR(c.gap, gap, 1e-12);
      EXPECT_NEAR(c.point.y(), gap / 2, 1e-12);  // midway between the surfaces
    }
    EXPECT_NEAR(p[0].point.x(), -0.2, 1e-12);
    EXPECT_NEAR(p[1].point.x(), 0.8, 1e-12);
  }
  EXPECT_EQ(collide(make_shape(box(0.5, 0.25, Vec3(0.3, 0.25 + 1.01e-2, 0.0))), ground, kMargin).count, 0);
}

TEST(ContactNarrowPhase, TiltedBoxOnHalfPlaneTouchesWithOneCorner) {
  const HalfPlane ground;
  const double theta = 0.3, hw = 0.5, hh = 0.25;
  // Lowest corner (−hw, −hh) rotated: y = −hw sin θ − hh cos θ below the centre.
  const double depth = hw * std::sin(theta) + hh * std::cos(theta);
  const Manifold m = collide(make_shape(box(hw, hh, Vec3(0.0, depth - 1e-3, theta))), ground, kMargin);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].gap, -1e-3, 1e-12);
}

TEST(ContactNarrowPhase, BoxOnTiltedHalfPlane) {
  const double alpha = 0.4, hw = 0.3, hh = 0.2;
  const HalfPlane slope{Vec2(-std::sin(alpha), std::cos(alpha)), 0.7};
  const Vec2 tangent(std::cos(alpha), std::sin(alpha));
  const Vec2 on_plane = slope.offset * slope.normal + 1.5 * tangent;
  for (double gap : {-1e-3, 0.0, 4e-3}) {
    const Vec2 c = on_plane + (hh + gap) * slope.normal;
    const Manifold m = collide(make_shape(box(hw, hh, Vec3(c.x(), c.y(), alpha))), slope, kMargin);
    ASSERT_EQ(m.count, 2);
    EXPECT_NEAR((m.normal - slope.normal).norm(), 0.0, 1e-15);
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(m.points[k].gap, gap, 1e-12);
      EXPECT_NEAR(slope.normal.dot(m.points[k].point) - slope.offset, gap / 2, 1e-12);
    }
    // The two points are the two bottom corners, 2·hw apart along the slope.
    EXPECT_NEAR(std::abs(tangent.dot(m.points[0].point - m.points[1].point)), 2 * hw, 1e-12);
  }
}

TEST(ContactNarrowPhase, SmallBoxOnLargeBox) {
  const ConvexShape lower = make_shape(box(1.0, 0.5, Vec3(0, 0, 0)));
  for (double gap : {-1e-3, 0.0, 5e-3}) {
    const ConvexShape upper = make_shape(box(0.4, 0.25, Vec3(0.2, 0.75 + gap, 0)));
    const Manifold m = collide(upper, lower, kMargin);
    ASSERT_EQ(m.count, 2);
    EXPECT_EQ(m.normal, Vec2(0, 1));
    const auto p = sorted_points(m);
    EXPECT_NEAR(p[0].point.x(), -0.2, 1e-12);
    EXPECT_NEAR(p[1].point.x(), 0.6, 1e-12);
    for (const ManifoldPoint& c : p) {
      EXPECT_NEAR(c.gap, gap, 1e-12);
      EXPECT_NEAR(c.point.y(), 0.5 + gap / 2, 1e-12);
    }
    // Swapped arguments: the same points, the opposite normal.
    const Manifold r = collide(lower, upper, kMargin);
    ASSERT_EQ(r.count, 2);
    EXPECT_EQ(r.normal, Vec2(0, -1));
    const auto q = sorted_points(r);
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(q[k].point, p[k].point);
      EXPECT_EQ(q[k].gap, p[k].gap);
    }
  }
}

TEST(ContactNarrowPhase, EqualBoxesShareTheOverlapOfTheirFaces) {
  // Equal boxes offset sideways: both faces are candidates (a tie); the points span the
  // overlap x ∈ [−0.4, 0.5] either way, with one normal.
  const ConvexShape lower = make_shape(box(0.5, 0.5, Vec3(0, 0, 0)));
  const ConvexShape upper = make_shape(box(0.5, 0.5, Vec3(0.1, 1.0 + 2e-3, 0)));
  const Manifold m = collide(upper, lower, kMargin);
  ASSERT_EQ(m.count, 2);
  EXPECT_EQ(m.normal, Vec2(0, 1));
  const auto p = sorted_points(m);
  EXPECT_NEAR(p[0].point.x(), -0.4, 1e-12);
  EXPECT_NEAR(p[1].point.x(), 0.5, 1e-12);
  EXPECT_NEAR(p[0].gap, 2e-3, 1e-12);
  EXPECT_NEAR(p[1].gap, 2e-3, 1e-12);
}

TEST(ContactNarrowPhase, SlightlyRotatedBoxOnBoxHasOneNormal) {
  const ConvexShape lower = make_shape(box(0.5, 0.5, Vec3(0, 0, 0)));
  const double theta = 2e-3;
  // Upper box rotated by θ, lowest corner 1e-3 into the lower box.
  const double drop = 0.5 * std::cos(theta) + 0.5 * std::sin(theta);
  const ConvexShape upper = make_shape(box(0.5, 0.5, Vec3(0.0, 0.5 + drop - 1e-3, theta)));
  const Manifold m = collide(upper, lower, kMargin);
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.normal.norm(), 1.0, 1e-15);
  EXPECT_LT((m.normal - Vec2(0, 1)).norm(), 3e-3);
  const auto p = sorted_points(m);
  EXPECT_NEAR(std::min(p[0].gap, p[1].gap), -1e-3, 1e-6);
  EXPECT_LT(std::max(p[0].gap, p[1].gap), kMargin);
  EXPECT_GT(std::max(p[0].gap, p[1].gap), 0.0);  // the other corner is lifted by ≈ θ
}

TEST(ContactNarrowPhase, RotatedTriangleCornerIntoBox) {
  Polygon tri;
  tri.vertices = {{0.0, -0.5}, {0.3, 0.2}, {-0.3, 0.2}};
  const Polygon centred = recentred(tri);
  const double theta = 0.2;
  // Place the apex (vertex 0) 0.01 below the box's top face y = 0.5.
  const Vec2 apex_offset = to_world(Vec3(0, 0, theta), centred.vertices[0]);
  const Vec2 apex(0.15, 0.5 - 0.01);
  RigidBody t;
  t.shape = centred;
  t.pose = Vec3(apex.x() - apex_offset.x(), apex.y() - apex_offset.y(), theta);
  const ConvexShape triangle = make_shape(t);
  const ConvexShape block = make_shape(box(1.0, 0.5, Vec3(0, 0, 0)));

  const Manifold m = collide(triangle, block, kMargin);
  ASSERT_EQ(m.count, 1);
  EXPECT_EQ(m.normal, Vec2(0, 1));
  EXPECT_NEAR(m.points[0].gap, -0.01, 1e-12);
  EXPECT_NEAR(m.points[0].point.x(), apex.x(), 1e-12);
  EXPECT_NEAR(m.points[0].point.y(), apex.y() + 0.005, 1e-12);
}

TEST(ContactNarrowPhase, SeparationAroundTheMargin) {
  const ConvexShape lower = make_shape(box(0.5, 0.5, Vec3(0, 0, 0)));
  // Face to face: 0.02 apart → nothing; 0.005 apart → two near contacts with φ > 0.
  EXPECT_EQ(collide(make_shape(box(0.5, 0.5, Vec3(0.2, 1.02, 0))), lower, kMargin).count, 0);
  const Manifold near = collide(make_shape(box(0.5, 0.5, Vec3(0.2, 1.005, 0))), lower, kMargin);
  ASSERT_EQ(near.count, 2);
  EXPECT_NEAR(near.points[0].gap, 5e-3, 1e-12);
  EXPECT_NEAR(near.points[1].gap, 5e-3, 1e-12);
  // Corner to corner, 0.008 apart along both axes: the separating axes see 0.008 < margin,
  // but the true distance 0.0113 exceeds it → nothing.
  EXPECT_EQ(collide(make_shape(box(0.5, 0.5, Vec3(1.008, 1.008, 0))), lower, kMargin).count, 0);
  // 0.006 along both axes: distance 0.00849 → one contact along the diagonal.
  const Manifold corner = collide(make_shape(box(0.5, 0.5, Vec3(1.006, 1.006, 0))), lower, kMargin);
  ASSERT_EQ(corner.count, 1);
  EXPECT_NEAR(corner.points[0].gap, 0.006 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR((corner.normal - Vec2(1, 1).normalized()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((corner.points[0].point - Vec2(0.503, 0.503)).norm(), 0.0, 1e-12);
  // Zero margin: touching contacts only.
  EXPECT_EQ(collide(make_shape(box(0.5, 0.5, Vec3(0.2, 1.005, 0))), lower, 0.0).count, 0);
  EXPECT_EQ(collide(make_shape(box(0.5, 0.5, Vec3(0.2, 1.0, 0))), lower, 0.0).count, 2);
}

TEST(ContactNarrowPhase, PolygonAgainstSegmentFromBothSides) {
  for (const Segment& seg : {Segment{{-2, 0}, {2, 0}}, Segment{{2, 0}, {-2, 0}}}) {
    const ConvexShape s = make_shape(seg);
    for (double gap : {-3e-3, 0.0, 6e-3}) {
      const Manifold above = collide(make_shape(box(0.5, 0.25, Vec3(0.4, 0.25 + gap, 0))), s, kMargin);
      ASSERT_EQ(above.count, 2);
      EXPECT_EQ(above.normal, Vec2(0, 1));
      const Manifold below = collide(make_shape(box(0.5, 0.25, Vec3(0.4, -0.25 - gap, 0))), s, kMargin);
      ASSERT_EQ(below.count, 2);
      EXPECT_EQ(below.normal, Vec2(0, -1));
      const auto pa = sorted_points(above), pb = sorted_points(below);
      for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(pa[k].gap, gap, 1e-12);
        EXPECT_NEAR(pb[k].gap, gap, 1e-12);
        EXPECT_NEAR(pa[k].point.y(), gap / 2, 1e-12);
        EXPECT_NEAR(pb[k].point.y(), -gap / 2, 1e-12);
      }
      EXPECT_NEAR(pa[0].point.x(), -0.1, 1e-12);
      EXPECT_NEAR(pa[1].point.x(), 0.9, 1e-12);
    }
  }
  // A box overhanging the segment's end touches only where the segment is.
  const Manifold over = collide(make_shape(box(0.5, 0.25, Vec3(0.0, 0.25, 0))), make_shape(Segment{{-2, 0}, {0, 0}}),
                                kMargin);
  ASSERT_EQ(over.count, 2);
  const auto p = sorted_points(over);
  EXPECT_NEAR(p[0].point.x(), -0.5, 1e-12);
  EXPECT_NEAR(p[1].point.x(), 0.0, 1e-12);
  // The end of a vertical segment pokes 2 mm into the box's bottom face: one contact.
  const Manifold poke = collide(make_shape(box(0.5, 0.25, Vec3(0.1, 0.25 - 2e-3, 0))),
                                make_shape(Segment{{0, -1}, {0, 0}}), kMargin);
  ASSERT_EQ(poke.count, 1);
  EXPECT_EQ(poke.normal, Vec2(0, 1));
  EXPECT_NEAR(poke.points[0].gap, -2e-3, 1e-12);
}

// --- random pairs against an independent reference ---------------------------------------

RigidBody random_polygon(std::mt19937& rng, const Vec2& where) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> count(3, 12);
  const int n = count(rng);
  for (;;) {
    std::vector<double> angle(n);
    for (double& a : angle) a = 2 * M_PI * u(rng);
    std::sort(angle.begin(), angle.end());
    const double rx = 0.05 + 0.2 * u(rng), ry = 0.05 + 0.2 * u(rng);
    Polygon p;
    for (double a : angle) p.vertices.emplace_back(rx * std::cos(a), ry * std::sin(a));
    if (!polygon_validation_error(p).empty()) continue;  // too thin or nearly collinear: retry
    return make_body(p, 1.0, Vec3(where.x(), where.y(), 2 * M_PI * u(rng)));
  }
}

// Independent reference: SAT separation (exact overlap test) and brute-force distance.
double reference_distance(const ConvexShape& a, const ConvexShape& b, bool& overlap) {
  double sat = -std::numeric_limits<double>::infinity();
  for (const ConvexShape* s : {&a, &b}) {
    const ConvexShape& o = s == &a ? b : a;
    for (int i = 0; i < s->count; ++i) {
      double m = std::numeric_limits<double>::infinity();
      for (int j = 0; j < o.count; ++j) m = std::min(m, s->normals[i].dot(o.vertices[j] - s->vertices[i]));
      sat = std::max(sat, m);
    }
  }
  overlap = sat < 0;
  double d = std::numeric_limits<double>::infinity();
  for (const ConvexShape* s : {&a, &b}) {
    const ConvexShape& o = s == &a ? b : a;
    for (int i = 0; i < s->count; ++i)
      for (int j = 0; j < o.count; ++j) {
        const Vec2 q1 = o.vertices[j], e = o.vertices[(j + 1) % o.count] - q1;
        const double t = std::clamp((s->vertices[i] - q1).dot(e) / e.squaredNorm(), 0.0, 1.0);
        d = std::min(d, (s->vertices[i] - q1 - t * e).norm());
      }
  }
  return d;
}

TEST(ContactNarrowPhase, RandomPairsAgreeWithReference) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.35, 0.35);
  int overlapping = 0, near = 0, far = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const ConvexShape a = make_shape(random_polygon(rng, Vec2(0, 0)));
    const ConvexShape b = make_shape(random_polygon(rng, Vec2(u(rng), u(rng))));
    bool overlap = false;
    const double distance = reference_distance(a, b, overlap);
    const Manifold m = collide(a, b, kMargin);
    const Manifold r = collide(b, a, kMargin);
    SCOPED_TRACE(trial);

    // Symmetry: the same points and gaps, opposite normals.
    ASSERT_EQ(m.count, r.count);
    if (m.count > 0) {
      EXPECT_EQ(m.normal, Vec2(-r.normal));
    }
    const auto pm = sorted_points(m), pr = sorted_points(r);
    for (int k = 0; k < m.count; ++k) {
      EXPECT_EQ(pm[k].point, pr[k].point);
      EXPECT_EQ(pm[k].gap, pr[k].gap);
    }

    EXPECT_NEAR(m.normal.norm(), 1.0, 1e-12);
    for (int k = 0; k < m.count; ++k) {
      EXPECT_LE(m.points[k].gap, kMargin);
      if (!overlap) {
        EXPECT_GE(m.points[k].gap, distance - 1e-12);  // φ bounds the distance from above
      }
    }
    if (overlap) {
      ++overlapping;
      ASSERT_GE(m.count, 1);
      double deepest = std::numeric_limits<double>::infinity();
      for (int k = 0; k < m.count; ++k) deepest = std::min(deepest, m.points[k].gap);
      EXPECT_LT(deepest, 0.0);
      // Moving a along the normal by the deepest penetration separates the shapes (up to
      // the reference-face tie band).
      ConvexShape moved = a;
      for (int i = 0; i < moved.count; ++i) moved.vertices[i] += (-deepest + 1e-4) * m.normal;
      bool still = false;
      reference_distance(moved, b, still);
      EXPECT_FALSE(still);
    } else if (distance > kMargin) {
      ++far;
      EXPECT_EQ(m.count, 0);
    } else {
      ++near;
    }
  }
  // The sampling covers all three regimes.
  EXPECT_GT(overlapping, 1000);
  EXPECT_GT(near, 100);
  EXPECT_GT(far, 1000);
}

}  // namespace
}  // namespace lcprelax
