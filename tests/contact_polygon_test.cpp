// Polygon geometry: validation messages, mass properties against closed forms (square,
// rectangle far from the origin, right and general triangles), recentring (the returned
// shift, bit-for-bit centred polygons), world vertices and bounding boxes.
#include <lcprelax/contact/aabb.hpp>
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lcprelax {
namespace {

Polygon poly(std::initializer_list<Vec2> v) { return Polygon{std::vector<Vec2>(v)}; }

Polygon unit_square() { return poly({{0, 0}, {1, 0}, {1, 1}, {0, 1}}); }

Polygon regular(int n, double r) {
  Polygon p;
  for (int i = 0; i < n; ++i) p.vertices.emplace_back(r * std::cos(2 * M_PI * i / n), r * std::sin(2 * M_PI * i / n));
  return p;
}

TEST(ContactPolygon, ValidPolygonsPass) {
  EXPECT_EQ(polygon_validation_error(unit_square()), "");
  EXPECT_EQ(polygon_validation_error(poly({{0, 0}, {3, 0}, {0, 4}})), "");
  EXPECT_EQ(polygon_validation_error(regular(12, 0.1)), "");
  EXPECT_EQ(polygon_validation_error(regular(3, 1e-4)), "");  // tolerances are relative
}

TEST(ContactPolygon, ClockwiseIsRejected) {
  EXPECT_EQ(polygon_validation_error(poly({{0, 0}, {0, 1}, {1, 1}, {1, 0}})), "vertices are clockwise");
}

TEST(ContactPolygon, NonConvexNamesTheVertex) {
  // Vertex 3 (the dent at (0.5, 0.5)) turns right.
  EXPECT_EQ(polygon_validation_error(poly({{0, 0}, {1, 0}, {1, 1}, {0.5, 0.5}, {0, 1}})),
            "vertex 3 makes the polygon non-convex");
  // A collinear middle vertex is not strictly convex.
  EXPECT_EQ(polygon_validation_error(poly({{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}})),
            "vertex 1 makes the polygon non-convex");
}

TEST(ContactPolygon, VertexCountLimits) {
  EXPECT_NE(polygon_validation_error(poly({{0, 0}, {1, 0}})).find("at least 3"), std::string::npos);
  EXPECT_NE(polygon_validation_error(Polygon{}).find("at least 3"), std::string::npos);
  EXPECT_NE(polygon_validation_error(regular(13, 1.0)).find("at most 12"), std::string::npos);
}

TEST(ContactPolygon, NonFiniteAndDegenerate) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(polygon_validation_error(poly({{0, 0}, {1, nan}, {0, 1}})), "vertex 1 is not finite");
  EXPECT_EQ(polygon_validation_error(poly({{0, 0}, {1, 0}, {HUGE_VAL, 1}})), "vertex 2 is not finite");
  EXPECT_EQ(polygon_validation_error(poly({{0, 0}, {1, 0}, {1, 0}, {0, 1}})), "vertices 1 and 2 coincide");
  EXPECT_EQ(polygon_validation_error(poly({{0, 0}, {1, 0}, {2, 1e-12}})), "polygon has zero area");
}

TEST(ContactPolygon, SelfIntersectingStarIsRejected) {
  // Pentagram: every turn is to the left but the boundary winds twice.
  Polygon star;
  for (int i = 0; i < 5; ++i) star.vertices.emplace_back(std::cos(4 * M_PI * i / 5), std::sin(4 * M_PI * i / 5));
  EXPECT_EQ(polygon_validation_error(star), "polygon winds more than once (self-intersecting)");
}

TEST(ContactPolygon, UnitSquareMassProperties) {
  // Square [0,1]²: A = 1, C = (½, ½), I = m (1² + 1²)/12 = m/6.
  const double rho = 2.5;
  const MassProperties m = mass_properties(unit_square(), rho);
  EXPECT_NEAR(m.area, 1.0, 1e-15);
  EXPECT_NEAR(m.centroid.x(), 0.5, 1e-15);
  EXPECT_NEAR(m.centroid.y(), 0.5, 1e-15);
  EXPECT_NEAR(m.mass, rho, 1e-15);
  EXPECT_NEAR(m.inertia, rho / 6.0, 1e-14);
}

TEST(ContactPolygon, RightTriangleMassPropertiesFarFromOrigin) {
  // Legs a (along x), b (along y): A = ab/2, C = corner + (a/3, b/3),
  // I = m (a² + b²)/18 about the centroid.
  const double a = 3.0, b = 2.0, rho = 0.7;
  const Vec2 o(1000.0, -500.0);
  const MassProperties m = mass_properties(poly({o, o + Vec2(a, 0), o + Vec2(0, b)}), rho);
  const double mass = rho * a * b / 2;
  EXPECT_NEAR(m.area, a * b / 2, 1e-12);
  EXPECT_NEAR(m.centroid.x(), o.x() + a / 3, 1e-12);
  EXPECT_NEAR(m.centroid.y(), o.y() + b / 3, 1e-12);
  EXPECT_NEAR(m.mass, mass, 1e-12);
  EXPECT_NEAR(m.inertia, mass * (a * a + b * b) / 18, 1e-12);
}

TEST(ContactPolygon, RectangleMassPropertiesFarFromOrigin) {
  // w × h rectangle with a corner at (1e6, −1e6): A = wh, C = corner + (w/2, h/2),
  // I = m (w² + h²)/12 (the sums are relative to the first vertex, so nothing cancels).
  const double w = 2.0, h = 0.5, rho = 3.0;
  const Vec2 o(1e6, -1e6);
  const MassProperties m = mass_properties(poly({o, o + Vec2(w, 0), o + Vec2(w, h), o + Vec2(0, h)}), rho);
  EXPECT_DOUBLE_EQ(m.area, w * h);
  EXPECT_NEAR(m.centroid.x(), o.x() + w / 2, 1e-9);
  EXPECT_NEAR(m.centroid.y(), o.y() + h / 2, 1e-9);
  EXPECT_DOUBLE_EQ(m.mass, rho * w * h);
  EXPECT_NEAR(m.inertia, rho * w * h * (w * w + h * h) / 12.0, 1e-12);
}

TEST(ContactPolygon, GeneralTriangleMassProperties) {
  // Any triangle (a, b, c): A = ½ (b − a) × (c − a), C = (a + b + c)/3,
  // I = m (|ab|² + |bc|² + |ca|²)/36 about the centroid.
  const Vec2 a(0.3, -0.2), b(2.1, 0.4), c(0.7, 1.9);
  const double rho = 1.7;
  const MassProperties m = mass_properties(poly({a, b, c}), rho);
  const Vec2 e1 = b - a, e2 = c - a;
  const double area = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
  const double sides2 = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  EXPECT_NEAR(m.area, area, 1e-14);
  EXPECT_NEAR((m.centroid - (a + b + c) / 3.0).norm(), 0.0, 1e-14);
  EXPECT_NEAR(m.inertia, rho * area * sides2 / 36.0, 1e-14);
}

TEST(ContactPolygon, MassPropertiesRejectBadInput) {
  EXPECT_THROW(mass_properties(unit_square(), 0.0), InputError);
  EXPECT_THROW(mass_properties(unit_square(), std::nan("")), InputError);
  EXPECT_THROW(mass_properties(poly({{0, 0}, {0, 1}, {1, 0}}), 1.0), InputError);
}

TEST(ContactPolygon, RecentredHasCentroidAtOrigin) {
  const Polygon p = recentred(poly({{2, 1}, {5, 1}, {2, 3}}));
  const MassProperties m = mass_properties(p, 1.0);
  EXPECT_LT(m.centroid.norm(), 1e-14);
  EXPECT_NEAR(p.vertices[0].x(), -1.0, 1e-14);
  EXPECT_NEAR(p.vertices[0].y(), -2.0 / 3.0, 1e-14);

  // recentre() returns the shift C: to_world(reference, C) keeps the world shape.
  Polygon q = poly({{0, 0}, {2, 0}, {2, 1}, {0, 1}});
  const Vec2 c = recentre(q);
  EXPECT_EQ(c, Vec2(1.0, 0.5));
  const Vec3 reference(1.0, -2.0, 0.7);
  const Vec3 pose(to_world(reference, c).x(), to_world(reference, c).y(), reference.z());
  EXPECT_NEAR((to_world(pose, q.vertices[2]) - to_world(reference, Vec2(2, 1))).norm(), 0.0, 1e-15);

  // An already centred polygon is kept bit for bit, and the shift is exactly zero.
  Polygon centred = poly({{-0.1, -0.3}, {0.1, -0.3}, {0.1, 0.3}, {-0.1, 0.3}});
  const Polygon copy = centred;
  EXPECT_EQ(recentre(centred), Vec2::Zero());
  EXPECT_EQ(centred.vertices, copy.vertices);
  Polygon clockwise = poly({{0, 0}, {0, 1}, {1, 0}});
  EXPECT_THROW(recentre(clockwise), InputError);

  const RigidBody body = make_body(unit_square(), 3.0, Vec3(1, 2, 0.3));
  EXPECT_NEAR(body.mass, 3.0, 1e-15);
  EXPECT_NEAR(body.inertia, 0.5, 1e-14);
  EXPECT_NEAR(body.shape.vertices[0].x(), -0.5, 1e-15);
}

TEST(ContactPolygon, WorldVerticesAndBox) {
  RigidBody body;
  body.shape = poly({{-1, -0.5}, {1, -0.5}, {1, 0.5}, {-1, 0.5}});
  body.pose = Vec3(3.0, 4.0, M_PI / 2);  // rotated a quarter turn
  const std::vector<Vec2> w = world_vertices(body);
  ASSERT_EQ(w.size(), 4u);
  EXPECT_NEAR(w[0].x(), 3.5, 1e-15);
  EXPECT_NEAR(w[0].y(), 3.0, 1e-15);
  const Aabb box = aabb(body, 0.1);
  EXPECT_NEAR(box.lower.x(), 2.4, 1e-14);
  EXPECT_NEAR(box.upper.x(), 3.6, 1e-14);
  EXPECT_NEAR(box.lower.y(), 2.9, 1e-14);
  EXPECT_NEAR(box.upper.y(), 5.1, 1e-14);

  const Aabb sbox = aabb(Segment{{2, 1}, {-1, 3}}, 0.0);
  EXPECT_EQ(sbox.lower, Vec2(-1, 1));
  EXPECT_EQ(sbox.upper, Vec2(2, 3));

  HalfPlane ground;  // y ≥ 0
  EXPECT_TRUE(box_near_half_plane(Aabb{{0, 0.05}, {1, 1}}, ground, 0.05));
  EXPECT_FALSE(box_near_half_plane(Aabb{{0, 0.06}, {1, 1}}, ground, 0.05));
  HalfPlane tilted{Vec2(1, 1).normalized(), 0.0};
  EXPECT_TRUE(box_near_half_plane(Aabb{{-1, 0.5}, {0, 1}}, tilted, 0.0));
  EXPECT_FALSE(box_near_half_plane(Aabb{{0.1, 0.1}, {1, 1}}, tilted, 0.1));
}

}  // namespace
}  // namespace lcprelax
