// Scene JSON files: the example scenes load with the documented meaning, write_scene then
// parse_scene reproduces a world exactly, and every validation rule throws InputError
// naming the field path.
#include <gtest/gtest.h>

#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

const std::string kDir = std::string(LCPRELAX_TEST_DATA_DIR) + "/scenes/";
constexpr double kPi = 3.14159265358979323846;

// A valid scene with every kind of entry; tests break one field at a time.
const char* const kBase = R"({
  "name": "base", "gravity": [0, -9.81], "dt": 0.01, "steps": 10, "model": "convex",
  "margin": 0.02,
  "friction": {"default": 0.4, "pairs": [{"materials": [0, 1], "mu": 0.9}]},
  "bodies": [
    {"vertices": [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]], "density": 2,
     "position": [0, 0.5]},
    {"vertices": [[0, 0], [1, 0], [0, 1]], "mass": 3, "inertia": 0.25, "position": [2, 0],
     "angle": 0.3, "velocity": [1, -2], "angular_velocity": 0.5, "material": 1},
    {"vertices": [[-1, -1], [1, -1], [1, 1], [-1, 1]], "static": true, "position": [5, 1]}
  ],
  "half_planes": [{"normal": [0, 2], "offset": 1}],
  "segments": [{"a": [-3, 0], "b": [-3, 2], "material": 1}]
})";

