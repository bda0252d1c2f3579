// Parameters of a polygon on a ground half-plane (polygon_params.hpp).
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/math_constants.hpp>
#include <lcprelax/learn/polygon_params.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <random>

namespace lcprelax::learn {
namespace {


std::string vertex_name(Index i, char axis) { return "vertex" + std::to_string(i) + "." + axis; }

}  // namespace

std::string PolygonModel::validation_error() const {
  const int n = static_cast<int>(shape.vertices.size());
  if (n < kMinPolygonVertices || n > kMaxPolygonVertices)
    return "shape: " + std::to_string(n) + " vertices (3 to 12 expected)";
  for (int i = 0; i < n; ++i)
    if (!shape.vertices[static_cast<std::size_t>(i)].allFinite())
      return "shape: vertex " + std::to_string(i) + " is not finite";
  if (!(std::isfinite(mu) && mu > 0)) return "mu: must be finite and > 0";
  if (!(std::isfinite(mass) && mass > 0)) return "mass: must be finite and > 0";
  if (!(std::isfinite(inertia) && inertia > 0)) return "inertia: must be finite and > 0";
  if (!std::isfinite(ground_height)) return "ground_height: must be finite";
  if (!(std::isfinite(ground_angle) && std::abs(ground_angle) < kHalfPi))
    return "ground_angle: must be finite with |angle| < pi/2";
  return {};
}

HalfPlane ground_half_plane(double height, double angle) {
  HalfPlane g;
  g.normal = Vec2(-std::sin(angle), std::cos(angle));
  g.offset = height * std::cos(angle);
  return g;
}

ParameterSet make_polygon_parameters(const PolygonModel& model, const PolygonLearnFlags& flags) {
  const std::string error = model.validation_error();
  if (!error.empty()) throw InputError("polygon model: " + error);
  ParameterSet theta;
  theta.add({"mu", model.mu, Transform::log, 1e-12, 1e6, flags.mu});
  theta.add({"mass", model.mass, Transform::log, 1e-12, 1e12, flags.mass});
  theta.add({"inertia", model.inertia, Transform::log, 1e-12, 1e12, flags.inertia});
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < model.shape.vertices.size(); ++i) {
    const Vec2& v = model.shape.vertices[i];
    theta.add({vertex_name(static_cast<Index>(i), 'x'), v.x(), Transform::identity, -inf, inf, flags.vertices});
    theta.add({vertex_name(static_cast<Index>(i), 'y'), v.y(), Transform::identity, -inf, inf, flags.vertices});
  }
  theta.add({"ground_height", model.ground_height, Transform::identity, -inf, inf, flags.ground});
  theta.add({"ground_angle", model.ground_angle, Transform::identity, -1.5, 1.5, flags.ground});
  return theta;
}

PolygonModel polygon_model(const ParameterSet& theta) {
  const Index n = (theta.size() - 5) / 2;
  PolygonLayout layout{n};
  if (n < kMinPolygonVertices || layout.size() != theta.size() || theta[layout.kMu].name != "mu" ||
      theta[layout.kMass].name != "mass" || theta[layout.kInertia].name != "inertia" ||
      theta[layout.ground_height()].name != "ground_height" || theta[layout.ground_angle()].name != "ground_angle")
    throw InputError("parameter set does not have the polygon layout (mu, mass, inertia, vertices, ground)");
  PolygonModel m;
  m.mu = theta[layout.kMu].value;
  m.mass = theta[layout.kMass].value;
  m.inertia = theta[layout.kInertia].value;
  m.shape.vertices.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    if (theta[layout.vertex_x(i)].name != vertex_name(i, 'x') || theta[layout.vertex_y(i)].name != vertex_name(i, 'y'))
      throw InputError("parameter set: expected " + vertex_name(i, 'x') + " at index " +
                       std::to_string(layout.vertex_x(i)));
    m.shape.vertices[static_cast<std::size_t>(i)] = Vec2(theta[layout.vertex_x(i)].value, theta[layout.vertex_y(i)].value);
  }
  m.ground_height = theta[layout.ground_height()].value;
  m.ground_angle = theta[layout.ground_angle()].value;
  return m;
}

double polygon_radius(const Polygon& shape) {
  double r = 0.0;
  for (const Vec2& v : shape.vertices) r = std::max(r, v.norm());
  return r;
}

PolygonModel perturb_polygon_model(const PolygonModel& truth, const PolygonLearnFlags& flags, double fraction,
                                   std::uint64_t seed) {
  if (!(std::isfinite(fraction) && fraction >= 0 && fraction < 1))
    throw InputError("perturbation fraction: must be in [0, 1)");
  std::mt19937_64 rng(seed);
  auto sign = [&rng]() { return (rng() >> 63) ? 1.0 : -1.0; };
  PolygonModel m = truth;
  const double r = polygon_radius(truth.shape);
  // Signs are drawn for every parameter (in layout order) so that the values of one kind do
  // not depend on which other kinds are learned.
  const double s_mu = sign(), s_mass = sign(), s_inertia = sign();
  if (flags.mu) m.mu *= 1.0 + s_mu * fraction;
  if (flags.mass) m.mass *= 1.0 + s_mass * fraction;
  if (flags.inertia) m.inertia *= 1.0 + s_inertia * fraction;
  for (Vec2& v : m.shape.vertices) {
    const double sx = sign(), sy = sign();
    if (flags.vertices) v += 0.5 * fraction * r * Vec2(sx, sy);
  }
  const double s_h = sign(), s_a = sign();
  if (flags.ground) {
    m.ground_height += s_h * 0.5 * fraction * r;
    m.ground_angle += s_a * 0.1 * fraction;
  }
  return m;
}

double polygon_relative_error(const ParameterSet& estimate, const ParameterSet& truth, Index k) {
  if (estimate.size() != truth.size() || k < 0 || k >= truth.size())
    throw InputError("polygon_relative_error: parameter sets of different layouts or index out of range");
  const PolygonLayout layout{(truth.size() - 5) / 2};
  const double d = std::abs(estimate[k].value - truth[k].value);
  if (k <= PolygonLayout::kInertia) return d / std::abs(truth[k].value);
  if (k == layout.ground_angle()) return d;
  return d / polygon_radius(polygon_model(truth).shape);
}

PolygonModel reference_polygon_model() {
  PolygonModel m;
  Polygon p;
  p.vertices = {Vec2(-0.30, -0.22), Vec2(0.34, -0.18), Vec2(0.26, 0.24), Vec2(-0.22, 0.20)};
  m.shape = recentred(p);
  m.mu = 0.4;
  m.mass = 1.5;
  m.inertia = 0.06;
  return m;
}

}  // namespace lcprelax::learn
