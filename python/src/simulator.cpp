// Binds lcprelax::Simulator (models/simulator.hpp) as lcprelax.Simulator, built from a scene
// (scenes/scene_json.hpp: a JSON file path or the JSON text itself), with StepStats as a
// read-only result object.
//
// Conventions (world/world.hpp, docs/conventions.md, docs/python.md "Simulation"), SI units:
// - poses: (nbodies, 3) float64 rows (x, y, θ) in m, m, rad (centre of mass, θ
//   counter-clockwise); velocities: rows (vx, vy, ω) in m/s, m/s, rad/s. EVERY body of the
//   scene's "bodies" list is a row, static bodies included (they never move; is_static
//   tells which); half-planes and segments are not bodies.
// - step(applied): applied is None or (nbodies, 3) rows (fx, fy, τ) in N, N, N·m acting
//   during the step in addition to gravity (rows of static bodies are ignored).
// - contacts: those found at the start of the last step (before it: none), normal from
//   body b to body a, gap φ (m) negative when overlapping; body_b = −1 for a half-plane or
//   segment (static_kind, static_index name it).
// Settings: the scene file's (dt, model, margin, softening), then keyword overrides named as
// the SimulatorSettings fields (model as 'lcp' | 'convex', softening as the convex model's
// normal softening, qp= and lemke= as dicts of QpSettings / LemkeSettings fields); invalid
// values raise InputError with SimulatorSettings::validation_error()'s message.
// step() releases the GIL; one Simulator serves one call at a time (else UsageError).
#include "bindings.hpp"
#include "scene_source.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/scene.hpp>
#include <lcprelax/scenes/scene_json.hpp>

#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace lcprelax::python {
namespace {

/// An enum setting named by a local table (the library has no to_string for it).
template <class S, class E>
SettingField<S> named_field(const char* name, E S::*member, std::vector<std::pair<E, const char*>> names) {
  return {name,
          [=](S& s, py::handle v) {
            const std::string text = setting_string(v, name);
            std::string valid;
            for (const auto& [e, n] : names) {
              if (text == n) {
                s.*member = e;
                return;
              }
              valid += (valid.empty() ? "" : ", ") + std::string(n);
            }
            throw InputError(std::string(name) + " = '" + text + "' is not one of: " + valid);
          },
          [=](const S& s) {
            for (const auto& [e, n] : names)
              if (s.*member == e) return py::object(py::str(n));
            return py::object(py::none());
          }};
}

/// A nested settings struct given as a dict of its own keyword fields (qp=, lemke=).
template <class S, class N>
SettingField<S> nested_field(const char* name, N S::*member, const std::vector<SettingField<N>>& (*fields)()) {
  return {name,
          [=](S& s, py::handle v) {
            if (!py::isinstance<py::dict>(v)) throw py::type_error(std::string(name) + " must be a dict of settings");
            py::kwargs kw;
            for (auto item : py::reinterpret_borrow<py::dict>(v)) kw[item.first] = item.second;
            apply_settings(s.*member, fields(), kw, std::string("Simulator(") + name + "=...)");
          },
          [=](const S& s) { return py::object(settings_dict(s.*member, fields())); }};
}

const std::vector<SettingField<SimulatorSettings>>& simulator_fields() {
  using S = SimulatorSettings;
  static const std::vector<SettingField<S>> fields = {
      double_field("dt", &S::dt),
      named_field("model", &S::model, {{ContactModel::lcp, "lcp"}, {ContactModel::convex, "convex"}}),
      double_field("margin", &S::margin),
      double_field("penetration_slop", &S::penetration_slop),
      double_field("convex_rho", &S::convex_rho),
      SettingField<S>{"softening",
                      [](S& s, py::handle v) {
                        s.convex_softening.method = parse_normal_softening(setting_string(v, "softening"));
                      },
                      [](const S& s) { return py::object(py::str(to_string(s.convex_softening.method))); }},
      named_field("convex_formulation", &S::convex_formulation,
                  {{ConvexFormulation::automatic, "automatic"}, {ConvexFormulation::dual, "dual"},
                   {ConvexFormulation::lifted, "lifted"}}),
      named_field("convex_solver", &S::convex_solver,
                  {{ConvexSolver::interior_point, "interior_point"}, {ConvexSolver::active_set_newton, "active_set_newton"}}),
      bool_field("post_stabilization", &S::post_stabilization),
      int_field("post_stabilization_passes", &S::post_stabilization_passes),
      bool_field("warm_start", &S::warm_start),
      int_field("threads", &S::threads),
      bool_field("reuse_convex_solvers", &S::reuse_convex_solvers),
      bool_field("convex_release_open_contacts", &S::convex_release_open_contacts),
      nested_field("qp", &S::qp, &qp_fields),
      nested_field("lemke", &S::lemke, &lemke_fields)};
  return fields;
}

std::string type_name(py::handle obj) { return py::str(py::type::handle_of(obj).attr("__qualname__")); }

}  // namespace