// kBase with the first occurrence of `from` replaced by `to`.
std::string edit(const std::string& from, const std::string& to) {
  std::string s = kBase;
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

// parse_scene(text) throws InputError whose message contains every one of `parts`.
void expect_error(const std::string& text, std::initializer_list<const char*> parts) {
  try {
    parse_scene(text);
    ADD_FAILURE() << "no error; expected: " << *parts.begin();
  } catch (const InputError& e) {
    for (const char* p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

void expect_same(const World& a, const World& b) {
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(a.bodies[i].shape.vertices, b.bodies[i].shape.vertices);
    EXPECT_EQ(a.bodies[i].mass, b.bodies[i].mass);
    EXPECT_EQ(a.bodies[i].inertia, b.bodies[i].inertia);
    EXPECT_EQ(a.bodies[i].pose, b.bodies[i].pose);
    EXPECT_EQ(a.bodies[i].velocity, b.bodies[i].velocity);
    EXPECT_EQ(a.bodies[i].material, b.bodies[i].material);
    EXPECT_EQ(a.bodies[i].is_static, b.bodies[i].is_static);
  }
  ASSERT_EQ(a.half_planes.size(), b.half_planes.size());
  for (std::size_t i = 0; i < a.half_planes.size(); ++i) {
    EXPECT_EQ(a.half_planes[i].normal, b.half_planes[i].normal);
    EXPECT_EQ(a.half_planes[i].offset, b.half_planes[i].offset);
    EXPECT_EQ(a.half_planes[i].material, b.half_planes[i].material);
  }
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    EXPECT_EQ(a.segments[i].a, b.segments[i].a);
    EXPECT_EQ(a.segments[i].b, b.segments[i].b);
    EXPECT_EQ(a.segments[i].material, b.segments[i].material);
  }
  EXPECT_EQ(a.gravity, b.gravity);
  EXPECT_EQ(a.friction.default_mu, b.friction.default_mu);
  ASSERT_EQ(a.friction.pairs.size(), b.friction.pairs.size());
  for (std::size_t i = 0; i < a.friction.pairs.size(); ++i) {
    EXPECT_EQ(a.friction.pairs[i].material_a, b.friction.pairs[i].material_a);
    EXPECT_EQ(a.friction.pairs[i].material_b, b.friction.pairs[i].material_b);
    EXPECT_EQ(a.friction.pairs[i].mu, b.friction.pairs[i].mu);
  }
}

TEST(SceneJson, BaseSceneHasTheDocumentedMeaning) {
  const Scene s = parse_scene(kBase);
  EXPECT_EQ(s.name, "base");
  EXPECT_EQ(s.settings.model, ContactModel::convex);
  EXPECT_EQ(s.steps, 10);
  EXPECT_DOUBLE_EQ(s.settings.margin, 0.02);
  EXPECT_DOUBLE_EQ(s.world.friction.mu(1, 0), 0.9);
  EXPECT_DOUBLE_EQ(s.world.friction.mu(0, 0), 0.4);
  ASSERT_EQ(s.world.bodies.size(), 3u);
  EXPECT_DOUBLE_EQ(s.world.bodies[0].mass, 2.0);  // ρ·1 m²
  EXPECT_DOUBLE_EQ(s.world.bodies[0].inertia, 2.0 / 6.0);
  // The triangle (0,0),(1,0),(0,1) has its centroid at (1/3, 1/3): recentred, and the centre
  // of mass is position + R(0.3)·(1/3, 1/3).
  const RigidBody& t = s.world.bodies[1];
  const double c = std::cos(0.3), sn = std::sin(0.3), k = 1.0 / 3.0;
  EXPECT_NEAR(t.pose.x(), 2 + (c - sn) * k, 1e-15);
  EXPECT_NEAR(t.pose.y(), (sn + c) * k, 1e-15);
  EXPECT_EQ(t.pose.z(), 0.3);
  EXPECT_NEAR(t.shape.vertices[0].x(), -k, 1e-15);
  EXPECT_EQ(t.mass, 3.0);
  EXPECT_EQ(t.velocity, Vec3(1, -2, 0.5));
  EXPECT_TRUE(s.world.bodies[2].is_static);
  EXPECT_EQ(s.world.bodies[2].mass, 0.0);
  // The half-plane {(0,2)·p ≥ 1} is normalized to {(0,1)·p ≥ 0.5}.
  EXPECT_EQ(s.world.half_planes[0].normal, Vec2(0, 1));
  EXPECT_EQ(s.world.half_planes[0].offset, 0.5);
  EXPECT_EQ(s.world.segments[0].material, 1);
}

TEST(SceneJson, DefaultsForAnEmptyObject) {
  const Scene s = parse_scene("{}");
  EXPECT_EQ(s.settings.dt, SimulatorSettings{}.dt);
  EXPECT_EQ(s.steps, Scene{}.steps);
  EXPECT_EQ(s.settings.model, ContactModel::lcp);
  EXPECT_EQ(s.world.gravity, Vec2(0, -9.81));
  EXPECT_TRUE(s.world.bodies.empty());
}

TEST(SceneJson, WriteThenParseGivesTheSameScene) {
  Scene a = parse_scene(kBase);
  a.world.bodies[0].pose = Vec3(0.1, 1.0 / 3.0, -2.5e-7);  // values without short decimals
  a.world.bodies[0].velocity = Vec3(std::sqrt(2.0), -1e-300, 1e300);
  a.world.gravity = Vec2(0.1, -9.81);
  const std::string text = write_scene(a);
  const Scene b = parse_scene(text);
  EXPECT_EQ(b.name, a.name);
  EXPECT_EQ(b.settings.dt, a.settings.dt);
  EXPECT_EQ(b.steps, a.steps);
  EXPECT_EQ(b.settings.model, a.settings.model);
  EXPECT_EQ(b.settings.margin, a.settings.margin);
  expect_same(a.world, b.world);
  EXPECT_EQ(write_scene(b), text);
}

TEST(SceneJson, ExampleFilesLoadAndRoundTrip) {
  const Scene box = load_scene(kDir + "box_on_ground.json");
  ASSERT_EQ(box.world.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(box.world.bodies[0].mass, 1000.0);
  EXPECT_DOUBLE_EQ(box.world.bodies[0].inertia, 1000.0 / 6.0);
  EXPECT_EQ(box.world.half_planes.size(), 1u);

  const Scene stack = load_scene(kDir + "box_stack.json");
  ASSERT_EQ(stack.world.bodies.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(stack.world.bodies[i].pose.x(), 0.0, 1e-15);
    EXPECT_NEAR(stack.world.bodies[i].pose.y(), 0.5 + i, 1e-15);
    EXPECT_NEAR(stack.world.bodies[i].inertia, 1000.0 / 6.0, 1e-9);
  }
  EXPECT_EQ(stack.world.friction.mu(1, 0), 0.8);

  const Scene tri = load_scene(kDir + "triangle_on_incline.json");
  EXPECT_EQ(tri.settings.model, ContactModel::convex);
  EXPECT_NEAR(tri.world.half_planes[0].normal.norm(), 1.0, 1e-15);
  EXPECT_EQ(tri.world.segments.size(), 1u);
  for (const Scene* s : {&box, &stack, &tri}) expect_same(parse_scene(write_scene(*s)).world, s->world);
}

TEST(SceneJson, ContactModelText) {
  EXPECT_EQ(parse_contact_model("lcp"), ContactModel::lcp);
  EXPECT_EQ(parse_contact_model(to_string(ContactModel::convex)), ContactModel::convex);
  EXPECT_THROW(parse_contact_model("LCP"), InputError);
  expect_error(edit(R"("model": "convex")", R"("model": "qp")"), {"model: unknown contact model 'qp'"});
}

// "softening" (the convex model's normal softening) is read, defaults to exp_phi, round-trips,
// and a bad value names the field.
TEST(SceneJson, SofteningIsReadAndWritten) {
  EXPECT_EQ(parse_scene(kBase).settings.convex_softening.method, NormalSoftening::exp_phi);
  const Scene s = parse_scene(edit(R"("model": "convex")", R"("model": "convex", "softening": "impedance")"));
  EXPECT_EQ(s.settings.convex_softening.method, NormalSoftening::mujoco_impedance);
  EXPECT_EQ(parse_scene(write_scene(s)).settings.convex_softening.method, NormalSoftening::mujoco_impedance);
  expect_error(edit(R"("model": "convex")", R"("model": "convex", "softening": "hard")"),
               {"softening: unknown softening 'hard'"});
}

TEST(SceneJson, PolygonErrorsNameTheBody) {
  // The messages are polygon_validation_error's (contact/polygon.hpp), prefixed by the field path.
  expect_error(edit("[[0, 0], [1, 0], [0, 1]]", "[[0, 0], [0, 1], [1, 0]]"),
               {"bodies[1].vertices: vertices are clockwise"});
  expect_error(edit("[[0, 0], [1, 0], [0, 1]]", "[[0, 0], [2, 0], [0.5, 0.5], [0, 2]]"),
               {"bodies[1].vertices: vertex 2 makes the polygon non-convex"});
  expect_error(edit("[[0, 0], [1, 0], [0, 1]]", "[[0, 0], [1, 0], [2, 0], [0, 1]]"),
               {"bodies[1].vertices: vertex 1 makes the polygon non-convex"});
  expect_error(edit("[[0, 0], [1, 0], [0, 1]]", "[[0, 0], [1, 0], [1, 0], [0, 1]]"),
               {"bodies[1].vertices: vertices 1 and 2 coincide"});
  expect_error(edit("[[0, 0], [1, 0], [0, 1]]", "[[0, 0], [1, 0]]"), {"bodies[1].vertices", "at least 3"});
  std::string many = "[";
  for (int k = 0; k < 13; ++k)
    many += (k ? ", [" : "[") + std::to_string(std::cos(k * 2 * kPi / 13)) + ", " +
            std::to_string(std::sin(k * 2 * kPi / 13)) + "]";
  expect_error(edit("[[0, 0], [1, 0], [0, 1]]", many + "]"), {"bodies[1].vertices", "13 vertices, at most 12"});
  // A pentagram turns left at every vertex but winds twice.
  std::string star = "[";
  for (int k = 0; k < 5; ++k)
    star += (k ? ", [" : "[") + std::to_string(std::cos(k * 4 * kPi / 5)) + ", " +
            std::to_string(std::sin(k * 4 * kPi / 5)) + "]";
  expect_error(edit("[[0, 0], [1, 0], [0, 1]]", star + "]"), {"bodies[1].vertices: polygon winds more than once"});
  expect_error(edit("[[0, 0], [1, 0], [0, 1]]", "[[0, 0], [1, 0, 3], [0, 1]]"), {"bodies[1].vertices[1]"});
  expect_error(edit(R"("vertices": [[0, 0], [1, 0], [0, 1]], )", ""), {"bodies[1]: missing required key 'vertices'"});
}

TEST(SceneJson, RecentringKeepsTheWorldShape) {
  // A 2 × 1 rectangle with a corner at its origin, at position (1, −2) rotated by 0.7: the
  // world shape is position + R(0.7) v; the body's vertices are recentred on C = (1, ½) and
  // its pose (centre of mass) is position + R(0.7) C.
  const std::vector<Vec2> v = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const Scene s = parse_scene(R"({"bodies": [{"vertices": [[0, 0], [2, 0], [2, 1], [0, 1]],
      "density": 3, "position": [1, -2], "angle": 0.7}]})");
  const RigidBody& b = s.world.bodies.at(0);
  const Vec3 reference(1.0, -2.0, 0.7);
  const double c = std::cos(0.7), sn = std::sin(0.7);
  EXPECT_NEAR(b.pose.x(), 1.0 + c * 1.0 - sn * 0.5, 1e-15);
  EXPECT_NEAR(b.pose.y(), -2.0 + sn * 1.0 + c * 0.5, 1e-15);
  EXPECT_EQ(b.pose.z(), 0.7);
  const std::vector<Vec2> world = world_vertices(b);
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_NEAR((world[i] - to_world(reference, v[i])).norm(), 0.0, 1e-14);
  EXPECT_LT(mass_properties(b.shape, 1.0).centroid.norm(), 1e-15);
  EXPECT_DOUBLE_EQ(b.mass, 6.0);                       // ρ·2·1
  EXPECT_DOUBLE_EQ(b.inertia, 6.0 * (4.0 + 1.0) / 12);  // m(w² + h²)/12

  // Centred vertices are kept bit for bit, and the position is the centre of mass.
  const Scene t = parse_scene(R"({"bodies": [{"vertices": [[-0.1, -0.3], [0.1, -0.3], [0.1, 0.3], [-0.1, 0.3]],
      "density": 1, "position": [0.3, 0.7], "angle": 2}]})");
  EXPECT_EQ(t.world.bodies[0].shape.vertices[0], Vec2(-0.1, -0.3));
  EXPECT_EQ(t.world.bodies[0].pose, Vec3(0.3, 0.7, 2.0));
}

