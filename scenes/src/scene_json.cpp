// Scene files: JSON reader and writer (scenes/scene_json.hpp documents the schema).
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/core/text_input.hpp>

#include "json_fields.hpp"
#include "scene_warm_start_json.hpp"

#include <climits>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace lcprelax {
namespace {

using scene_json::Json;
using scene_json::element;
using scene_json::fail;
using scene_json::find;
using scene_json::member;

constexpr long long kMaxInt = INT_MAX;

// polygon_validation_error, as an InputError "PATH: message" ("bodies[3].vertices: vertices are
// clockwise").
void check_polygon(const Polygon& polygon, const std::string& path) {
  const std::string error = polygon_validation_error(polygon);
  if (!error.empty()) fail(path, error);
}

double nonnegative(const Json& j, const std::string& path) {
  const double v = scene_json::number(j, path);
  if (v < 0.0) fail(path, "must be >= 0");
  return v;
}

double unit_interval(const Json& j, const std::string& path) {
  const double v = scene_json::number(j, path);
  if (!(v >= 0.0 && v <= 1.0)) fail(path, "must be in [0, 1]");
  return v;
}

double positive(const Json& j, const std::string& path) {
  const double v = scene_json::number(j, path);
  if (!(v > 0.0)) fail(path, "must be > 0");
  return v;
}

int material(const Json& obj, const std::string& path) {
  const Json* m = find(obj, "material");
  return m ? static_cast<int>(scene_json::integer(*m, member(path, "material"), 0, kMaxInt)) : 0;
}

FrictionTable read_friction(const Json& j, const std::string& path) {
  scene_json::expect_object(j, path, {"default", "compliance", "erp", "pairs"});
  FrictionTable table;
  if (const Json* d = find(j, "default")) table.default_mu = nonnegative(*d, member(path, "default"));
  if (const Json* d = find(j, "compliance")) table.default_compliance = nonnegative(*d, member(path, "compliance"));
  if (const Json* d = find(j, "erp")) table.default_erp = unit_interval(*d, member(path, "erp"));
  const Json* pairs = find(j, "pairs");
  if (pairs == nullptr) return table;
  const std::string ppath = member(path, "pairs");
  scene_json::array(*pairs, ppath);
  for (std::size_t i = 0; i < pairs->size(); ++i) {
    const std::string ip = element(ppath, i);
    const Json& p = (*pairs)[i];
    scene_json::expect_object(p, ip, {"materials", "mu", "compliance", "erp"});
    const std::string mp = member(ip, "materials");
    const Json& m = scene_json::require(p, ip, "materials");
    if (!m.is_array() || m.size() != 2) fail(mp, "expected two material indices [a, b]");
    FrictionTable::Pair pair;
    pair.material_a = static_cast<int>(scene_json::integer(m[0], element(mp, 0), 0, kMaxInt));
    pair.material_b = static_cast<int>(scene_json::integer(m[1], element(mp, 1), 0, kMaxInt));
    pair.mu = nonnegative(scene_json::require(p, ip, "mu"), member(ip, "mu"));
    const Json* c = find(p, "compliance");
    pair.compliance = c ? nonnegative(*c, member(ip, "compliance")) : table.default_compliance;
    const Json* e = find(p, "erp");
    pair.erp = e ? unit_interval(*e, member(ip, "erp")) : table.default_erp;
    for (const FrictionTable::Pair& q : table.pairs)
      if ((q.material_a == pair.material_a && q.material_b == pair.material_b) ||
          (q.material_a == pair.material_b && q.material_b == pair.material_a))
        fail(mp, "pair (" + std::to_string(pair.material_a) + ", " +
                     std::to_string(pair.material_b) + ") is listed twice");
    table.pairs.push_back(pair);
  }
  return table;
}

// "velocity_residual": 3 rows (vx, vy, ω) of 4 numbers (per vx, vy, ω and 1).
Mat34 read_velocity_residual(const Json& j, const std::string& path) {
  if (!j.is_array() || j.size() != 3) fail(path, "expected 3 rows of 4 numbers");
  Mat34 w;
  for (std::size_t r = 0; r < 3; ++r) {
    const std::string rp = element(path, r);
    if (!j[r].is_array() || j[r].size() != 4) fail(rp, "expected 4 numbers");
    for (std::size_t c = 0; c < 4; ++c)
      w(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = scene_json::number(j[r][c], element(rp, c));
  }
  return w;
}

RigidBody read_body(const Json& j, const std::string& path) {
  scene_json::expect_object(j, path, {"vertices", "density", "mass", "inertia", "position", "angle",
                                      "velocity", "angular_velocity", "material", "static", "gap_offset",
                                      "velocity_residual"});
  RigidBody body;
  const std::string vpath = member(path, "vertices");
  const Json& vs = scene_json::array(scene_json::require(j, path, "vertices"), vpath);
  Polygon polygon;
  for (std::size_t i = 0; i < vs.size(); ++i) polygon.vertices.push_back(scene_json::vec2(vs[i], element(vpath, i)));
  check_polygon(polygon, vpath);

  if (const Json* s = find(j, "static")) body.is_static = scene_json::boolean(*s, member(path, "static"));
  const Json* p = find(j, "position");
  const Vec2 position = p ? scene_json::vec2(*p, member(path, "position")) : Vec2::Zero();
  const Json* a = find(j, "angle");
  const double angle = a ? scene_json::number(*a, member(path, "angle")) : 0.0;

  // Mass properties: density (from the polygon) or mass and inertia as given.
  const Json* density = find(j, "density");
  const Json* mass = find(j, "mass");
  const Json* inertia = find(j, "inertia");
  if (density && (mass || inertia)) fail(path, "give either 'density' or 'mass' and 'inertia', not both");
  if (density) {
    const std::string dpath = member(path, "density");
    const double rho = positive(*density, dpath);
    MassProperties props;
    try {
      props = mass_properties(polygon, rho);
    } catch (const InputError& e) {  // an extreme density: mass or inertia overflows
      fail(dpath, e.what());
    }
    body.mass = props.mass;
    body.inertia = props.inertia;
  } else if (mass || inertia) {
    if (!mass) fail(path, "'inertia' given without 'mass'");
    if (!inertia) fail(path, "'mass' given without 'inertia'");
    const auto read = body.is_static ? nonnegative : positive;
    body.mass = read(*mass, member(path, "mass"));
    body.inertia = read(*inertia, member(path, "inertia"));
  } else if (!body.is_static) {
    fail(path, "a dynamic body needs 'density' or 'mass' and 'inertia'");
  } else {
    body.mass = body.inertia = 0.0;
  }

  // Recentre the polygon on its centroid C: the centre of mass is position + R(angle) C.
  const Vec2 c = recentre(polygon);
  body.shape = std::move(polygon);
  body.pose << to_world(Vec3(position.x(), position.y(), angle), c), angle;

  const Json* v = find(j, "velocity");
  const Vec2 velocity = v ? scene_json::vec2(*v, member(path, "velocity")) : Vec2::Zero();
  const Json* w = find(j, "angular_velocity");
  body.velocity = Vec3(velocity.x(), velocity.y(), w ? scene_json::number(*w, member(path, "angular_velocity")) : 0.0);
  body.material = material(j, path);
  if (const Json* g = find(j, "gap_offset")) body.gap_offset = scene_json::number(*g, member(path, "gap_offset"));
  if (const Json* w = find(j, "velocity_residual")) body.velocity_residual = read_velocity_residual(*w, member(path, "velocity_residual"));
  return body;
}

HalfPlane read_half_plane(const Json& j, const std::string& path) {
  scene_json::expect_object(j, path, {"normal", "offset", "material"});
  HalfPlane h;
  h.normal = scene_json::vec2(scene_json::require(j, path, "normal"), member(path, "normal"));
  const Json* d = find(j, "offset");
  h.offset = d ? scene_json::number(*d, member(path, "offset")) : 0.0;
  const double n = h.normal.norm();
  if (!(n > 0.0)) fail(member(path, "normal"), "zero length");
  if (std::abs(n - 1.0) > 4.0 * std::numeric_limits<double>::epsilon()) {  // keep unit normals exact
    h.normal /= n;
    h.offset /= n;
  }
  h.material = material(j, path);
  return h;
}

Segment read_segment(const Json& j, const std::string& path) {
  scene_json::expect_object(j, path, {"a", "b", "material"});
  Segment s;
  s.a = scene_json::vec2(scene_json::require(j, path, "a"), member(path, "a"));
  s.b = scene_json::vec2(scene_json::require(j, path, "b"), member(path, "b"));
  if (s.a == s.b) fail(path, "end points 'a' and 'b' coincide");
  s.material = material(j, path);
  return s;
}

// Reads the array `key` of the scene with `read(element, path)`.
template <class T, class Read>
std::vector<T> read_list(const Json& root, const char* key, Read read) {
  std::vector<T> out;
  const Json* list = find(root, key);
  if (list == nullptr) return out;
  scene_json::array(*list, key);
  for (std::size_t i = 0; i < list->size(); ++i) out.push_back(read((*list)[i], element(key, i)));
  return out;
}

}  // namespace

Scene parse_scene(std::string_view json_text) {
  const Json root = scene_json::parse_json(json_text);
  scene_json::expect_object(root, "", {"name", "gravity", "dt", "steps", "model", "softening", "margin", "friction",
                                       "bodies", "half_planes", "segments", "warm_start"});
  Scene scene;
  if (const Json* n = find(root, "name")) scene.name = scene_json::string(*n, "name");
  if (const Json* g = find(root, "gravity")) scene.world.gravity = scene_json::vec2(*g, "gravity");
  SimulatorSettings& s = scene.settings;
  if (const Json* dt = find(root, "dt")) s.dt = positive(*dt, "dt");
  if (const Json* k = find(root, "steps")) scene.steps = static_cast<int>(scene_json::integer(*k, "steps", 0, kMaxInt));
  if (const Json* m = find(root, "model")) {
    const std::string model = scene_json::string(*m, "model");
    try {
      s.model = parse_contact_model(model);
    } catch (const InputError& e) {  // its message echoes the whole string: cut it
      const std::string what = e.what();
      fail("model", model.size() > text::kMaxEchoChars
                        ? "unknown contact model " + text::quote(model) + what.substr(what.rfind(" ("))
                        : what);
    }
  }
  if (const Json* m = find(root, "softening")) {
    const std::string method = scene_json::string(*m, "softening");
    try {
      s.convex_softening.method = parse_normal_softening(method);
    } catch (const InputError&) {
      fail("softening", "unknown softening " + text::quote(method) +
                            " (valid: exp_phi, linear_penalty, mujoco_impedance, or exp, penalty, impedance)");
    }
  }
  if (const Json* m = find(root, "margin")) s.margin = nonnegative(*m, "margin");
  scene.validate();
  if (const Json* f = find(root, "friction")) scene.world.friction = read_friction(*f, "friction");
  scene.world.bodies = read_list<RigidBody>(root, "bodies", read_body);
  scene.world.half_planes = read_list<HalfPlane>(root, "half_planes", read_half_plane);
  scene.world.segments = read_list<Segment>(root, "segments", read_segment);
  if (const Json* ws = find(root, "warm_start"))
    scene.warm_start = scene_json::read_warm_start(*ws, static_cast<int>(scene.world.bodies.size()));
  return scene;
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file");
  // At most kMaxSceneBytes are read (a device such as /dev/zero never ends).
  std::string json;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    const std::string_view chunk(buffer, static_cast<std::size_t>(in.gcount()));
    if (const std::size_t nul = chunk.find('\0'); nul != std::string_view::npos)  // never in JSON text
      throw InputError(path + ": NUL byte at offset " + std::to_string(json.size() + nul) + " (not a JSON text)");
    json.append(chunk);
    if (json.size() > kMaxSceneBytes)
      throw InputError(path + ": scene file larger than " + std::to_string(kMaxSceneBytes) + " bytes (the limit)");
  }
  try {
    return parse_scene(json);
  } catch (const InputError& e) {
    throw InputError(text::clip_message(path + ": " + e.what()));
  }
}