Scene scene_from_python(const py::object& source) {
  const bool text = PyUnicode_Check(source.ptr());
  if (!text && !py::hasattr(source, "__fspath__"))
    throw py::type_error("scene must be a JSON file path (str or os.PathLike) or JSON text, got " + type_name(source));
  if (text) {
    const std::string s = source.cast<std::string>();
    const auto first = s.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && s[first] == '{') {
      py::gil_scoped_release nogil;
      return parse_scene(s);
    }
  }
  const py::object path = py::module_::import("os").attr("fspath")(source);
  if (!PyUnicode_Check(path.ptr())) throw py::type_error("scene path must be a text path (bytes are not supported)");
  const std::string p = path.cast<std::string>();
  py::gil_scoped_release nogil;
  return load_scene(p);
}

namespace {

/// (rows, 3) float64 array from Vec3 rows.
py::array_t<double> rows3(const std::vector<Vec3>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int j = 0; j < 3; ++j) m(static_cast<py::ssize_t>(i), j) = v[i](j);
  return a;
}

/// The applied forces: None (empty) or array_like of shape (nbodies, 3), finite.
std::vector<Vec3> applied_from(const py::object& obj, std::size_t nbodies) {
  if (obj.is_none()) return {};
  if (PyUnicode_Check(obj.ptr()) || PyBytes_Check(obj.ptr()))
    throw py::type_error("applied must be an array of shape (nbodies, 3), got " + type_name(obj));
  const py::array a = py::module_::import("numpy").attr("asarray")(obj);
  if (std::string("biuf").find(a.dtype().kind()) == std::string::npos)
    throw py::type_error("applied must hold real numbers, got dtype " + std::string(py::str(a.dtype())));
  if (a.ndim() != 2 || a.shape(0) != static_cast<py::ssize_t>(nbodies) || a.shape(1) != 3)
    throw InputError("applied must have shape (" + std::to_string(nbodies) + ", 3) (one (fx, fy, torque) per body), got " +
                     std::string(py::str(a.attr("shape"))));
  using Reals = py::array_t<double, py::array::c_style | py::array::forcecast>;
  const Reals r = Reals::ensure(a);
  std::vector<Vec3> out(nbodies);
  for (std::size_t i = 0; i < nbodies; ++i)
    for (int j = 0; j < 3; ++j) {
      const double x = r.data()[3 * i + static_cast<std::size_t>(j)];
      if (!std::isfinite(x))
        throw InputError("applied[" + std::to_string(i) + ", " + std::to_string(j) + "] is not finite");
      out[i](j) = x;
    }
  return out;
}

const char* static_kind_name(Contact::StaticKind k) {
  switch (k) {
    case Contact::StaticKind::half_plane: return "half_plane";
    case Contact::StaticKind::segment: return "segment";
    case Contact::StaticKind::none: break;
  }
  return "none";
}

class PySimulator {
 public:
  PySimulator(const py::object& source, const py::kwargs& kw) {
    Scene scene = scene_from_python(source);
    SimulatorSettings s = scene.settings;
    apply_settings(s, simulator_fields(), kw, "Simulator()");
    if (std::string e = s.validation_error(); !e.empty()) throw InputError("Simulator settings: " + e);
    name_ = scene.name;
    scene_steps_ = scene.steps;
    sim_ = std::make_unique<Simulator>(std::move(scene.world), s);
    if (!scene.warm_start.empty()) sim_->set_warm_start_state(scene.warm_start);
  }

  // The warm-start state as a list of (body a, body b, static kind, static index, ordinal,
  // normal code, friction code, regularized 0/1): a scene file's "warm_start" entries.
  py::list warm_start_state() const {
    py::list out;
    for (const ContactWarmRecord& r : sim_->warm_start_state())
      out.append(py::make_tuple(r.key[0], r.key[1], r.key[2], r.key[3], r.key[4], static_cast<int>(r.normal),
                                static_cast<int>(r.friction), static_cast<int>(r.regularized)));
    return out;
  }

