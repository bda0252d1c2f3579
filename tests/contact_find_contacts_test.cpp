// find_contacts: labelling conventions (a dynamic, lower index first, static shapes as
// body_b = −1), friction lookup, ordering, determinism, symmetry under relabelling the
// bodies, input validation, and a 2000-body pile.
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <utility>

namespace lcprelax {
namespace {

RigidBody box(double hw, double hh, const Vec3& pose, bool is_static = false, int material = 0) {
  RigidBody b;
  b.shape.vertices = {{-hw, -hh}, {hw, -hh}, {hw, hh}, {-hw, hh}};
  b.pose = pose;
  b.is_static = is_static;
  b.material = material;
  return b;
}

RigidBody random_polygon(std::mt19937& rng, const Vec2& where, double radius) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = std::uniform_int_distribution<int>(3, 12)(rng);
  for (;;) {
    std::vector<double> angle(n);
    for (double& a : angle) a = 2 * M_PI * u(rng);
    std::sort(angle.begin(), angle.end());
    Polygon p;
    const double rx = radius * (0.6 + 0.4 * u(rng)), ry = radius * (0.6 + 0.4 * u(rng));
    for (double a : angle) p.vertices.emplace_back(rx * std::cos(a), ry * std::sin(a));
    if (polygon_validation_error(p).empty()) return make_body(p, 1.0, Vec3(where.x(), where.y(), 2 * M_PI * u(rng)));
  }
}

// A pile of columns × rows random polygons on a jittered grid (neighbours touch or overlap
// a little), every 25th static, in a container: floor half-plane, two segment walls.
World pile(int columns, int rows, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  const double spacing = 0.1;
  World w;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      const Vec2 at((c + 0.5) * spacing + jitter(rng), (r + 0.5) * spacing + jitter(rng));
      w.bodies.push_back(random_polygon(rng, at, 0.075));
      w.bodies.back().is_static = w.bodies.size() % 25 == 7;
      w.bodies.back().material = static_cast<int>(w.bodies.size() % 3);
    }
  w.half_planes.push_back(HalfPlane{Vec2(0, 1), 0.0, 1});
  w.segments.push_back(Segment{{0.0, 0.0}, {0.0, rows * spacing + 1.0}, 2});
  w.segments.push_back(Segment{{columns * spacing, rows * spacing + 1.0}, {columns * spacing, 0.0}, 2});
  w.friction.default_mu = 0.4;
  w.friction.pairs = {{0, 1, 0.9}, {2, 2, 0.0}, {1, 2, 0.25}};
  return w;
}

// Checks every documented invariant of a contact list.
void expect_well_formed(const World& w, const std::vector<Contact>& contacts, double margin) {
  EXPECT_TRUE(std::is_sorted(contacts.begin(), contacts.end(), contact_less));
  std::map<std::tuple<int, int, int, int>, int> per_pair;
  for (const Contact& c : contacts) {
    ASSERT_GE(c.body_a, 0);
    EXPECT_FALSE(w.bodies[c.body_a].is_static);
    EXPECT_TRUE(c.point.allFinite());
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
    EXPECT_LE(c.gap, margin);
    int material_b;
    if (c.body_b >= 0) {
      EXPECT_EQ(c.static_kind, Contact::StaticKind::none);
      EXPECT_NE(c.body_a, c.body_b);
      if (!w.bodies[c.body_b].is_static) {
        EXPECT_LT(c.body_a, c.body_b);
      }
      material_b = w.bodies[c.body_b].material;
    } else {
      ASSERT_NE(c.static_kind, Contact::StaticKind::none);
      material_b = c.static_kind == Contact::StaticKind::half_plane ? w.half_planes.at(c.static_index).material
                                                                     : w.segments.at(c.static_index).material;
    }
    EXPECT_EQ(c.mu, w.friction.mu(w.bodies[c.body_a].material, material_b));
    ++per_pair[{c.body_a, c.body_b, static_cast<int>(c.static_kind), c.static_index}];
  }
  for (const auto& [pair, count] : per_pair) EXPECT_LE(count, 2);
}

