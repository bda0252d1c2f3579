// The scene parameter map (learn/scene_params.hpp): layout, round trip θ → World → θ, and
// the pullback of a WorldGradient against central differences of the linear functional
// L(θ) = ⟨g, primitives(apply(θ))⟩.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/scene_params.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace lcprelax::learn {
namespace {

Polygon box(double w, double h) {
  return Polygon{{{-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}}};
}

World two_class_world() {
  World w;
  RigidBody a;
  a.shape = box(0.2, 0.1);
  a.mass = 2.0, a.inertia = 0.01, a.material = 0;
  RigidBody b;
  b.shape = Polygon{{{-0.1, -0.05}, {0.1, -0.05}, {0.0, 0.1}}};
  b.mass = 1.0, b.inertia = 0.004, b.material = 1;
  RigidBody wall = a;
  wall.is_static = true;
  w.bodies = {a, b, a, b, wall};
  for (int i = 0; i < 4; ++i) w.bodies[i].pose = Vec3(0.3 * i, 0.1, 0.1 * i);
  w.half_planes.push_back(HalfPlane{Vec2(0.0, 1.0), 0.0, 0});
  w.half_planes.push_back(HalfPlane{Vec2(1.0, 0.0), -1.0, 1});
  w.segments.push_back(Segment{Vec2(2.0, 0.0), Vec2(2.0, 1.0), 0});
  w.friction.default_mu = 0.4;
  w.friction.pairs.push_back({0, 1, 0.7});
  return w;
}

TEST(SceneParams, ShapeClassesAndLayout) {
  const World w = two_class_world();
  EXPECT_EQ(scene_shape_classes(w), (std::vector<int>{0, 1, 0, 1, -1}));
  SceneParameterSettings s;
  s.mu_per_pair = true;
  const SceneParameterMap map(w, s);
  const ParameterSet theta = map.parameters(w);
  // mu, mu[0,1], class0 (2 + 8), class1 (2 + 6), 2 half-planes (2 each), 1 segment (4)
  EXPECT_EQ(theta.size(), 2 + 10 + 8 + 4 + 4);
  EXPECT_EQ(map.size(), theta.size());
  EXPECT_DOUBLE_EQ(theta.value("mu[0,1]"), 0.7);
  EXPECT_DOUBLE_EQ(theta.value("class1.inertia"), 0.004);
  EXPECT_DOUBLE_EQ(theta.value("class0.vertex2.y"), 0.05);
  EXPECT_NEAR(theta.value("half_plane0.angle"), M_PI / 2, 1e-15);
  EXPECT_DOUBLE_EQ(theta.value("segment0.b.y"), 1.0);
  EXPECT_FALSE(theta[theta.index("half_plane0.offset")].learn);  // ground not learned by default
  EXPECT_TRUE(theta[theta.index("class0.vertex0.x")].learn);
}

TEST(SceneParams, ApplyRoundTripsAndSetsEveryBodyOfAClass) {
  const World w = two_class_world();
  const SceneParameterMap map(w, SceneParameterSettings{});
  ParameterSet theta = map.parameters(w);
  theta.set_value("class1.mass", 3.5);
  theta.set_value("class0.vertex1.x", 0.12);
  theta.set_value("mu", 0.9);
  World v = w;
  map.apply(theta, v);
  EXPECT_DOUBLE_EQ(v.bodies[1].mass, 3.5);
  EXPECT_DOUBLE_EQ(v.bodies[3].mass, 3.5);
  EXPECT_DOUBLE_EQ(v.bodies[0].shape.vertices[1].x(), 0.12);
  EXPECT_DOUBLE_EQ(v.bodies[2].shape.vertices[1].x(), 0.12);
  EXPECT_DOUBLE_EQ(v.bodies[4].shape.vertices[1].x(), 0.1);  // static body untouched
  EXPECT_DOUBLE_EQ(v.friction.mu(0, 1), 0.9);                  // global μ: every pair
  const ParameterSet back = map.parameters(v);
  for (Index k = 0; k < theta.size(); ++k) EXPECT_NEAR(back[k].value, theta[k].value, 1e-15) << theta[k].name;
}

// L(θ) = Σ over the world primitives of g · primitive, evaluated after apply(θ).
double linear_functional(const World& w, const std::vector<Contact>& contacts, const WorldGradient& g) {
  double L = 0.0;
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    L += g.bodies[b].mass * w.bodies[b].mass + g.bodies[b].inertia * w.bodies[b].inertia;
    for (std::size_t i = 0; i < w.bodies[b].shape.vertices.size(); ++i)
      L += g.bodies[b].vertices[i].dot(w.bodies[b].shape.vertices[i]);
  }
  for (std::size_t h = 0; h < w.half_planes.size(); ++h)
    L += g.half_plane_normal[h].dot(w.half_planes[h].normal) + g.half_plane_offset[h] * w.half_planes[h].offset;
  for (std::size_t s = 0; s < w.segments.size(); ++s)
    L += g.segment_ends[s][0].dot(w.segments[s].a) + g.segment_ends[s][1].dot(w.segments[s].b);
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const Contact& k = contacts[c];
    const int mb = k.body_b >= 0 ? w.bodies[k.body_b].material
                   : k.static_kind == Contact::StaticKind::half_plane ? w.half_planes[k.static_index].material
                                                                       : w.segments[k.static_index].material;
    L += g.contact_mu[c] * w.friction.mu(w.bodies[k.body_a].material, mb);
  }
  return L;
}