  StepStats step(const py::object& applied) {
    const std::vector<Vec3> f = applied_from(applied, sim_->world().bodies.size());
    Busy busy(mutex_, "Simulator");
    py::gil_scoped_release nogil;
    return sim_->step(f);
  }

  py::array_t<double> poses() const { return body_rows([](const RigidBody& b) { return b.pose; }); }
  py::array_t<double> velocities() const { return body_rows([](const RigidBody& b) { return b.velocity; }); }
  py::array_t<bool> is_static() const {
    const auto& bodies = sim_->world().bodies;
    py::array_t<bool> a(static_cast<py::ssize_t>(bodies.size()));
    for (std::size_t i = 0; i < bodies.size(); ++i) a.mutable_data()[i] = bodies[i].is_static;
    return a;
  }
  py::array_t<double> masses() const { return body_values([](const RigidBody& b) { return b.mass; }); }
  py::array_t<double> inertias() const { return body_values([](const RigidBody& b) { return b.inertia; }); }

  py::dict contacts() const {
    const std::vector<Contact>& c = sim_->contacts();
    const auto n = static_cast<py::ssize_t>(c.size());
    py::array_t<int> a(n), b(n), index(n);
    py::array_t<double> point({n, py::ssize_t{2}}), normal({n, py::ssize_t{2}}), gap(n), mu(n);
    py::list kind;
    for (py::ssize_t i = 0; i < n; ++i) {
      const Contact& k = c[static_cast<std::size_t>(i)];
      a.mutable_data()[i] = k.body_a, b.mutable_data()[i] = k.body_b, index.mutable_data()[i] = k.static_index;
      for (int j = 0; j < 2; ++j) point.mutable_data()[2 * i + j] = k.point(j), normal.mutable_data()[2 * i + j] = k.normal(j);
      gap.mutable_data()[i] = k.gap, mu.mutable_data()[i] = k.mu;
      kind.append(static_kind_name(k.static_kind));
    }
    py::dict d;
    d["body_a"] = a, d["body_b"] = b, d["static_kind"] = kind, d["static_index"] = index;
    d["point"] = point, d["normal"] = normal, d["gap"] = gap, d["mu"] = mu;
    return d;
  }

  const Simulator& sim() const { return *sim_; }
  py::dict settings() const { return settings_dict(sim_->settings(), simulator_fields()); }
  const std::string& name() const { return name_; }
  int scene_steps() const { return scene_steps_; }

 private:
  template <class F>
  py::array_t<double> body_rows(F get) const {
    std::vector<Vec3> rows;
    for (const RigidBody& b : sim_->world().bodies) rows.push_back(get(b));
    return rows3(rows);
  }
  template <class F>
  py::array_t<double> body_values(F get) const {
    const auto& bodies = sim_->world().bodies;
    py::array_t<double> a(static_cast<py::ssize_t>(bodies.size()));
    for (std::size_t i = 0; i < bodies.size(); ++i) a.mutable_data()[i] = get(bodies[i]);
    return a;
  }

  std::unique_ptr<Simulator> sim_;
  std::string name_;
  int scene_steps_ = 0;
  std::mutex mutex_;
};

}  // namespace