TEST(SceneJson, MassErrorsNameTheField) {
  expect_error(edit(R"("mass": 3)", R"("mass": 0)"), {"bodies[1].mass: must be > 0"});
  expect_error(edit(R"("inertia": 0.25)", R"("inertia": -1)"), {"bodies[1].inertia: must be > 0"});
  expect_error(edit(R"("density": 2)", R"("density": 0)"), {"bodies[0].density: must be > 0"});
  expect_error(edit(R"("density": 2)", R"("density": 2, "mass": 1, "inertia": 1)"),
               {"bodies[0]", "either 'density' or 'mass'"});
  expect_error(edit(R"("mass": 3, "inertia": 0.25)", R"("mass": 3)"), {"bodies[1]", "'mass' given without 'inertia'"});
  expect_error(edit(R"("mass": 3, "inertia": 0.25, )", ""), {"bodies[1]", "needs 'density' or 'mass'"});
  // Static bodies may have zero mass, not a negative one.
  expect_error(edit(R"("static": true)", R"("static": true, "mass": -1, "inertia": 0)"),
               {"bodies[2].mass: must be >= 0"});
}

TEST(SceneJson, UnknownAndDuplicateKeys) {
  expect_error(edit(R"("density": 2)", R"("densty": 2)"), {"unknown key 'densty' in bodies[0]"});
  expect_error(edit(R"("dt": 0.01)", R"("dt": 0.01, "time_step": 1)"), {"unknown key 'time_step' in the scene"});
  expect_error(edit(R"("mu": 0.9)", R"("mu": 0.9, "mu2": 1)"), {"unknown key 'mu2' in friction.pairs[0]"});
  expect_error(edit(R"("offset": 1)", R"("offset": 1, "offset": 2)"), {"duplicate key 'offset' in half_planes[0]"});
  expect_error(edit(R"("mass": 3)", R"("mass": 3, "mass": 4)"), {"duplicate key 'mass' in bodies[1]"});
}

