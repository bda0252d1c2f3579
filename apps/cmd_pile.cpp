// `lcprelax pile [--bodies N] [--steps K] [--model lcp|convex]
//  [--softening exp|impedance|penalty] [--threads T] [--picture OUT.svg|OUT.png]
//  [--frames DIR] [--scene FILE.json] [--export-fc2d FILE] [--json]` (docs/cli.md): random
// convex polygons dropped into a container (or a scene file), simulated with
// models/simulator.hpp.
// JSON: bodies, contacts_max, steps, seconds_per_step, max_penetration (m), max_residual
// (largest contact-solve residual), max_energy_gain (largest one-step increase of kinetic +
// potential energy divided by the initial total), plus model, softening (convex model only),
// failed_islands, seconds.
// Exit status 1 when any island's contact solve failed (it was then solved by the convex
// fallback, see simulator.cpp), 2 on bad input. --scene FILE: the file's "model", "softening"
// and "steps" hold unless --model / --softening / --steps name them. --softening (the convex
// model's normal softening, models/normal_softening.hpp; JSON "softening" with the convex
// model) is an error with the lcp model. Output paths are checked before the first step;
// progress goes to stderr (a status line on a terminal, else a line every 10 s).
#include "cli_common.hpp"

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
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace lcprelax::cli {
namespace {

struct PileCliOptions {
  int bodies = 150;  // with 300 steps about a minute on 2 cores (measured 200 × 300: 112 s)
  int steps = 300;
  std::string model = "convex";
  std::string softening;  // empty: the scene's (exp_phi for a random pile)
  int threads = 0;
  std::uint64_t seed = 1;
  std::string picture, frames, scene, export_fc2d, color = "contacts";
  int frame_every = 5;
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
}

// Progress on stderr every kProgressSeconds whatever the terminal (a long run, such as a
// 10⁶-body scene, says how far it is; also under --json: stdout keeps its one object).
constexpr double kProgressSeconds = 10.0;

int run_pile(const PileCliOptions& o, const CLI::App& app) {
  const Stopwatch setup_watch;
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
  const int steps = scene.steps;
  const std::string model = to_string(scene.settings.model);
  const std::string softening = to_string(scene.settings.convex_softening.method);
  SimulatorSettings settings;
  settings.threads = o.threads;
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
  if (o.json) {
    print_json(j);
  } else {
    for (const auto& [key, value] : j.items()) std::cout << key << ": " << value.dump() << '\n';
    if (failed) std::cout << "first failure: " << first_failure << '\n';
  }
  return failed == 0 ? kExitSuccess : kExitSolveFailed;
}

}  // namespace

Command add_pile_command(CLI::App& parent) {
  auto o = std::make_shared<PileCliOptions>();
  CLI::App* app = parent.add_subcommand("pile", "Drop random convex polygons into a container and simulate");
  app->add_option("--bodies", o->bodies, "Number of polygons")->check(CLI::Range(1, 1000000))->capture_default_str();
  app->add_option("--steps", o->steps, "Time steps")->check(CLI::Range(0, 100000000))->capture_default_str();
  app->add_option("--model", o->model, "Contact model: convex (interior point, default) or lcp (Lemke)")
      ->check(CLI::IsMember({"lcp", "convex"}))
      ->capture_default_str();
  app->add_option("--softening", o->softening,
                  "convex model's normal softening: exp (exp(phi), default), impedance (MuJoCo) or penalty")
      ->check(CLI::IsMember({"exp", "impedance", "penalty"}));
  app->add_option("--threads", o->threads, "OpenMP threads over islands (0: default)")->check(CLI::Range(0, 1024));
  app->add_option("--seed", o->seed, "Random seed of the pile")->capture_default_str();
  app->add_option("--scene", o->scene, "Simulate this scene JSON file instead of a random pile");
  app->add_option("--picture", o->picture, "Write the final state to OUT.svg or OUT.png");
  app->add_option("--frames", o->frames, "Write numbered PNG frames into this directory");
  app->add_option("--frame-every", o->frame_every, "Steps between frames")->check(CLI::Range(1, 1000000));
  app->add_option("--color", o->color, "Color bodies by contacts or speed")
      ->check(CLI::IsMember({"contacts", "speed"}))
      ->capture_default_str();
  app->add_flag("--draw-contacts", o->draw_contacts, "Draw contact points and normals");
  app->add_option("--export-fc2d", o->export_fc2d, "Write the last step's contact problem as a Siconos fc2d file");
  add_json_flag(*app, o->json);
  return Command{app, [o, app] { return run_pile(*o, *app); }};
}

}  // namespace lcprelax::cli
