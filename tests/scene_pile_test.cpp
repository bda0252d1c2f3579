// Generated scenes (scenes/pile_scene.hpp): the random pile is deterministic for a seed,
// starts with no overlaps and inside its container, scales to 2000 bodies, and validates its
// options; the box stack, pyramid and incline touch with gap 0 and 2 contacts per
// resting interface.
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace lcprelax {
namespace {

// `make()` throws InputError whose message contains `part`.
template <class F>
void expect_error(F make, const std::string& part) {
  try {
    make();
    ADD_FAILURE() << "no error; expected: " << part;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

// Contacts per touching pair (a, b, static kind, static index).
std::map<std::tuple<int, int, int, int>, int> per_pair(const std::vector<Contact>& contacts) {
  std::map<std::tuple<int, int, int, int>, int> count;
  for (const Contact& c : contacts)
    ++count[{c.body_a, c.body_b, static_cast<int>(c.static_kind), c.static_index}];
  return count;
}

// Checks that every contact of a resting configuration has gap 0 (up to rounding) and that
// every touching pair has exactly two contacts; returns the number of contacts.
std::size_t expect_resting(const Scene& scene, double mu) {
  CollisionSettings touching;
  touching.margin = 1e-9;  // gaps of ±1 ulp count as touching
  const std::vector<Contact> contacts = find_contacts(scene.world, touching);
  for (const Contact& c : contacts) {
    EXPECT_LT(std::abs(c.gap), 1e-12) << c.body_a << " " << c.body_b;
    EXPECT_EQ(c.mu, mu);
  }
  for (const auto& [pair, n] : per_pair(contacts))
    EXPECT_EQ(n, 2) << std::get<0>(pair) << " " << std::get<1>(pair);
  return contacts.size();
}

void expect_same(const World& a, const World& b) {
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i].shape.vertices, b.bodies[i].shape.vertices) << i;
    EXPECT_EQ(a.bodies[i].pose, b.bodies[i].pose) << i;
    EXPECT_EQ(a.bodies[i].velocity, b.bodies[i].velocity) << i;
    EXPECT_EQ(a.bodies[i].mass, b.bodies[i].mass) << i;
    EXPECT_EQ(a.bodies[i].inertia, b.bodies[i].inertia) << i;
  }
}

// Checks the documented layout of a pile: valid centred polygons, vertex counts and sizes in
// range, inside the container (walls x = 0 and x = W, from y = 0 to H), no contact at
// margin 0 and every near gap ≥ 0.1·max_size.
void expect_valid_pile(const Scene& s, const PileOptions& o) {
  const World& w = s.world;
  ASSERT_EQ(static_cast<int>(w.bodies.size()), o.bodies);
  ASSERT_EQ(w.half_planes.size(), 1u);
  ASSERT_EQ(w.segments.size(), 2u);
  const double width = w.segments[1].a.x(), height = w.segments[0].b.y();
  EXPECT_EQ(w.segments[0].a, Vec2(0, 0));
  EXPECT_EQ(w.segments[1].b, Vec2(width, height));
  for (const RigidBody& b : w.bodies) {
    const int n = static_cast<int>(b.shape.vertices.size());
    EXPECT_GE(n, o.min_vertices);
    EXPECT_LE(n, o.max_vertices);
    EXPECT_EQ(polygon_validation_error(b.shape), "");
    const MassProperties m = mass_properties(b.shape, o.density);
    EXPECT_LT(m.centroid.norm(), 1e-12);
    EXPECT_NEAR(b.mass, m.mass, 1e-12 * m.mass);
    EXPECT_NEAR(b.inertia, m.inertia, 1e-12 * m.inertia);
    double diameter = 0.0;  // ≤ 2·circumradius
    for (const Vec2& p : b.shape.vertices)
      for (const Vec2& q : b.shape.vertices) diameter = std::max(diameter, (p - q).norm());
    EXPECT_LE(diameter, 2.0 * o.max_size * (1 + 1e-12));
    for (const Vec2& p : world_vertices(b)) {
      EXPECT_GT(p.x(), 0.0);
      EXPECT_LT(p.x(), width);
      EXPECT_GT(p.y(), 0.0);
      EXPECT_LT(p.y(), height);
    }
  }
  CollisionSettings zero;
  zero.margin = 0.0;
  EXPECT_TRUE(find_contacts(w, zero).empty());
  CollisionSettings near;
  near.margin = 2.2 * o.max_size;  // a grid cell: reports neighbours, walls and the ground
  const std::vector<Contact> contacts = find_contacts(w, near);
  EXPECT_FALSE(contacts.empty());
  for (const Contact& c : contacts) EXPECT_GE(c.gap, 0.1 * o.max_size * (1 - 1e-9));
}

TEST(ScenePile, DefaultPileIsValid) {
  const PileOptions o;
  const Scene s = make_pile_scene(o);
  expect_valid_pile(s, o);
  EXPECT_EQ(s.settings.dt, o.dt);
  EXPECT_EQ(s.settings.model, ContactModel::lcp);
  EXPECT_EQ(s.world.friction.default_mu, 0.5);
  EXPECT_EQ(s.world.gravity, Vec2(0, -9.81));
  // Varied shapes: every vertex count of the range appears among 200 bodies.
  std::set<std::size_t> counts;
  for (const RigidBody& b : s.world.bodies) counts.insert(b.shape.vertices.size());
  EXPECT_EQ(counts.size(), 6u);
  // Automatic width: about bodies·(min_size + max_size)/5 = 8 m.
  EXPECT_NEAR(s.world.segments[1].a.x(), 8.0, 1e-12);
}

TEST(ScenePile, SameSeedSameSceneOtherSeedOtherScene) {
  PileOptions o;
  o.bodies = 50;
  o.seed = 12345;
  const Scene a = make_pile_scene(o), b = make_pile_scene(o);
  expect_same(a.world, b.world);
  o.seed = 12346;
  const Scene c = make_pile_scene(o);
  EXPECT_NE(a.world.bodies[0].shape.vertices, c.world.bodies[0].shape.vertices);
  EXPECT_NE(a.world.bodies[0].velocity, c.world.bodies[0].velocity);
}

TEST(ScenePile, RoundTripsThroughSceneJson) {
  // Centred vertices are kept bit for bit by the reader (recentre), so a written pile reads
  // back exactly.
  PileOptions o;
  o.bodies = 30;
  const Scene a = make_pile_scene(o);
  const Scene b = parse_scene(write_scene(a));
  expect_same(a.world, b.world);
  EXPECT_EQ(b.world.segments[1].b, a.world.segments[1].b);
}

TEST(ScenePile, VertexCountsDoNotDependOnTheStandardLibrary) {
  // std::mt19937_64 output is fixed by the standard and the mapping to [0, 1) is ours, so
  // the vertex counts for seed 1 are the same everywhere (computed once, kept here).
  const Scene s = make_pile_scene(PileOptions{});
  const std::vector<std::size_t> expected = {3, 3, 4, 5, 3, 7, 3, 6, 5, 7};
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_EQ(s.world.bodies[i].shape.vertices.size(), expected[i]) << i;
}

TEST(ScenePile, OptionsAreHonoured) {
  PileOptions o;
  o.bodies = 37;
  o.seed = 7;
  o.min_size = o.max_size = 0.2;
  o.min_vertices = o.max_vertices = 12;
  o.density = 2.5;
  o.mu = 0.1;
  o.container_width = 1.5;  // 3 cells of 0.44 m per row
  o.dt = 5e-3;
  o.model = ContactModel::convex;
  const Scene s = make_pile_scene(o);
  expect_valid_pile(s, o);
  EXPECT_EQ(s.world.segments[1].a.x(), 1.5);
  EXPECT_EQ(s.settings.dt, 5e-3);
  EXPECT_EQ(s.settings.model, ContactModel::convex);
  EXPECT_EQ(s.world.friction.default_mu, 0.1);
  EXPECT_NEAR(s.world.segments[0].b.y(), (13 + 1) * 0.44, 1e-12);  // ⌈37/3⌉ rows + 1 cell
}

TEST(ScenePile, ExtremeOptions) {
  PileOptions o;
  o.bodies = 10;
  o.min_size = o.max_size = 1e-6;  // tolerances are relative: micrometre polygons are fine
  expect_valid_pile(make_pile_scene(o), o);
  o.bodies = 1;
  o.min_size = 1e-6;
  o.max_size = 1e6;
  expect_valid_pile(make_pile_scene(o), o);
  o = PileOptions{};
  o.bodies = 4;
  o.container_width = 4 * 2.2 * o.max_size;  // the widest: one column per body, one row
  const Scene s = make_pile_scene(o);
  expect_valid_pile(s, o);
  EXPECT_NEAR(s.world.segments[0].b.y(), 2 * 2.2 * o.max_size, 1e-12);  // H = (rows + 1)·cell
}

TEST(ScenePile, TwoThousandBodies) {
  PileOptions o;
  o.bodies = 2000;
  o.seed = 99;
  o.max_vertices = 12;
  const Scene s = make_pile_scene(o);
  expect_valid_pile(s, o);
}

TEST(ScenePile, InvalidOptionsNameTheField) {
  const auto with = [](auto edit) {
    return [edit] {
      PileOptions o;
      edit(o);
      return make_pile_scene(o);
    };
  };
  expect_error(with([](PileOptions& o) { o.bodies = 0; }), "PileOptions.bodies: must be in [1, ");
  expect_error(with([](PileOptions& o) { o.min_size = 0; }), "PileOptions.min_size: must be in [1e-6, 1e6] m (got 0)");
  expect_error(with([](PileOptions& o) { o.min_size = 1e-300; }), "PileOptions.min_size");
  expect_error(with([](PileOptions& o) { o.min_size = NAN; }), "PileOptions.min_size");
  expect_error(with([](PileOptions& o) { o.max_size = 0.01; }), "PileOptions.max_size: must be in [min_size, 1e6] m");
  expect_error(with([](PileOptions& o) { o.max_size = INFINITY; }), "PileOptions.max_size");
  expect_error(with([](PileOptions& o) { o.min_vertices = 2; }), "PileOptions.min_vertices: must be >= 3");
  expect_error(with([](PileOptions& o) { o.max_vertices = 13; }),
               "PileOptions.max_vertices: must be in [min_vertices, 12]");
  expect_error(with([](PileOptions& o) { o.min_vertices = 9; }), "PileOptions.max_vertices");
  expect_error(with([](PileOptions& o) { o.density = -1; }), "PileOptions.density: must be finite and > 0");
  expect_error(with([](PileOptions& o) { o.mu = -0.1; }), "PileOptions.mu: must be finite and >= 0");
  expect_error(with([](PileOptions& o) { o.container_width = 0.3; }),
               "PileOptions.container_width: must be 0 (automatic)");
  expect_error(with([](PileOptions& o) { o.container_width = -1; }), "PileOptions.container_width");
  expect_error(with([](PileOptions& o) { o.container_width = 1e300; }), "PileOptions.container_width");
  expect_error(with([](PileOptions& o) { o.container_width = NAN; }), "PileOptions.container_width");
  expect_error(with([](PileOptions& o) { o.dt = 0; }), "PileOptions.dt: must be finite and > 0");
  expect_error(with([](PileOptions& o) { o.model = static_cast<ContactModel>(7); }), "PileOptions.model");
}

TEST(SceneBoxes, StackRestsWithGapZero) {
  for (const double size : {0.1, 1.0, 0.37}) {
    const Scene s = make_box_stack_scene(5, size, 0.6);
    ASSERT_EQ(s.world.bodies.size(), 5u);
    EXPECT_NEAR(s.world.bodies[0].mass, 1000 * size * size, 1e-12);
    EXPECT_EQ(expect_resting(s, 0.6), 2u * 5);  // the ground and 4 box-on-box interfaces
  }
  EXPECT_EQ(expect_resting(make_box_stack_scene(1, 0.5, 0.0), 0.0), 2u);
}

TEST(SceneBoxes, PyramidRestsWithGapZero) {
  for (const int base : {1, 2, 5, 10}) {
    const Scene s = make_pyramid_scene(base, 0.3, 0.5);
    ASSERT_EQ(static_cast<int>(s.world.bodies.size()), base * (base + 1) / 2);
    // 2 with the ground per base box, 2 per box-on-box support (two per box above the
    // ground), 2 per pair of row neighbours.
    const int expected = 2 * base + 2 * base * (base - 1) + base * (base - 1);
    EXPECT_EQ(static_cast<int>(expect_resting(s, 0.5)), expected) << base;
  }
}

TEST(SceneBoxes, InclineBoxLiesFlatOnThePlane) {
  for (const double angle : {0.0, 0.3, -0.7, 1.2}) {
    const Scene s = make_incline_scene(angle, 0.2, 0.5, 300);
    ASSERT_EQ(s.world.half_planes.size(), 1u);
    const HalfPlane& plane = s.world.half_planes[0];
    EXPECT_NEAR(plane.normal.x(), -std::sin(angle), 1e-15);
    EXPECT_NEAR(plane.normal.y(), std::cos(angle), 1e-15);
    EXPECT_EQ(s.world.bodies.at(0).pose.z(), angle);
    EXPECT_NEAR(s.world.bodies[0].mass, 300 * 0.25, 1e-12);
    EXPECT_EQ(expect_resting(s, 0.2), 2u);
    for (const Contact& c : find_contacts(s.world)) EXPECT_EQ(c.normal, plane.normal);
  }
}

TEST(SceneBoxes, InvalidArgumentsNameTheArgument) {
  expect_error([] { return make_box_stack_scene(0, 1, 0.5); }, "make_box_stack_scene: boxes: must be >= 1");
  expect_error([] { return make_box_stack_scene(3, -1, 0.5); }, "make_box_stack_scene: size");
  expect_error([] { return make_pyramid_scene(3, 1, NAN); }, "make_pyramid_scene: mu");
  expect_error([] { return make_pyramid_scene(-2, 1, 0.5); }, "make_pyramid_scene: base");
  expect_error([] { return make_incline_scene(1.6, 0.5); },
               "make_incline_scene: angle: must be in (-pi/2, pi/2)");
  expect_error([] { return make_incline_scene(0.3, 0.5, 0.0); }, "make_incline_scene: size");
  expect_error([] { return make_incline_scene(0.3, 0.5, 1.0, 0.0); }, "make_incline_scene: density");
}

}  // namespace
}  // namespace lcprelax