std::string write_scene(const Scene& scene) {
  using scene_json::finite;
  scene.validate();
  const World& w = scene.world;
  Json root = Json::object();
  root["name"] = scene.name;
  root["gravity"] = finite(w.gravity, "gravity");
  root["dt"] = scene.settings.dt;
  root["steps"] = scene.steps;
  root["model"] = to_string(scene.settings.model);
  root["softening"] = to_string(scene.settings.convex_softening.method);
  root["margin"] = scene.settings.margin;
  Json pairs = Json::array();
  for (std::size_t i = 0; i < w.friction.pairs.size(); ++i) {
    const FrictionTable::Pair& p = w.friction.pairs[i];
    Json pair = {{"materials", {p.material_a, p.material_b}},
                 {"mu", finite(p.mu, member(element("friction.pairs", i), "mu"))}};
    if (w.friction.has_softness()) {
      pair["compliance"] = finite(p.compliance, member(element("friction.pairs", i), "compliance"));
      pair["erp"] = finite(p.erp, member(element("friction.pairs", i), "erp"));
    }
    pairs.push_back(pair);
  }
  root["friction"] = {{"default", finite(w.friction.default_mu, "friction.default")}, {"pairs", pairs}};
  if (w.friction.has_softness()) {
    root["friction"]["compliance"] = finite(w.friction.default_compliance, "friction.compliance");
    root["friction"]["erp"] = finite(w.friction.default_erp, "friction.erp");
  }
  Json bodies = Json::array();
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const RigidBody& b = w.bodies[i];
    const std::string path = element("bodies", i);
    Json vertices = Json::array();
    for (std::size_t k = 0; k < b.shape.vertices.size(); ++k)
      vertices.push_back(finite(b.shape.vertices[k], element(member(path, "vertices"), k)));
    Json body = {{"vertices", vertices}};
    if (!b.is_static || b.mass != 0.0 || b.inertia != 0.0) {
      body["mass"] = finite(b.mass, member(path, "mass"));
      body["inertia"] = finite(b.inertia, member(path, "inertia"));
    }
    body["position"] = finite(Vec2(b.pose.x(), b.pose.y()), member(path, "position"));
    body["angle"] = finite(b.pose.z(), member(path, "angle"));
    body["velocity"] = finite(Vec2(b.velocity.x(), b.velocity.y()), member(path, "velocity"));
    body["angular_velocity"] = finite(b.velocity.z(), member(path, "angular_velocity"));
    body["material"] = b.material;
    body["static"] = b.is_static;
    if (b.gap_offset != 0.0) body["gap_offset"] = finite(b.gap_offset, member(path, "gap_offset"));
    if ((b.velocity_residual.array() != 0.0).any()) {
      Json rows = Json::array();
      for (Eigen::Index r = 0; r < 3; ++r) {
        Json row = Json::array();
        for (Eigen::Index c = 0; c < 4; ++c)
          row.push_back(finite(b.velocity_residual(r, c), element(element(member(path, "velocity_residual"), static_cast<std::size_t>(r)), static_cast<std::size_t>(c))));
        rows.push_back(std::move(row));
      }
      body["velocity_residual"] = std::move(rows);
    }
    bodies.push_back(std::move(body));
  }
  root["bodies"] = std::move(bodies);
  Json half_planes = Json::array();
  for (std::size_t i = 0; i < w.half_planes.size(); ++i) {
    const HalfPlane& h = w.half_planes[i];
    const std::string path = element("half_planes", i);
    half_planes.push_back({{"normal", finite(h.normal, member(path, "normal"))},
                           {"offset", finite(h.offset, member(path, "offset"))},
                           {"material", h.material}});
  }
  root["half_planes"] = std::move(half_planes);
  Json segments = Json::array();
  for (std::size_t i = 0; i < w.segments.size(); ++i) {
    const Segment& s = w.segments[i];
    const std::string path = element("segments", i);
    segments.push_back({{"a", finite(s.a, member(path, "a"))},
                        {"b", finite(s.b, member(path, "b"))},
                        {"material", s.material}});
  }
  root["segments"] = std::move(segments);
  if (!scene.warm_start.empty()) root["warm_start"] = scene_json::warm_start_json(scene.warm_start, static_cast<int>(w.bodies.size()));
  return scene_json::pretty(root);
}

void save_scene(const std::string& path, const Scene& scene) {
  const std::string text = write_scene(scene);
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot write scene file");
}

}  // namespace lcprelax