TEST(ContactFindContacts, BoxOnGroundAndOnStaticAndDynamicBoxes) {
  World w;
  w.bodies.push_back(box(0.5, 0.25, Vec3(4.0, 0.7 + 0.25 + 2e-3, 0), false, 1));  // 0: on body 2
  w.bodies.push_back(box(1.0, 0.2, Vec3(0.0, 0.2, 0), true, 2));                 // 1: static slab
  w.bodies.push_back(box(1.0, 0.35, Vec3(4.0, 0.35 - 1e-3, 0), false, 2));       // 2: on the ground
  w.bodies.push_back(box(0.3, 0.1, Vec3(0.0, 0.4 + 0.1 + 3e-3, 0), false, 0));   // 3: on static body 1
  w.half_planes.push_back(HalfPlane{Vec2(0, 1), 0.0, 0});
  w.friction.pairs = {{1, 2, 0.3}, {0, 2, 0.7}};
  w.friction.default_mu = 0.5;
  const std::vector<Contact> c = find_contacts(w, CollisionSettings{});
  expect_well_formed(w, c, 1e-2);
  ASSERT_EQ(c.size(), 6u);

  // Body 0 on body 2 (both dynamic, a = 0): normal from 2 to 0 is +y.
  for (int k : {0, 1}) {
    EXPECT_EQ(c[k].body_a, 0);
    EXPECT_EQ(c[k].body_b, 2);
    EXPECT_EQ(c[k].normal, Vec2(0, 1));
    EXPECT_NEAR(c[k].gap, 3e-3, 1e-12);
    EXPECT_EQ(c[k].mu, 0.3);
  }
  EXPECT_LT(c[0].point.x(), c[1].point.x());
  // Body 2 on the ground: static shapes (body_b = −1) come first within body 2.
  for (int k : {2, 3}) {
    EXPECT_EQ(c[k].body_a, 2);
    EXPECT_EQ(c[k].body_b, -1);
    EXPECT_EQ(c[k].static_kind, Contact::StaticKind::half_plane);
    EXPECT_EQ(c[k].static_index, 0);
    EXPECT_EQ(c[k].normal, Vec2(0, 1));
    EXPECT_NEAR(c[k].gap, -1e-3, 1e-12);
    EXPECT_EQ(c[k].mu, 0.7);
  }
  // Body 3 on static body 1 (lower index): a is the dynamic body 3, normal from 1 to 3.
  for (int k : {4, 5}) {
    EXPECT_EQ(c[k].body_a, 3);
    EXPECT_EQ(c[k].body_b, 1);
    EXPECT_EQ(c[k].normal, Vec2(0, 1));
    EXPECT_NEAR(c[k].gap, 3e-3, 1e-12);
    EXPECT_EQ(c[k].mu, 0.7);
  }
  // Static body 1 rests on the ground, but static bodies get no contacts.
  // Body 0 hovering 2.5 cm above body 2 leaves the margin: its two contacts disappear.
  w.bodies[0].pose.y() += 0.025;
  EXPECT_EQ(find_contacts(w).size(), 4u);
}

TEST(ContactFindContacts, SegmentContactsFromBothSides) {
  World w;
  w.segments.push_back(Segment{{-1, 1}, {1, 1}, 0});
  w.bodies.push_back(box(0.2, 0.1, Vec3(0, 1.1 + 1e-3, 0)));   // above
  w.bodies.push_back(box(0.2, 0.1, Vec3(0.5, 0.9 - 2e-3, 0)));  // below
  const std::vector<Contact> c = find_contacts(w);
  ASSERT_EQ(c.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(c[k].body_b, -1);
    EXPECT_EQ(c[k].static_kind, Contact::StaticKind::segment);
    EXPECT_EQ(c[k].static_index, 0);
    EXPECT_EQ(c[k].normal, Vec2(0, k < 2 ? 1 : -1));
    EXPECT_NEAR(c[k].gap, k < 2 ? 1e-3 : 2e-3, 1e-12);
  }
}

