// Binds the scene generators of scenes/pile_scene.hpp as lcprelax.pile_scene,
// box_stack_scene, pyramid_scene and incline_scene. Each returns the scene as JSON text in
// the schema of scenes/scene_json.hpp (write_scene: round-trip precision, so
// lcprelax.Simulator(text) simulates exactly the generated scene); save it to a file to
// reuse it with the command line tool.
//
// Conventions (pile_scene.hpp): SI units (m, kg/m², s, rad); gravity (0, −9.81) m/s²; every
// pair has friction coefficient `mu`; the ground is the half-plane y ≥ 0. Invalid options
// raise InputError naming the field (check_pile_options and the generators' checks).
#include "bindings.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene_json.hpp>

#include <cstdint>
#include <string>

namespace lcprelax::python {
namespace {

ContactModel model_from(const std::string& text) { return parse_contact_model(text); }

/// Generates and serializes a scene with the GIL released.
template <class Make>
std::string scene_text(Make make) {
  py::gil_scoped_release nogil;
  return write_scene(make());
}

}  // namespace

void bind_scenes(py::module_& m) {
  m.def(
      "pile_scene",
      [](int bodies, long long seed, double min_size, double max_size, int min_vertices, int max_vertices,
         double density, double mu, double container_width, double dt, const std::string& model) {
        if (seed < 0) throw InputError("seed: must be >= 0");
        PileOptions o;
        o.bodies = bodies, o.seed = static_cast<std::uint64_t>(seed);
        o.min_size = min_size, o.max_size = max_size, o.min_vertices = min_vertices, o.max_vertices = max_vertices;
        o.density = density, o.mu = mu, o.container_width = container_width, o.dt = dt, o.model = model_from(model);
        check_pile_options(o);
        return scene_text([&] { return make_pile_scene(o); });
      },
      py::kw_only(), py::arg("bodies") = 200, py::arg("seed") = 1, py::arg("min_size") = 0.05,
      py::arg("max_size") = 0.15, py::arg("min_vertices") = 3, py::arg("max_vertices") = 8,
      py::arg("density") = 1000.0, py::arg("mu") = 0.5, py::arg("container_width") = 0.0, py::arg("dt") = 1e-2,
      py::arg("model") = "lcp",
      "A random pile of convex polygons between two walls above the ground y >= 0, as scene JSON\n"
      "text (scenes/pile_scene.hpp): bodies (1..1e6), seed, circumradius range min_size..max_size\n"
      "(m), vertex counts min_vertices..max_vertices (3..12), density (kg/m^2), mu, container_width\n"
      "(m, 0: automatic), dt (s), model ('lcp' | 'convex'). No two shapes touch initially.");
  m.def(
      "box_stack_scene",
      [](int boxes, double size, double mu) { return scene_text([&] { return make_box_stack_scene(boxes, size, mu); }); },
      py::kw_only(), py::arg("boxes") = 3, py::arg("size") = 1.0, py::arg("mu") = 0.5,
      "A column of `boxes` square boxes of side `size` (m) resting on the ground (gaps 0), as\n"
      "scene JSON text; density 1000 kg/m^2.");
  m.def(
      "pyramid_scene",
      [](int base, double size, double mu) { return scene_text([&] { return make_pyramid_scene(base, size, mu); }); },
      py::kw_only(), py::arg("base") = 3, py::arg("size") = 1.0, py::arg("mu") = 0.5,
      "A pyramid of square boxes (base boxes in the bottom row) resting on the ground, as scene JSON text.");
  m.def(
      "incline_scene",
      [](double angle, double mu, double size, double density) {
        return scene_text([&] { return make_incline_scene(angle, mu, size, density); });
      },
      py::kw_only(), py::arg("angle"), py::arg("mu"), py::arg("size") = 1.0, py::arg("density") = 1000.0,
      "A square box resting on the half-plane through the origin tilted by `angle` (rad, ccw), as\n"
      "scene JSON text. With mu < tan|angle| it slides down (towards -x for angle > 0).");
}

}  // namespace lcprelax::python