void bind_simulator(py::module_& m) {
  py::class_<StepStats>(m, "StepStats", "What one Simulator.step() did (models/simulator.hpp StepStats)")
      .def_readonly("contacts", &StepStats::contacts, "contacts posed (speculative margin included)")
      .def_readonly("islands", &StepStats::islands, "= solved_islands + inaccurate_islands + failed_islands")
      .def_readonly("solved_islands", &StepStats::solved_islands)
      .def_readonly("inaccurate_islands", &StepStats::inaccurate_islands)
      .def_readonly("failed_islands", &StepStats::failed_islands, "islands whose solve failed (a fallback was used)")
      .def_readonly("first_failure", &StepStats::first_failure)
      .def_readonly("first_inaccurate", &StepStats::first_inaccurate)
      .def_readonly("largest_island_unknowns", &StepStats::largest_island_unknowns)
      .def_readonly("work", &StepStats::work, "Lemke pivots + interior-point iterations")
      .def_readonly("warm_started_islands", &StepStats::warm_started_islands)
      .def_readonly("max_residual", &StepStats::max_residual, "largest contact-solve residual")
      .def_readonly("max_penetration", &StepStats::max_penetration, "largest -gap >= 0 at the start of the step (m)")
      .def_readonly("projected_islands", &StepStats::projected_islands)
      .def_readonly("failed_projections", &StepStats::failed_projections)
      .def_readonly("newton_fallbacks", &StepStats::newton_fallbacks)
      .def_readonly("collision_seconds", &StepStats::collision_seconds)
      .def_readonly("solve_seconds", &StepStats::solve_seconds)
      .def("__repr__", [](const StepStats& s) {
        return "StepStats(contacts=" + std::to_string(s.contacts) + ", islands=" + std::to_string(s.islands) +
               ", failed_islands=" + std::to_string(s.failed_islands) +
               ", max_penetration=" + std::string(py::repr(py::float_(s.max_penetration))) + ")";
      });

  py::class_<PySimulator>(m, "Simulator", "2-D rigid-body time stepping of a scene (models/simulator.hpp, docs/python.md)")
      .def(py::init([](const py::object& scene, const py::kwargs& kw) { return std::make_unique<PySimulator>(scene, kw); }),
           py::arg("scene"),
           "Simulator(scene, **settings): scene is a scene JSON file path (str or os.PathLike) or\n"
           "JSON text (a str starting with '{'). Keywords override the scene's settings: dt (s),\n"
           "model ('lcp' | 'convex'), margin (m), penetration_slop (m), convex_rho, softening,\n"
           "convex_formulation, convex_solver, post_stabilization, post_stabilization_passes,\n"
           "warm_start, threads (0: all),\n"
           "reuse_convex_solvers, convex_release_open_contacts, qp (dict of QpSettings), lemke (dict of\n"
           "LemkeSettings).")
      .def("step", &PySimulator::step, py::arg("applied") = py::none(),
           "Advances one step of dt. applied: None or (nbodies, 3) array of (fx, fy, torque) in\n"
           "N, N, N*m per body (static bodies' rows ignored). Returns StepStats.")
      .def_property_readonly("poses", &PySimulator::poses, "(nbodies, 3) copy: (x, y, theta) in m, m, rad; static bodies included")
      .def_property_readonly("velocities", &PySimulator::velocities, "(nbodies, 3) copy: (vx, vy, omega) in m/s, rad/s")
      .def_property_readonly("is_static", &PySimulator::is_static, "(nbodies,) bool")
      .def_property_readonly("masses", &PySimulator::masses, "(nbodies,) kg (0 for static bodies)")
      .def_property_readonly("inertias", &PySimulator::inertias, "(nbodies,) kg*m^2 about the centre of mass")
      .def_property_readonly("num_bodies", [](const PySimulator& s) { return s.sim().world().bodies.size(); })
      .def_property_readonly("gravity", [](const PySimulator& s) { return to_numpy(s.sim().world().gravity); }, "m/s^2")
      .def_property_readonly("time", [](const PySimulator& s) { return s.sim().time(); }, "simulated time (s)")
      .def_property_readonly("steps_taken", [](const PySimulator& s) { return s.sim().steps_taken(); })
      .def_property_readonly("kinetic_energy", [](const PySimulator& s) { return s.sim().kinetic_energy(); },
                             "1/2 sum(m|v|^2 + I omega^2) (J)")
      .def_property_readonly("potential_energy", [](const PySimulator& s) { return s.sim().potential_energy(); },
                             "-sum m g.x (J, zero at the origin)")
      .def_property_readonly("total_energy", [](const PySimulator& s) { return s.sim().total_energy(); }, "J")
      .def_property_readonly("contacts", &PySimulator::contacts,
                             "contacts found at the start of the last step: dict of arrays body_a, body_b (-1: a\n"
                             "half-plane or segment), static_kind (list of 'none' | 'half_plane' | 'segment'),\n"
                             "static_index, point (n, 2) m, normal (n, 2) from b to a, gap (m), mu")
      .def_property_readonly("warm_start_state", &PySimulator::warm_start_state,
                             "what the next step warm-starts from: a list of (body_a, body_b, static_kind,\n"
                             "static_index, ordinal, normal_code, friction_code, regularized) per contact of the\n"
                             "last step, as a scene file's 'warm_start' entries (docs/formats.md); a scene's own entries\n"
                             "are loaded by Simulator()")
      .def_property_readonly("settings", &PySimulator::settings, "the settings in use as a dict")
      .def_property_readonly("name", &PySimulator::name, "the scene's name")
      .def_property_readonly("scene_steps", &PySimulator::scene_steps, "the scene file's 'steps'")
      .def("__repr__", [](const PySimulator& s) {
        return "Simulator(name='" + s.name() + "', bodies=" + std::to_string(s.sim().world().bodies.size()) +
               ", time=" + std::string(py::repr(py::float_(s.sim().time()))) + ")";
      });
}

}  // namespace lcprelax::python
