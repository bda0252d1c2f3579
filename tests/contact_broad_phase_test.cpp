// Broad phase: the grid's pair set equals brute force on random scenes (with static bodies
// and large boxes), never misses a pair the narrow phase would report, handles degenerate
// inputs, and pairs bodies with half-planes and segments.
#include <lcprelax/contact/broad_phase.hpp>
#include <lcprelax/contact/convex_shape.hpp>
#include <lcprelax/contact/narrow_phase.hpp>
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>

namespace lcprelax {
namespace {

RigidBody box(double hw, double hh, const Vec3& pose, bool is_static = false) {
  RigidBody b;
  b.shape.vertices = {{-hw, -hh}, {hw, -hh}, {hw, hh}, {-hw, hh}};
  b.pose = pose;
  b.is_static = is_static;
  return b;
}

RigidBody random_polygon(std::mt19937& rng, const Vec2& where, double size) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = std::uniform_int_distribution<int>(3, 12)(rng);
  for (;;) {
    std::vector<double> angle(n);
    for (double& a : angle) a = 2 * M_PI * u(rng);
    std::sort(angle.begin(), angle.end());
    Polygon p;
    const double rx = size * (0.3 + u(rng)), ry = size * (0.3 + u(rng));
    for (double a : angle) p.vertices.emplace_back(rx * std::cos(a), ry * std::sin(a));
    if (polygon_validation_error(p).empty()) return make_body(p, 1.0, Vec3(where.x(), where.y(), 2 * M_PI * u(rng)));
  }
}

// 500 random polygons of mixed sizes in a 4 m × 4 m box, every 10th static, plus a few long
// static walls, one large dynamic plank and a large static block across it (boxes of
// more than kMaxGridCellsPerBox cells, kept out of the grid).
World random_world(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(0.0, 4.0);
  std::uniform_real_distribution<double> size(0.02, 0.15);
  World w;
  for (int i = 0; i < 500; ++i) {
    w.bodies.push_back(random_polygon(rng, Vec2(x(rng), x(rng)), size(rng)));
    w.bodies.back().is_static = i % 10 == 3;
  }
  w.bodies.insert(w.bodies.begin() + 17, box(2.0, 0.02, Vec3(2.0, -0.01, 0.0), true));
  w.bodies.insert(w.bodies.begin() + 200, box(0.02, 2.0, Vec3(0.05, 2.0, 0.0), true));
  w.bodies.push_back(box(1.5, 0.03, Vec3(2.0, 2.0, 0.4)));
  w.bodies.push_back(box(1.0, 0.6, Vec3(2.0, 2.2, 0.0), true));  // large, overlaps the plank
  w.half_planes.push_back(HalfPlane{Vec2(0, 1), 0.1});
  w.half_planes.push_back(HalfPlane{Vec2(-1, 0), -3.9});  // x ≤ 3.9
  w.segments.push_back(Segment{{0.0, 4.0}, {4.0, 3.8}});
  w.segments.push_back(Segment{{1.0, 1.0}, {1.3, 1.6}});
  return w;
}

std::vector<BodyPair> brute_force_pairs(const std::vector<Aabb>& boxes, const std::vector<bool>& is_static) {
  std::vector<BodyPair> out;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(boxes.size()); ++j)
      if (!(is_static[i] && is_static[j]) && overlaps(boxes[i], boxes[j])) out.push_back({i, j});
  return out;
}

TEST(ContactBroadPhase, GridEqualsBruteForceOnRandomPolygons) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const World w = random_world(seed);
    for (double margin : {0.0, 0.01, 0.05}) {
      std::vector<Aabb> boxes;
      std::vector<bool> is_static;
      for (const RigidBody& b : w.bodies) boxes.push_back(aabb(b, margin / 2)), is_static.push_back(b.is_static);
      const std::vector<BodyPair> grid = overlapping_pairs(boxes, is_static);
      const std::vector<BodyPair> brute = brute_force_pairs(boxes, is_static);  // already sorted
      EXPECT_GT(brute.size(), 300u);
      EXPECT_EQ(grid, brute) << "seed " << seed << " margin " << margin;
      const int plank = static_cast<int>(w.bodies.size()) - 2, block = plank + 1;
      EXPECT_TRUE(std::find(grid.begin(), grid.end(), BodyPair{plank, block}) != grid.end());
      EXPECT_EQ(broad_phase(w, margin).body_pairs, brute);
    }
  }
}

