// Generated scenes: random polygon pile, box stack, box pyramid, box on an incline
// (scenes/pile_scene.hpp documents the layouts).
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/math_constants.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace lcprelax {
namespace {

constexpr int kMaxPileBodies = 1000000;
constexpr double kMinSize = 1e-6, kMaxSize = 1e6;  // m, circumradius range
constexpr double kCellPerSize = 2.2;      // grid cell side / max_size: discs 0.2·max_size apart
constexpr double kSettledLayers = 5.0;    // automatic width: about this many diameters deep
constexpr double kAngleJitter = 0.3;      // vertex angle jitter, in units of 2π/n
constexpr double kBoxDensity = 1000.0;    // kg/m², the box scenes

// InputError "SUBJECT: must be RULE (got VALUE)" unless `ok`.
void require(bool ok, const std::string& subject, const std::string& rule, double value) {
  if (ok) return;
  std::ostringstream os;
  os << subject << ": must be " << rule << " (got " << value << ")";
  throw InputError(os.str());
}

bool is_finite_positive(double v) { return std::isfinite(v) && v > 0.0; }
bool is_finite_nonnegative(double v) { return std::isfinite(v) && v >= 0.0; }

// Uniform draws from the raw 64-bit output: the top 53 bits give a double in [0, 1).
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : engine_(seed) {}
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  int integer(int lo, int hi) {  // in [lo, hi]
    const int k = static_cast<int>(unit() * (static_cast<double>(hi) - lo + 1.0));
    return lo + std::min(k, hi - lo);
  }

 private:
  std::mt19937_64 engine_;
};

// A body of shape `polygon` (any origin) whose world shape is reference + R(θ) v: the
// polygon is recentred on its centroid C and the pose becomes to_world(reference, C), θ.
RigidBody body_at(Polygon polygon, double density, const Vec3& reference) {
  const Vec2 c = recentre(polygon);
  const MassProperties m = mass_properties(polygon, density);
  RigidBody body;
  body.shape = std::move(polygon);
  body.mass = m.mass;
  body.inertia = m.inertia;
  body.pose << to_world(reference, c), reference.z();
  return body;
}

// A random polygon with n vertices on the circle of radius r about the origin. Strictly
// convex by construction (angles on a circle at least 0.4·2π/n apart); validated anyway.
Polygon random_polygon(Draw& draw, int n, double r) {
  Polygon p;
  for (int attempt = 0; attempt < 16; ++attempt) {
    p.vertices.clear();
    const double phase = draw.uniform(0.0, 2.0 * kPi);
    for (int k = 0; k < n; ++k) {
      const double a = phase + 2.0 * kPi * (k + draw.uniform(-kAngleJitter, kAngleJitter)) / n;
      p.vertices.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    if (polygon_validation_error(p).empty()) return p;
  }
  throw std::logic_error("make_pile_scene: no valid polygon drawn: " + polygon_validation_error(p));
}

Scene base_scene(double mu, std::string name) {
  Scene scene;
  scene.name = std::move(name);
  scene.world.friction.default_mu = mu;
  scene.world.half_planes.push_back(HalfPlane{Vec2(0.0, 1.0), 0.0, 0});
  return scene;
}

// A square box of side `size` centred at pose (x, y), rotated by θ.
RigidBody box(double size, double density, const Vec3& pose) {
  const double h = 0.5 * size;
  return make_body(Polygon{{{-h, -h}, {h, -h}, {h, h}, {-h, h}}}, density, pose);
}

void check_boxes(const char* function, const char* count_name, int count, double size, double mu) {
  const std::string f = function;
  require(count >= 1, f + ": " + count_name, ">= 1", count);
  require(is_finite_positive(size), f + ": size", "finite and > 0", size);
  require(is_finite_nonnegative(mu), f + ": mu", "finite and >= 0", mu);
}

}  // namespace

void check_pile_options(const PileOptions& o) {
  require(o.bodies >= 1 && o.bodies <= kMaxPileBodies, "PileOptions.bodies",
          "in [1, " + std::to_string(kMaxPileBodies) + "]", o.bodies);
  require(o.min_size >= kMinSize && o.min_size <= kMaxSize, "PileOptions.min_size",
          "in [1e-6, 1e6] m", o.min_size);
  require(o.max_size >= o.min_size && o.max_size <= kMaxSize, "PileOptions.max_size",
          "in [min_size, 1e6] m", o.max_size);
  require(o.min_vertices >= kMinPolygonVertices, "PileOptions.min_vertices",
          ">= " + std::to_string(kMinPolygonVertices), o.min_vertices);
  require(o.max_vertices >= o.min_vertices && o.max_vertices <= kMaxPolygonVertices,
          "PileOptions.max_vertices", "in [min_vertices, " + std::to_string(kMaxPolygonVertices) + "]",
          o.max_vertices);
  require(is_finite_positive(o.density), "PileOptions.density", "finite and > 0", o.density);
  require(is_finite_nonnegative(o.mu), "PileOptions.mu", "finite and >= 0", o.mu);
  const double cell = kCellPerSize * o.max_size;
  // Between one cell and one cell per body (wider containers only lose precision).
  const double widest = cell * o.bodies;
  require(o.container_width == 0.0 || (o.container_width >= cell && o.container_width <= widest),
          "PileOptions.container_width",
          "0 (automatic) or in [2.2·max_size, bodies·2.2·max_size] = [" + std::to_string(cell) + ", " +
              std::to_string(widest) + "] m",
          o.container_width);
  require(is_finite_positive(o.dt), "PileOptions.dt", "finite and > 0", o.dt);
  require(o.model == ContactModel::lcp || o.model == ContactModel::convex, "PileOptions.model",
          "lcp or convex", static_cast<double>(o.model));
}

Scene make_pile_scene(const PileOptions& o) {
  check_pile_options(o);
  const double cell = kCellPerSize * o.max_size;
  const double width = o.container_width > 0.0
                           ? o.container_width
                           : std::max(cell, o.bodies * (o.min_size + o.max_size) / kSettledLayers);
  const int columns = static_cast<int>(std::clamp(std::floor(width / cell), 1.0, 1.0 * o.bodies));
  const int rows = (o.bodies + columns - 1) / columns;
  const double left = 0.5 * (width - columns * cell);  // centres the grid between the walls
  const double height = (rows + 1) * cell;

  Scene scene = base_scene(o.mu, "pile of " + std::to_string(o.bodies) + " polygons (seed " +
                                     std::to_string(o.seed) + ")");
  scene.settings.dt = o.dt;
  scene.settings.model = o.model;
  World& w = scene.world;
  w.segments.push_back(Segment{{0.0, 0.0}, {0.0, height}, 0});
  w.segments.push_back(Segment{{width, 0.0}, {width, height}, 0});

  Draw draw(o.seed);
  const double speed = 0.5 * o.max_size;  // m/s, per velocity component
  w.bodies.reserve(o.bodies);
  for (int i = 0; i < o.bodies; ++i) {
    const int n = draw.integer(o.min_vertices, o.max_vertices);
    const double r = draw.uniform(o.min_size, o.max_size);
    Polygon polygon = random_polygon(draw, n, r);
    const double angle = draw.uniform(0.0, 2.0 * kPi);
    const Vec3 centre(left + (i % columns + 0.5) * cell, (i / columns + 0.5) * cell, angle);
    RigidBody body = body_at(std::move(polygon), o.density, centre);
    const double vx = draw.uniform(-speed, speed), vy = draw.uniform(-speed, speed);
    body.velocity = Vec3(vx, vy, draw.uniform(-1.0, 1.0));
    w.bodies.push_back(std::move(body));
  }
  return scene;
}

Scene make_box_stack_scene(int boxes, double size, double mu) {
  check_boxes("make_box_stack_scene", "boxes", boxes, size, mu);
  Scene scene = base_scene(mu, "stack of " + std::to_string(boxes) + " boxes");
  for (int i = 0; i < boxes; ++i)
    scene.world.bodies.push_back(box(size, kBoxDensity, Vec3(0.0, (i + 0.5) * size, 0.0)));
  return scene;
}

Scene make_pyramid_scene(int base, double size, double mu) {
  check_boxes("make_pyramid_scene", "base", base, size, mu);
  Scene scene = base_scene(mu, "pyramid of boxes, base " + std::to_string(base));
  for (int r = 0; r < base; ++r)
    for (int j = 0; j < base - r; ++j) {
      const Vec3 pose((j + 0.5 * (r + 1)) * size, (r + 0.5) * size, 0.0);  // half a box per row
      scene.world.bodies.push_back(box(size, kBoxDensity, pose));
    }
  return scene;
}

Scene make_incline_scene(double angle, double mu, double size, double density) {
  require(std::isfinite(angle) && std::abs(angle) < 0.5 * kPi, "make_incline_scene: angle",
          "in (-pi/2, pi/2)", angle);
  require(is_finite_nonnegative(mu), "make_incline_scene: mu", "finite and >= 0", mu);
  require(is_finite_positive(size), "make_incline_scene: size", "finite and > 0", size);
  require(is_finite_positive(density), "make_incline_scene: density", "finite and > 0", density);
  Scene scene = base_scene(mu, "box on an incline");
  const Vec2 normal(-std::sin(angle), std::cos(angle));
  scene.world.half_planes[0].normal = normal;
  const Vec2 centre = 0.5 * size * normal;  // the bottom face lies on the plane
  scene.world.bodies.push_back(box(size, density, Vec3(centre.x(), centre.y(), angle)));
  return scene;
}

}  // namespace lcprelax
