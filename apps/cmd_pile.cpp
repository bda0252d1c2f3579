// `lcprelax pile [--bodies N] [--steps K] [--model lcp|convex]
//  [--softening exp|impedance|penalty] [--dt S] [--gravity G] [--qp-eps E] [--lemke-tol E]
//  [--post-stabilization-passes K] [--release-open-contacts] [--threads T] [--picture OUT.svg|OUT.png] [--frames DIR] [--scene FILE.json]
//  [--export-fc2d FILE] [--save-scene FILE.json] [--json]` (docs/cli.md): random convex polygons dropped into a
// container (or a scene file), simulated with models/simulator.hpp.
// Units: --dt in s; --gravity in m/s², the magnitude of gravity: a random pile's points
// along −y, a scene's keeps the file's direction (−y when the file's gravity is zero);
// --qp-eps is the interior point's absolute tolerance (convex model and the fallbacks),
// --lemke-tol Lemke's accepted complementarity residual max|min(z, w)| (lcp model and the
// position projection; 0: 1e-9·‖q‖∞). Each is bad input (exit 2, naming the flag) unless
// finite and in range (dt > 0, gravity ≥ 0 and ≤ 1e15, qp-eps > 0, lemke-tol ≥ 0).
// --post-stabilization-passes K ≥ 1 (SimulatorSettings::post_stabilization_passes): after
// the linearized position projection, up to K − 1 passes on the true overlaps.
// --release-open-contacts (convex model only; SimulatorSettings::convex_release_open_contacts):
// phase 2 puts no normal impulse on a contact whose gap phase 1 leaves open.
// Human output: a brief report (cli_report.hpp) of the JSON fields plus the scene's name,
// time step and gravity.
// JSON: bodies, contacts_max, steps, seconds_per_step, max_penetration (m), max_residual
// (largest contact-solve residual), max_energy_gain (largest one-step increase of kinetic +
// potential energy divided by the initial total), plus model, softening (convex model only),
// failed_islands, seconds, and saved_scene with --save-scene (the final state as a scene
// file: the run's scene with its bodies' poses and velocities at the end and the simulator's
// warm-start state; --scene continues from it as the run would have continued).
// Exit status 1 when any island's contact solve failed (it was then solved by the convex
// fallback, see simulator.cpp), 2 on bad input. --scene FILE: the file's "model", "softening"
// and "steps" hold unless --model / --softening / --steps name them. --softening (the convex
// model's normal softening, models/normal_softening.hpp; JSON "softening" with the convex
// model) is an error with the lcp model. Output paths are checked before the first step;
// progress goes to stderr (a status line on a terminal, else a line every 10 s).
#include "cli_common.hpp"
#include "cli_report.hpp"

#include <lcprelax/contact/collision.hpp>
#include <lcprelax/io/siconos_writer.hpp>
#include <lcprelax/models/fc2d_export.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/picture.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/core/errors.hpp>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