TEST(ContactFindContacts, InvalidInputThrows) {
  World w;
  w.bodies.push_back(box(0.5, 0.5, Vec3::Zero()));
  EXPECT_NE(CollisionSettings{-1.0}.validation_error(), "");
  EXPECT_EQ(CollisionSettings{}.validation_error(), "");
  EXPECT_THROW(find_contacts(w, CollisionSettings{-1e-3}), InputError);
  EXPECT_THROW(find_contacts(w, CollisionSettings{std::nan("")}), InputError);
  w.bodies.push_back(box(0.5, 0.5, Vec3(0.5, 0, 0)));
  w.bodies[1].shape.vertices.resize(2);
  EXPECT_THROW(find_contacts(w), InputError);
  w.bodies[1] = box(0.5, 0.5, Vec3(0.5, 0, std::nan("")));
  EXPECT_THROW(find_contacts(w), InputError);
  World empty;
  EXPECT_TRUE(find_contacts(empty).empty());
}

TEST(ContactFindContacts, DeterministicAndSymmetricUnderRelabelling) {
  const World w = pile(20, 15, 5);
  const std::vector<Contact> base = find_contacts(w);
  expect_well_formed(w, base, 1e-2);
  ASSERT_GT(base.size(), 300u);
  const std::vector<Contact> again = find_contacts(w);
  ASSERT_EQ(again.size(), base.size());
  for (std::size_t k = 0; k < base.size(); ++k) {
    EXPECT_EQ(again[k].point, base[k].point);
    EXPECT_EQ(again[k].normal, base[k].normal);
    EXPECT_EQ(again[k].gap, base[k].gap);
  }

  // Shuffle the bodies, find contacts, map the labels back and re-canonicalize.
  std::mt19937 rng(99);
  std::vector<int> perm(w.bodies.size());  // new index k holds old body perm[k]
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  World shuffled = w;
  for (std::size_t k = 0; k < perm.size(); ++k) shuffled.bodies[k] = w.bodies[perm[k]];
  std::vector<Contact> mapped = find_contacts(shuffled);
  expect_well_formed(shuffled, mapped, 1e-2);
  for (Contact& c : mapped) {
    c.body_a = perm[c.body_a];
    if (c.body_b >= 0) {
      c.body_b = perm[c.body_b];
      if (!w.bodies[c.body_b].is_static && c.body_b < c.body_a) {
        std::swap(c.body_a, c.body_b);
        c.normal = -c.normal;
      }
    }
  }
  std::sort(mapped.begin(), mapped.end(), contact_less);
  ASSERT_EQ(mapped.size(), base.size());
  for (std::size_t k = 0; k < base.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(mapped[k].body_a, base[k].body_a);
    EXPECT_EQ(mapped[k].body_b, base[k].body_b);
    EXPECT_EQ(mapped[k].static_kind, base[k].static_kind);
    EXPECT_EQ(mapped[k].static_index, base[k].static_index);
    EXPECT_NEAR((mapped[k].point - base[k].point).norm(), 0.0, 1e-12);
    EXPECT_NEAR((mapped[k].normal - base[k].normal).norm(), 0.0, 1e-12);
    EXPECT_NEAR(mapped[k].gap, base[k].gap, 1e-12);
    EXPECT_EQ(mapped[k].mu, base[k].mu);
  }
}

TEST(ContactFindContacts, TwoThousandBodyPile) {
  const World w = pile(50, 40, 2024);
  ASSERT_EQ(w.bodies.size(), 2000u);
  const CollisionSettings settings;
  const std::vector<Contact> c = find_contacts(w, settings);
  expect_well_formed(w, c, settings.margin);
  // A jittered grid of touching polygons: several contacts per body, all kinds present.
  EXPECT_GT(c.size(), 3000u);
  int ground = 0, walls = 0, overlapping = 0;
  for (const Contact& k : c) {
    ground += k.static_kind == Contact::StaticKind::half_plane;
    walls += k.static_kind == Contact::StaticKind::segment;
    overlapping += k.gap < 0;
  }
  EXPECT_GT(ground, 20);
  EXPECT_GT(walls, 20);
  EXPECT_GT(overlapping, 500);
}

}  // namespace
}  // namespace lcprelax