TEST(SceneJson, TypeErrorsAndNonFiniteNumbers) {
  expect_error(edit(R"("mass": 3)", R"("mass": "nan")"), {"bodies[1].mass: expected a number, got string"});
  expect_error(edit(R"("dt": 0.01)", R"("dt": "Infinity")"), {"dt: expected a number, got string"});
  expect_error(edit(R"("angle": 0.3)", R"("angle": "0.3")"), {"bodies[1].angle: expected a number, got string"});
  expect_error(edit(R"("position": [2, 0])", R"("position": [2, null])"), {"bodies[1].position[1]: expected a number, got null"});
  expect_error(edit(R"("angle": 0.3)", R"("angle": 1e999)"), {"invalid JSON", "overflow"});
  expect_error(edit(R"("angle": 0.3)", R"("angle": NaN)"), {"invalid JSON"});
  expect_error(edit(R"("steps": 10)", R"("steps": 2.5)"), {"steps: expected an integer, got 2.5"});
  expect_error(edit(R"("steps": 10)", R"("steps": -1)"), {"steps: must be in [0, "});
  expect_error(edit(R"("material": 1)", R"("material": true)"), {"bodies[1].material: expected an integer, got boolean"});
  expect_error(edit(R"("static": true)", R"("static": 1)"), {"bodies[2].static: expected a boolean, got number"});
  expect_error(edit(R"("name": "base")", R"("name": 7)"), {"name: expected a string, got number"});
  expect_error(edit(R"("bodies": [)", R"("bodies": {"x": [)") , {"invalid JSON"});
  expect_error(R"({"bodies": {}})", {"bodies: expected an array, got object"});
  expect_error("[1, 2]", {"expected an object, got array"});
  expect_error("{", {"invalid JSON"});
}

