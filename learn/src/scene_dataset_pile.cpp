// The learning pile: polygons of a few shape classes dropped into a box
// (scene_dataset.hpp: make_learning_pile states the layout and the class table).
#include "random_draws.hpp"
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/math_constants.hpp>
#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace lcprelax::learn {
namespace {

using detail::uniform;

constexpr int kMaxBodies = 100000;
constexpr int kClasses = 4;
constexpr double kCellPerRadius = 2.2;  // grid cell side / largest circumradius
constexpr double kFloorGap = 2e-3;      // m, lowest vertex above its row's floor
constexpr double kSpeed = 0.05;         // m/s, initial velocity components in ±kSpeed
constexpr double kSpin = 0.5;           // rad/s, initial angular velocity in ±kSpin

struct ShapeClass {
  Polygon polygon;  // about its circumcentre (not yet recentred)
  double radius;    // circumradius (m)
  double density;   // kg/m²
};

Polygon regular(int n, double r) {
  Polygon p;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * kPi * k / n;
    p.vertices.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return p;
}

Polygon rectangle(double w, double h) {
  return Polygon{{{-0.5 * w, -0.5 * h}, {0.5 * w, -0.5 * h}, {0.5 * w, 0.5 * h}, {-0.5 * w, 0.5 * h}}};
}

std::array<ShapeClass, kClasses> class_table() {
  return {{{rectangle(0.1, 0.1), 0.05 * std::sqrt(2.0), 1000.0},
           {regular(3, 0.08), 0.08, 1500.0},
           {regular(5, 0.07), 0.07, 800.0},
           {rectangle(0.14, 0.07), 0.5 * std::hypot(0.14, 0.07), 1200.0}}};
}

}  // namespace

std::string LearningPileOptions::validation_error() const {
  if (bodies < 1 || bodies > kMaxBodies) return "bodies: must be in [1, " + std::to_string(kMaxBodies) + "]";
  if (classes < 1 || classes > kClasses) return "classes: must be in [1, " + std::to_string(kClasses) + "]";
  if (!(std::isfinite(mu) && mu >= 0)) return "mu: must be finite and >= 0";
  if (!(std::isfinite(dt) && dt > 0)) return "dt: must be finite and > 0";
  if (!(std::isfinite(margin) && margin >= 0)) return "margin: must be finite and >= 0";
  if (post_stabilization_passes < 1) return "post_stabilization_passes: must be >= 1";
  return {};
}

Scene make_learning_pile(const LearningPileOptions& o) {
  const std::string error = o.validation_error();
  if (!error.empty()) throw InputError("LearningPileOptions." + error);
  const std::array<ShapeClass, kClasses> table = class_table();
  // Recentred shapes and mass properties, computed once per class so that every body of a
  // class has bitwise the same vertices, mass and inertia.
  std::array<Polygon, kClasses> shapes;
  std::array<Vec2, kClasses> centroid;  // of the circumcentred polygon
  std::array<MassProperties, kClasses> props;
  double r_max = 0.0;
  for (int c = 0; c < o.classes; ++c) {
    shapes[c] = table[c].polygon;
    props[c] = mass_properties(shapes[c], table[c].density);
    centroid[c] = recentre(shapes[c]);
    r_max = std::max(r_max, table[c].radius);
  }
  const double s = kCellPerRadius * r_max;
  const int columns = std::max(1, static_cast<int>(std::lround(o.bodies / 5.0)));
  const int rows = (o.bodies + columns - 1) / columns;
  const double width = columns * s;

  Scene scene;
  scene.name = "learning pile of " + std::to_string(o.bodies) + " bodies";
  scene.settings.dt = o.dt;
  scene.settings.margin = o.margin;
  scene.settings.post_stabilization_passes = o.post_stabilization_passes;
  scene.settings.model = o.model;
  scene.world.friction.default_mu = o.mu;
  scene.world.half_planes.push_back(HalfPlane{Vec2(0.0, 1.0), 0.0, 0});
  const double height = (rows + 1) * s;
  scene.world.segments.push_back(Segment{Vec2(0.0, 0.0), Vec2(0.0, height), 0});
  scene.world.segments.push_back(Segment{Vec2(width, 0.0), Vec2(width, height), 0});

  std::mt19937_64 rng(o.seed);
  for (int i = 0; i < o.bodies; ++i) {
    int c = i;
    if (i >= o.classes) c = std::min(o.classes - 1, static_cast<int>(uniform(rng, 0.0, o.classes)));
    const double angle = uniform(rng, 0.0, 2.0 * kPi);
    // Lowest point of the circumcentred polygon rotated by `angle` (relative to the circumcentre).
    double lowest = 0.0;
    for (const Vec2& v : table[c].polygon.vertices) lowest = std::min(lowest, to_world(Vec3(0, 0, angle), v).y());
    const int row = i / columns, column = i % columns;
    const Vec3 circumcentre((column + 0.5) * s, row * s + kFloorGap - lowest, angle);
    RigidBody body;
    body.shape = shapes[c];
    body.mass = props[c].mass;
    body.inertia = props[c].inertia;
    body.pose << to_world(circumcentre, centroid[c]), angle;
    body.velocity = Vec3(uniform(rng, -kSpeed, kSpeed), uniform(rng, -kSpeed, kSpeed), uniform(rng, -kSpin, kSpin));
    scene.world.bodies.push_back(std::move(body));
  }
  return scene;
}

Scene make_learning_pile(int bodies, std::uint64_t seed, ContactModel model) {
  LearningPileOptions options;
  options.bodies = bodies;
  options.seed = seed;
  options.model = model;
  return make_learning_pile(options);
}

}  // namespace lcprelax::learn