namespace lcprelax::cli {
namespace {

struct PileCliOptions {
  int bodies = 150;  // with 300 steps about a minute on 2 cores (measured 200 × 300: 112 s)
  int steps = 300;
  std::string model = "convex";
  std::string softening;  // empty: the scene's (exp_phi for a random pile)
  int threads = 0;
  std::uint64_t seed = 1;
  std::string picture, frames, scene, export_fc2d, save_scene, color = "contacts";
  int frame_every = 5;
  double dt = 0.0, gravity = 0.0;  // used only when --dt / --gravity are given
  double qp_eps = SimulatorSettings{}.qp.eps_abs;
  double lemke_tol = SimulatorSettings{}.lemke.residual_tolerance;
  int projection_passes = SimulatorSettings{}.post_stabilization_passes;
  bool release_open_contacts = false;
  bool draw_contacts = false;
  bool json = false;
};

PictureOptions picture_options(const PileCliOptions& o) {
  PictureOptions p;
  p.color = o.color == "speed" ? PictureOptions::Color::speed : PictureOptions::Color::contacts;
  p.draw_contacts = o.draw_contacts;
  return p;
}

// Output paths are checked before the simulation (a long run must not end in "cannot write").
void check_outputs(const PileCliOptions& o) {
  if (!o.picture.empty()) {
    std::string ext = std::filesystem::path(o.picture).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    require_option(ext == ".png" || ext == ".svg", "--picture", "must end in .png or .svg");
    require_writable_file("--picture", o.picture);
  }
  require_writable_directory("--frames", o.frames);
  require_writable_file("--export-fc2d", o.export_fc2d);
  require_writable_file("--save-scene", o.save_scene);
}

// --dt and --gravity onto the scene (a random pile's or the file's), --qp-eps and
// --lemke-tol onto the solver settings; each flag validated first (exit 2 naming it).
void apply_physics_options(const PileCliOptions& o, const CLI::App& app, Scene& scene, SimulatorSettings& settings) {
  const auto shown = [](double v) {  // the value as typed, also when it is nan or inf
    return std::isnan(v) ? std::string("nan") : std::isinf(v) ? std::string(v > 0 ? "inf" : "-inf") : format_number(v, 17);
  };
  if (app.count("--dt")) {
    require_option(std::isfinite(o.dt) && o.dt > 0.0, "--dt",
                   "the time step must be a positive finite number of seconds, got " + shown(o.dt));
    scene.settings.dt = o.dt;
  }
  if (app.count("--gravity")) {
    require_option(std::isfinite(o.gravity) && o.gravity >= 0.0 && o.gravity <= kMaxSceneMagnitude, "--gravity",
                   "the magnitude of gravity must be a finite number of m/s² in [0, 1e15], got " + shown(o.gravity));
    const Vec2 g = scene.world.gravity;
    const Vec2 down = g.norm() > 0.0 ? Vec2(g / g.norm()) : Vec2(0.0, -1.0);
    scene.world.gravity = o.gravity * down;
  }
  require_option(std::isfinite(o.qp_eps) && o.qp_eps > 0.0, "--qp-eps",
                 "must be a positive finite number, got " + shown(o.qp_eps));
  require_option(std::isfinite(o.lemke_tol) && o.lemke_tol >= 0.0, "--lemke-tol",
                 "must be a finite number >= 0 (0: 1e-9 times the largest |q|), got " + shown(o.lemke_tol));
  require_option(o.projection_passes >= 1, "--post-stabilization-passes",
                 "must be >= 1, got " + std::to_string(o.projection_passes));
  settings.qp.eps_abs = o.qp_eps;
  settings.lemke.residual_tolerance = o.lemke_tol;
  settings.post_stabilization_passes = o.projection_passes;
}

// Progress on stderr every kProgressSeconds whatever the terminal (a long run, such as a
// 10⁶-body scene, says how far it is; also under --json: stdout keeps its one object).
constexpr double kProgressSeconds = 10.0;

// The brief report (cli_report.hpp): status first (ok, or failed islands), the run's
// settings, then the JSON fields in words with their units.
void print_report(const Json& j, const Simulator& sim, const std::string& scene_name, const std::string& first_failure) {
  const long failed = j["failed_islands"].get<long>();
  const auto number = [&j](const char* key) { return j[key].is_number() ? j[key].get<double>() : std::nan(""); };
  BriefReport r;
  r.add("status", failed == 0 ? "ok" : "failed islands");
  if (failed > 0) r.add("first failure", first_failure);
  if (!scene_name.empty()) r.add("scene", scene_name);
  std::string model = j["model"].get<std::string>();
  if (j.contains("softening")) model += " (softening " + j["softening"].get<std::string>() + ")";
  r.add("model", model);
  r.add_count("bodies", j["bodies"].get<long long>());
  r.add_count("steps", j["steps"].get<long long>());
  r.add("time step", sim.settings().dt, "s");
  const Vec2 g = sim.world().gravity;
  r.add("gravity", "(" + format_number(g.x()) + ", " + format_number(g.y()) + ")", "m/s²");
  r.add_count("contacts (max)", j["contacts_max"].get<long long>(), "in one step");
  r.add("max penetration", number("max_penetration"), "m", 3);
  r.add("max residual", number("max_residual"), "(largest contact-solve residual)", 3);
  r.add("max energy gain", number("max_energy_gain"), "× the initial energy, in one step (< 0: always lost)", 3);
  r.add_count("failed islands", failed, failed > 0 ? "(solved by a fallback instead)" : "");
  const long long inaccurate = j["inaccurate_islands"].get<long long>();
  r.add_count("inaccurate islands", inaccurate, inaccurate > 0 ? "(outside the tolerance, kept)" : "");
  r.add("time", number("seconds"), "s (" + format_number(number("seconds_per_step"), 3) + " s per step)", 3);
  if (j.contains("picture")) r.add("picture", j["picture"].get<std::string>());
  if (j.contains("saved_scene")) r.add("saved scene", j["saved_scene"].get<std::string>());
  r.print();
}

int run_pile(const PileCliOptions& o, const CLI::App& app) {
  const Stopwatch setup_watch;
  require_threads(o.threads);
  check_outputs(o);
  Scene scene;
  if (!o.scene.empty()) {
    // The scene file's "model" and "steps" hold unless a flag names them.
    require_option(app.count("--bodies") == 0, "--bodies", "cannot be combined with --scene (the scene has its bodies)");
    require_option(app.count("--seed") == 0, "--seed", "cannot be combined with --scene (the scene is not random)");
    scene = load_scene(o.scene);
    if (app.count("--model")) scene.settings.model = parse_contact_model(o.model);
    if (app.count("--steps")) scene.steps = o.steps;
  } else {
    PileOptions p;
    p.bodies = o.bodies;
    p.seed = o.seed;
    scene = make_pile_scene(p);
    scene.settings.model = parse_contact_model(o.model);
    scene.steps = o.steps;
  }
  if (!o.softening.empty()) {
    require_option(scene.settings.model == ContactModel::convex, "--softening",
                   "applies to the convex model only (this run's model is lcp)");
    scene.settings.convex_softening.method = parse_normal_softening(o.softening);
  }
  if (o.release_open_contacts)
    require_option(scene.settings.model == ContactModel::convex, "--release-open-contacts",
                   "applies to the convex model only (this run's model is lcp)");
  SimulatorSettings settings;
  settings.threads = o.threads;
  settings.convex_release_open_contacts = o.release_open_contacts;
  apply_physics_options(o, app, scene, settings);
  const int steps = scene.steps;
  const std::string model = to_string(scene.settings.model);
  const std::string softening = to_string(scene.settings.convex_softening.method);
  const std::string scene_name = scene.name;
  // --save-scene: the scene as run (the flags applied), its bodies replaced by the final state
  // and its warm start by the simulator's (the last step's bases or active sets).
  std::optional<Scene> to_save;
  if (!o.save_scene.empty()) to_save = scene;
  Simulator sim = [&] {
    try {
      return make_simulator(std::move(scene), settings);
    } catch (const InputError& e) {  // a scene file's value the simulator refuses: name the file
      if (o.scene.empty()) throw;
      throw InputError(o.scene + ": " + e.what());
    }
  }();

  const bool progress = !o.json && isatty(STDERR_FILENO);
  double next_report = kProgressSeconds;
  if (setup_watch.seconds() > kProgressSeconds)  // 10⁶ bodies: about 20 s before the first step
    std::fprintf(stderr, "lcprelax pile: %zu bodies set up in %.0f s, %d steps to go\n", sim.world().bodies.size(),
                 setup_watch.seconds(), steps);
  const double e0 = sim.total_energy();
  double energy = e0, max_gain = -std::numeric_limits<double>::infinity(), max_pen = 0.0, max_res = 0.0;
  int contacts_max = 0;
  long failed = 0, inaccurate = 0;
  std::string first_failure;
  const Stopwatch watch;
  for (int k = 0; k < steps; ++k) {
    if (!o.export_fc2d.empty() && k + 1 == steps) {
      // the last step's contact problem, before it is solved
      const std::vector<Contact> c = find_contacts(sim.world(), CollisionSettings{sim.settings().margin});
      if (c.empty())  // a Siconos fc2d problem needs at least one contact (our reader refuses 0)
        throw InputError("--export-fc2d: the last step (" + std::to_string(steps) +
                         ") has no contacts, nothing to export; run more --steps");
      const io::Fc2dData d = export_fc2d(sim.world(), c, sim.settings().dt);
      io::write_siconos_fc2d(o.export_fc2d, d.W, d.q, d.mu);
    }
    const StepStats st = sim.step();
    const double e = sim.total_energy();
    max_gain = std::max(max_gain, (e - energy) / std::abs(e0));
    energy = e;
    max_pen = std::max(max_pen, st.max_penetration);
    max_res = std::max(max_res, st.max_residual);
    contacts_max = std::max(contacts_max, st.contacts);
    if (st.failed_islands > 0 && failed == 0) first_failure = st.first_failure;
    failed += st.failed_islands;
    inaccurate += st.inaccurate_islands;
    if (!o.frames.empty() && k % o.frame_every == 0)
      write_frame(o.frames, k / o.frame_every, sim.world(), sim.contacts(), picture_options(o));
    const double s = watch.seconds();
    if (progress && (k % 10 == 0 || k + 1 == steps)) {
      std::fprintf(stderr, "\rstep %d/%d  contacts %d  islands %d  %.3f s/step  ETA %.0f s   ", k + 1, steps,
                   st.contacts, st.islands, s / (k + 1), s / (k + 1) * (steps - k - 1));
    } else if (!progress && s >= next_report && k + 1 < steps) {
      std::fprintf(stderr, "lcprelax pile: step %d/%d, contacts %d, islands %d, %.3g s/step, ETA %.0f s\n", k + 1,
                   steps, st.contacts, st.islands, s / (k + 1), s / (k + 1) * (steps - k - 1));
      next_report = s + kProgressSeconds;
    }
  }
  if (progress) std::fprintf(stderr, "\n");
  const double seconds = watch.seconds();
  if (!o.picture.empty()) write_picture(o.picture, sim.world(), sim.contacts(), picture_options(o));
  if (to_save) {
    to_save->world = sim.world();
    to_save->warm_start = sim.warm_start_state();
    save_scene(o.save_scene, *to_save);
  }

  Json j;
  j["bodies"] = sim.world().bodies.size();
  j["contacts_max"] = contacts_max;
  j["steps"] = steps;
  j["seconds_per_step"] = steps > 0 ? seconds / steps : 0.0;
  j["max_penetration"] = max_pen;
  j["max_residual"] = max_res;
  j["max_energy_gain"] = steps > 0 ? number_or_null(max_gain) : Json(0.0);
  j["model"] = model;
  if (model == "convex") j["softening"] = softening;
  j["failed_islands"] = failed;
  j["inaccurate_islands"] = inaccurate;
  j["seconds"] = seconds;
  if (!o.picture.empty()) j["picture"] = o.picture;
  if (!o.save_scene.empty()) j["saved_scene"] = o.save_scene;
  if (o.json) print_json(j);
  else print_report(j, sim, scene_name.empty() ? o.scene : scene_name, first_failure);
  return failed == 0 ? kExitSuccess : kExitSolveFailed;
}

}  // namespace

Command add_pile_command(CLI::App& parent) {
  auto o = std::make_shared<PileCliOptions>();
  CLI::App* app = parent.add_subcommand(
      "pile", "Drop random convex polygons into a box (or load a scene file) and simulate them, with friction");
  app->add_option("--bodies", o->bodies, "number of random polygons")->check(CLI::Range(1, 1000000))->capture_default_str();
  app->add_option("--steps", o->steps, "time steps to simulate (a scene file's \"steps\" unless given)")
      ->check(CLI::Range(0, 100000000))
      ->capture_default_str();
  app->add_option("--model", o->model,
                  "contact model: convex (a convex optimization per step, slightly soft contacts; default) or lcp "
                  "(the exact complementarity problem, solved by pivoting)")
      ->check(CLI::IsMember({"lcp", "convex"}))
      ->capture_default_str();
  app->add_option("--softening", o->softening,
                  "convex model: how contacts are softened: exp (default), impedance (MuJoCo's) or penalty (a spring)")
      ->check(CLI::IsMember({"exp", "impedance", "penalty"}));
  app->add_option("--dt", o->dt, "time step in seconds, > 0 (default 0.01, or the scene file's \"dt\")");
  app->add_option("--gravity", o->gravity,
                  "magnitude of gravity in m/s², >= 0 (default 9.81, pointing down (-y); with --scene the file's "
                  "direction is kept)");
  app->add_option("--qp-eps", o->qp_eps,
                  "convex model: accuracy of each step's solve (largest residual accepted, absolute)")
      ->capture_default_str();
  app->add_option("--lemke-tol", o->lemke_tol,
                  "lcp model: largest complementarity residual accepted per step (0: 1e-9 times the problem's "
                  "largest |q|)")
      ->capture_default_str();
  app->add_option("--post-stabilization-passes", o->projection_passes,
                  "position projections per step, >= 1: the first on the step's contacts (linearized), each "
                  "further one on the overlaps still deeper than 0.1 mm at the projected positions (5 keeps a "
                  "dropping pile's overlaps near 0.1 mm)")
      ->capture_default_str();
  app->add_flag("--release-open-contacts", o->release_open_contacts,
                "convex model: no normal impulse on a contact whose gap stays open (without it, bodies can rest "
                "up to the 1 cm contact margin above their supports; docs/formulations.md)");
  add_threads_option(*app, o->threads, "the groups of touching bodies (islands)");
  app->add_option("--seed", o->seed, "random seed of the polygons' shapes, positions and velocities")->capture_default_str();
  app->add_option("--scene", o->scene, "simulate this scene JSON file (docs/formats.md) instead of a random pile");
  app->add_option("--picture", o->picture, "draw the final state to OUT.svg or OUT.png");
  app->add_option("--frames", o->frames, "write numbered PNG frames into this directory");
  app->add_option("--frame-every", o->frame_every, "steps between two frames")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  app->add_option("--color", o->color, "color the bodies by their number of contacts or by their speed")
      ->check(CLI::IsMember({"contacts", "speed"}))
      ->capture_default_str();
  app->add_flag("--draw-contacts", o->draw_contacts, "draw contact points and normals");
  app->add_option("--export-fc2d", o->export_fc2d,
                  "write the last step's contact problem as a Siconos 2-D frictional contact file");
  app->add_option("--save-scene", o->save_scene,
                  "write the final state as a scene JSON file (docs/formats.md) that --scene continues from, with the "
                  "simulator's warm-start state (the lcp model's last bases per contact), so that a continued lcp run "
                  "starts from them; a state that the convex model wrote has none");
  add_json_flag(*app, o->json);
  app->footer(exit_codes_help("every step's contact problems were solved",
                              "some island's contact solve failed (it was then solved by the other model or "
                              "without friction; see \"first failure\")"));
  return Command{app, [o, app] { return run_pile(*o, *app); }};
}

}  // namespace lcprelax::cli