TEST(ContactBroadPhase, NoNarrowPhaseContactIsMissed) {
  const World w = random_world(11);
  const double margin = 0.02;
  const BroadPhasePairs pairs = broad_phase(w, margin);
  std::set<std::pair<int, int>> candidates;
  for (const BodyPair& p : pairs.body_pairs) candidates.insert({p.a, p.b});
  int touching = 0;
  const int n = static_cast<int>(w.bodies.size());
  std::vector<ConvexShape> shapes;
  for (const RigidBody& b : w.bodies) shapes.push_back(make_shape(b));
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if (w.bodies[i].is_static && w.bodies[j].is_static) continue;
      if (collide(shapes[i], shapes[j], margin).count == 0) continue;
      ++touching;
      EXPECT_TRUE(candidates.count({i, j})) << i << " " << j;
    }
  EXPECT_GT(touching, 50);

  // Static shapes: every dynamic body with a contact against a half-plane or segment is
  // paired with it, in (body, kind, index) order.
  std::vector<std::tuple<int, int, int>> expected;
  for (int i = 0; i < n; ++i) {
    if (w.bodies[i].is_static) continue;
    for (int k = 0; k < 2; ++k)
      if (collide(shapes[i], w.half_planes[k], margin).count > 0) expected.emplace_back(i, 1, k);
    for (int k = 0; k < 2; ++k)
      if (collide(shapes[i], make_shape(w.segments[k]), margin).count > 0) expected.emplace_back(i, 2, k);
  }
  std::vector<std::tuple<int, int, int>> got;
  for (const ShapePair& p : pairs.shape_pairs) {
    EXPECT_FALSE(w.bodies[p.body].is_static);
    got.emplace_back(p.body, static_cast<int>(p.kind), p.index);
  }
  EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
  EXPECT_GT(expected.size(), 10u);
  for (const auto& e : expected) EXPECT_TRUE(std::binary_search(got.begin(), got.end(), e));
}

TEST(ContactBroadPhase, DegenerateInputs) {
  const std::vector<bool> dyn2{false, false};
  EXPECT_TRUE(overlapping_pairs({}, {}).empty());
  EXPECT_TRUE(overlapping_pairs({Aabb{{0, 0}, {1, 1}}}, {false}).empty());
  // Point boxes (zero extent) at the same place, and touching boxes.
  EXPECT_EQ(overlapping_pairs({Aabb{{1, 1}, {1, 1}}, Aabb{{1, 1}, {1, 1}}}, dyn2).size(), 1u);
  EXPECT_EQ(overlapping_pairs({Aabb{{0, 0}, {1, 1}}, Aabb{{1, 0}, {2, 1}}}, dyn2).size(), 1u);
  EXPECT_TRUE(overlapping_pairs({Aabb{{0, 0}, {1, 1}}, Aabb{{1.001, 0}, {2, 1}}}, dyn2).empty());
  // Two static bodies are never paired.
  EXPECT_TRUE(overlapping_pairs({Aabb{{0, 0}, {1, 1}}, Aabb{{0, 0}, {1, 1}}}, {true, true}).empty());
  // Many identical boxes in one cell: all pairs.
  EXPECT_EQ(overlapping_pairs(std::vector<Aabb>(30, Aabb{{0, 0}, {1, 1}}), std::vector<bool>(30, false)).size(),
            30u * 29u / 2u);
  // Far-flung boxes (cell indices would overflow 32 bits with the median cell size).
  EXPECT_EQ(overlapping_pairs({Aabb{{0, 0}, {0.1, 0.1}}, Aabb{{0.05, 0.05}, {0.2, 0.2}}, Aabb{{1e12, 0}, {1e12 + 0.1, 0.1}}},
                              {false, false, false})
                .size(),
            1u);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(overlapping_pairs({Aabb{{0, 0}, {1, nan}}, Aabb{{0, 0}, {1, 1}}}, dyn2), InputError);
  EXPECT_THROW(overlapping_pairs({Aabb{{0, 0}, {1, 1}}}, dyn2), InputError);

  World w;
  w.bodies.push_back(box(0.5, 0.5, Vec3(0, nan, 0)));
  EXPECT_THROW(broad_phase(w, 0.01), InputError);
  w.bodies[0].pose = Vec3::Zero();
  EXPECT_THROW(broad_phase(w, -1.0), InputError);
  w.half_planes.push_back(HalfPlane{Vec2(0, 2), 0.0});
  EXPECT_THROW(broad_phase(w, 0.01), InputError);
  w.half_planes[0].normal = Vec2(0, 1);
  w.segments.push_back(Segment{{1, 1}, {1, 1}});
  EXPECT_THROW(broad_phase(w, 0.01), InputError);
}

TEST(ContactBroadPhase, HalfPlaneAndSegmentCandidates) {
  World w;
  w.bodies.push_back(box(0.5, 0.5, Vec3(0, 0.5 + 0.004, 0)));         // 4 mm above y = 0
  w.bodies.push_back(box(0.5, 0.5, Vec3(3, 0.5 + 0.2, 0)));           // far above
  w.bodies.push_back(box(0.5, 0.5, Vec3(-3, 0.5 - 0.1, 0), true));    // static: never paired
  w.half_planes.push_back(HalfPlane{});
  w.segments.push_back(Segment{{2.4, -1}, {2.4, 3}});                 // wall 0.1 left of body 1
  const BroadPhasePairs p = broad_phase(w, 0.01);
  ASSERT_EQ(p.shape_pairs.size(), 1u);
  EXPECT_EQ(p.shape_pairs[0].body, 0);
  EXPECT_EQ(p.shape_pairs[0].kind, Contact::StaticKind::half_plane);
  const BroadPhasePairs wide = broad_phase(w, 0.25);
  ASSERT_EQ(wide.shape_pairs.size(), 3u);
  EXPECT_EQ(wide.shape_pairs[1].body, 1);
  EXPECT_EQ(wide.shape_pairs[1].kind, Contact::StaticKind::half_plane);
  EXPECT_EQ(wide.shape_pairs[2].kind, Contact::StaticKind::segment);
}

}  // namespace
}  // namespace lcprelax
