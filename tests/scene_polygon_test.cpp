// Polygon mass properties and validation: closed forms for squares, rectangles and
// triangles (A, centroid, polar moment about the centroid), recentring, polygon_body.
#include <gtest/gtest.h>

#include <lcprelax/scenes/polygon.hpp>
#include <lcprelax/sparse/errors.hpp>

#include <cmath>

namespace lcprelax {
namespace {

TEST(ScenePolygon, UnitSquareFromDensity) {
  // m = ρ·1, I = ρ(1² + 1²)/12 = ρ/6.
  const double rho = 7.5;
  const RigidBody b = polygon_body({{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}, rho, Vec3::Zero());
  EXPECT_DOUBLE_EQ(b.mass, rho);
  EXPECT_DOUBLE_EQ(b.inertia, rho / 6.0);
  EXPECT_EQ(b.pose, Vec3::Zero());
}

TEST(ScenePolygon, RectangleFarFromTheOrigin) {
  // w × h rectangle with a corner at (1e6, 1e6): A = wh, C = corner + (w/2, h/2),
  // J = wh(w² + h²)/12 (the vertex-mean shift keeps the cancellation small).
  const double w = 2.0, h = 0.5, x0 = 1e6, y0 = -1e6;
  const PolygonProperties p = polygon_properties({{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}});
  EXPECT_DOUBLE_EQ(p.area, w * h);
  EXPECT_NEAR(p.centroid.x(), x0 + w / 2, 1e-9);
  EXPECT_NEAR(p.centroid.y(), y0 + h / 2, 1e-9);
  EXPECT_NEAR(p.polar_moment, w * h * (w * w + h * h) / 12.0, 1e-9);
}

TEST(ScenePolygon, TriangleMatchesClosedForms) {
  // Any triangle: A = ½|(b−a)×(c−a)|, C = (a + b + c)/3, J = A(|ab|² + |bc|² + |ca|²)/36.
  const Vec2 a(0.3, -0.2), b(2.1, 0.4), c(0.7, 1.9);
  const PolygonProperties p = polygon_properties({a, b, c});
  const Vec2 e1 = b - a, e2 = c - a;
  const double area = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
  const double sides2 = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  EXPECT_NEAR(p.area, area, 1e-14);
  EXPECT_NEAR((p.centroid - (a + b + c) / 3.0).norm(), 0.0, 1e-14);
  EXPECT_NEAR(p.polar_moment, area * sides2 / 36.0, 1e-14);

  // Right triangle with legs 3 and 2 from density 4: m = 4·3, I = m(3² + 2²)/18.
  const RigidBody r = polygon_body({{0, 0}, {3, 0}, {0, 2}}, 4.0, Vec3(1, 1, 0));
  EXPECT_NEAR(r.mass, 12.0, 1e-14);
  EXPECT_NEAR(r.inertia, 12.0 * 13.0 / 18.0, 1e-13);
  EXPECT_NEAR(r.pose.x(), 2.0, 1e-15);  // (1, 1) + (3/3, 2/3)
  EXPECT_NEAR(r.pose.y(), 1.0 + 2.0 / 3.0, 1e-15);
}

TEST(ScenePolygon, RecentringKeepsTheWorldShape) {
  const std::vector<Vec2> v = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const Vec3 pose(1.0, -2.0, 0.7);
  const RigidBody b = polygon_body(v, 1.0, pose);
  const double c0 = std::cos(pose.z()), s0 = std::sin(pose.z());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 given(pose.x() + c0 * v[i].x() - s0 * v[i].y(), pose.y() + s0 * v[i].x() + c0 * v[i].y());
    const Vec2& u = b.shape.vertices[i];
    const Vec2 now(b.pose.x() + c0 * u.x() - s0 * u.y(), b.pose.y() + s0 * u.x() + c0 * u.y());
    EXPECT_NEAR((given - now).norm(), 0.0, 1e-14);
  }
  EXPECT_NEAR(polygon_properties(b.shape.vertices).centroid.norm(), 0.0, 1e-15);

  std::vector<Vec2> centred = {{-1, -0.5}, {1, -0.5}, {1, 0.5}, {-1, 0.5}};
  const std::vector<Vec2> copy = centred;
  EXPECT_EQ(recentre_polygon(centred), Vec2::Zero());
  EXPECT_EQ(centred, copy);  // bit for bit
}

TEST(ScenePolygon, Validation) {
  EXPECT_NO_THROW(check_convex_polygon({{0, 0}, {1, 0}, {0, 1}}, "p"));
  EXPECT_THROW(check_convex_polygon({{0, 0}, {0, 1}, {1, 0}}, "p"), InputError);           // clockwise
  EXPECT_THROW(check_convex_polygon({{0, 0}, {1, 0}, {1, 0}, {0, 1}}, "p"), InputError);   // repeated
  EXPECT_THROW(check_convex_polygon({{0, 0}, {1, 0}, {NAN, 0.5}, {0, 1}}, "p"), InputError);
  EXPECT_THROW(polygon_body({{0, 0}, {1, 0}, {0, 1}}, -1.0, Vec3::Zero()), InputError);
  try {
    check_convex_polygon({{0, 0}, {0, 1}, {1, 0}}, "bodies[3].vertices");
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("bodies[3].vertices: polygon is clockwise", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace lcprelax