TEST(SceneParams, GradientMatchesCentralDifferences) {
  const World w = two_class_world();
  std::vector<Contact> contacts(3);
  contacts[0].body_a = 0, contacts[0].body_b = 1;                         // materials 0–1: pair
  contacts[1].body_a = 2, contacts[1].static_kind = Contact::StaticKind::half_plane, contacts[1].static_index = 0;  // 0–0: default
  contacts[2].body_a = 3, contacts[2].static_kind = Contact::StaticKind::segment, contacts[2].static_index = 0;     // 1–0: pair
  for (bool per_pair : {false, true}) {
    SceneParameterSettings s;
    s.mu_per_pair = per_pair;
    s.learn.ground = true;
    const SceneParameterMap map(w, s);
    WorldGradient g;
    g.set_zero(w, contacts.size());
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (auto& b : g.bodies) {
      b.mass = u(rng), b.inertia = u(rng);
      for (Vec2& v : b.vertices) v = Vec2(u(rng), u(rng));
    }
    for (Vec2& n : g.half_plane_normal) n = Vec2(u(rng), u(rng));
    for (double& o : g.half_plane_offset) o = u(rng);
    for (auto& e : g.segment_ends) e = {Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng))};
    for (double& m : g.contact_mu) m = u(rng);

    const ParameterSet theta = map.parameters(w);
    World at = w;
    map.apply(theta, at);
    const Vector grad = map.gradient(at, contacts, g);
    ASSERT_EQ(grad.size(), theta.size());
    for (Index k = 0; k < theta.size(); ++k) {
      const double h = 1e-6 * std::max(1.0, std::abs(theta[k].value));
      Vector plus = theta.values(), minus = theta.values();
      plus(k) += h, minus(k) -= h;
      ParameterSet tp = theta, tm = theta;
      tp.set_values(plus), tm.set_values(minus);
      World wp = w, wm = w;
      map.apply(tp, wp), map.apply(tm, wm);
      const double fd = (linear_functional(wp, contacts, g) - linear_functional(wm, contacts, g)) / (2 * h);
      EXPECT_NEAR(grad(k), fd, 1e-7 * std::max(1.0, std::abs(fd))) << theta[k].name << " per_pair " << per_pair;
    }
  }
}

TEST(SceneParams, PerturbationAndRelativeError) {
  const World w = two_class_world();
  const SceneParameterMap map(w, SceneParameterSettings{});
  const ParameterSet truth = map.parameters(w);
  const ParameterSet p = perturb_scene_parameters(truth, map, 0.25, 3);
  EXPECT_EQ(p.values(), perturb_scene_parameters(truth, map, 0.25, 3).values());  // deterministic
  for (Index k = 0; k < truth.size(); ++k) {
    const double e = scene_relative_error(p, truth, map, k);
    if (!truth[k].learn) EXPECT_EQ(e, 0.0) << truth[k].name;
    else if (map.kind(k) == SceneParameterMap::Kind::vertex) EXPECT_NEAR(e, 0.125, 1e-12) << truth[k].name;
    else EXPECT_NEAR(e, 0.25, 1e-12) << truth[k].name;
  }
}

TEST(SceneParams, BadInput) {
  EXPECT_THROW(parse_scene_learn_flags("mu,friction"), InputError);
  EXPECT_THROW(parse_scene_learn_flags("mu,mu"), InputError);
  EXPECT_THROW(parse_scene_learn_flags(""), InputError);
  World empty;
  EXPECT_THROW(SceneParameterMap(empty, SceneParameterSettings{}), InputError);
  const World w = two_class_world();
  const SceneParameterMap map(w, SceneParameterSettings{});
  ParameterSet wrong;
  wrong.add(Parameter{"mu", 0.5, Transform::log});
  World v = w;
  EXPECT_THROW(map.apply(wrong, v), InputError);
  try {
    parse_scene_learn_flags("mu,friction");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("friction"), std::string::npos);
  }
}

}  // namespace
}  // namespace lcprelax::learn