TEST(SceneJson, SettingsFrictionAndStaticShapeErrors) {
  expect_error(edit(R"("dt": 0.01)", R"("dt": 0)"), {"dt: must be > 0"});
  expect_error(edit(R"("margin": 0.02)", R"("margin": -0.1)"), {"margin: must be >= 0"});
  expect_error(edit(R"("default": 0.4)", R"("default": -0.4)"), {"friction.default: must be >= 0"});
  expect_error(edit(R"("mu": 0.9)", R"("mu": -1)"), {"friction.pairs[0].mu: must be >= 0"});
  expect_error(edit(R"("materials": [0, 1])", R"("materials": [0])"), {"friction.pairs[0].materials"});
  expect_error(edit(R"("materials": [0, 1])", R"("materials": [0, -1])"), {"friction.pairs[0].materials[1]"});
  expect_error(edit(R"({"materials": [0, 1], "mu": 0.9})",
                    R"({"materials": [0, 1], "mu": 0.9}, {"materials": [1, 0], "mu": 0.1})"),
               {"friction.pairs[1].materials", "listed twice"});
  expect_error(edit(R"("normal": [0, 2])", R"("normal": [0, 0])"), {"half_planes[0].normal: zero length"});
  expect_error(edit(R"("normal": [0, 2], )", ""), {"half_planes[0]: missing required key 'normal'"});
  expect_error(edit(R"("b": [-3, 2])", R"("b": [-3, 0])"), {"segments[0]", "coincide"});
  expect_error(edit(R"("gravity": [0, -9.81])", R"("gravity": [0, -9.81, 0])"), {"gravity: expected [x, y]"});
}

TEST(SceneJson, LoadErrorsNameTheFile) {
  try {
    load_scene(kDir + "no_such_scene.json");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_scene.json: cannot open"), std::string::npos);
  }
}

TEST(SceneJson, WriterRejectsNonFiniteValues) {
  Scene s = parse_scene(kBase);
  s.world.bodies[1].velocity.z() = NAN;
  try {
    write_scene(s);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies[1].angular_velocity: not finite"), std::string::npos) << e.what();
  }
  s = parse_scene(kBase);
  s.settings.dt = -1;
  EXPECT_THROW(write_scene(s), InputError);
}

}  // namespace
}  // namespace lcprelax
