// run_pile_peers: lcprelax (convex and LCP contact models) side by side with Box2D 2.4 on
// the same scenes, in one run: time per step and physical error.
//
//   run_pile_peers [--pile-sizes 200,1000] [--settle-steps 300] [--steps 50]
//                  [--lcp-max-bodies 200] [--lcp-resettle-max-steps 0] [--lcp-scene-dir DIR]
//                  [--pile-scene FILE [--scene-warmup-steps 3]]
//                  [--pyramid-base 20] [--pyramid-steps 200]
//                  [--incline 0.3:0.2,...] [--incline-steps 100] [--engines ...]
//                  [--skip-pile] [--skip-pyramid] [--skip-incline] [--seed 1] [--csv OUT]
//
// Engines: lcprelax_convex, lcprelax_lcp (Simulator with default SimulatorSettings except
// threads = 1, Box2D being single-threaded) and box2d (box2d_runner.hpp: Box2D's default
// 8 velocity and 3 position iterations, sleeping off, polygons shrunk by its 0.01 m skin).
// Tests (SI units: m, s, m/s²):
// - pile: make_pile_scene(bodies, seed), polygons of 3-8 vertices (Box2D's limit is 8),
//   Δt = 0.01 s, μ = 0.5. Each engine drops and settles it for --settle-steps steps, then
//   runs --steps timed steps (with --lcp-resettle-max-steps K > 0, lcprelax_lcp's pile is
//   settled by the convex model for --settle-steps steps, with convex_release_open_contacts
//   so that no body is left held above its supports, then by the LCP model until every
//   body point is slower than 1e-3 m/s, at most K steps; the note says how many; with
//   --lcp-scene-dir DIR the re-settled pile is saved to
//   DIR/lcp_pile_<bodies>_seed<seed>_settle<settle steps>.json
//   with the simulator's warm-start state, and read from there by later runs, which take
//   --lcp-warmup-steps untimed steps first; with --pile-scene FILE, every
//   engine, lcprelax_lcp at any size, starts from FILE (e.g. written by lcprelax pile
//   --save-scene) and runs --scene-warmup-steps untimed steps instead of settling; μ is the
//   file's default): seconds_per_step (wall, the engine's step call only),
//   contacts_mean (lcprelax: contacts entering the problem, within the speculative margin;
//   Box2D: manifold points of touching contacts), max_penetration (the engine's own
//   measure: lcprelax the largest −φ at the start of a step, Box2D the largest overlap of
//   its skin-inflated shapes), polygon_overlap (the same for every engine: the largest −φ
//   of lcprelax's narrow phase on the original polygons at the engine's poses after every
//   step), final_speed (largest body point speed after the window, m/s: is it settled).
// - pyramid: the layout of tests/dynamics_support.hpp box_pyramid: rows r = 0..base−1 of
//   base − r unit boxes (1 m, 1 kg, I = 1/6 kg·m²), box i of row r at ((i + r/2)·1.1,
//   0.5 + r), each resting on two boxes and 0.1 m clear of its row neighbours, on the
//   ground y ≥ 0, μ = 0.5, Δt = 0.01 s, starting at rest. drift = the largest distance of a
//   box centre from its start over --pyramid-steps steps.
// - incline: make_incline_scene(α, μ) (a 1 m box, 1000 kg/m², on the plane through the
//   origin tilted by α), --incline-steps steps of Δt = 0.01 s; accel = the change of the
//   downhill velocity between steps 20 and the last, over that time; accel_exact =
//   max(0, g(sin α − μ cos α)), g = 9.81; sticks_observed = |accel| < 0.01 m/s².
// cpu_per_step: process CPU time around the same calls (one thread everywhere, so it is
// the step's own cost even when other jobs share the machine).
// CSV columns: test, engine, bodies, alpha, mu, steps, seconds_per_step, cpu_per_step,
// contacts_mean,
// max_penetration, polygon_overlap, drift, final_speed, accel, accel_exact, accel_error,
// sticks_expected, sticks_observed, failed_islands, note.
// Exit status: 0 after a run, 2 on bad arguments.
#include "box2d_runner.hpp"
#include "pile_timing.hpp"

#include <lcprelax/contact/collision.hpp>
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/core/errors.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;
using namespace lcprelax::bench;

/// One engine behind one interface: step (returns the wall time of the step call) and
/// the current world.
class Runner {
 public:
  virtual ~Runner() = default;
  virtual double step() = 0;
  virtual World world() const = 0;
  virtual int contacts() const = 0;
  virtual double own_penetration() const = 0;  ///< of the last step (m)
  virtual long failed() const { return 0; }    ///< failed islands so far
  /// The warm-start state a scene file saves with the world (lcprelax engines).
  virtual std::vector<ContactWarmRecord> warm_start_state() const { return {}; }
};

class LcprelaxRunner : public Runner {
 public:
  LcprelaxRunner(Scene scene, ContactModel model) : sim_(make_simulator(with_model(std::move(scene), model), settings())) {}
  double step() override {
    const double t0 = now_seconds();
    last_ = sim_.step();
    const double t = now_seconds() - t0;
    failed_ += last_.failed_islands;
    return t;
  }
  World world() const override { return sim_.world(); }
  int contacts() const override { return last_.contacts; }
  double own_penetration() const override { return last_.max_penetration; }
  long failed() const override { return failed_; }
  std::vector<ContactWarmRecord> warm_start_state() const override { return sim_.warm_start_state(); }

 private:
  static Scene with_model(Scene s, ContactModel m) {
    s.settings.model = m;
    return s;
  }
  static SimulatorSettings settings() {
    SimulatorSettings s;
    s.threads = 1;
    return s;
  }
  Simulator sim_;
  StepStats last_;
  long failed_ = 0;
};

class Box2dRunner : public Runner {
 public:
  explicit Box2dRunner(const Scene& scene) : b2_(scene) {}
  double step() override {
    const double t0 = now_seconds();
    b2_.step();
    return now_seconds() - t0;
  }
  World world() const override { return b2_.world(); }
  int contacts() const override { return b2_.contact_points(); }
  double own_penetration() const override { return b2_.max_penetration(); }

 private:
  Box2dWorld b2_;
};

std::unique_ptr<Runner> make_runner(const std::string& engine, const Scene& scene) {
  if (engine == "box2d") return std::make_unique<Box2dRunner>(scene);
  return std::make_unique<LcprelaxRunner>(scene, engine == "lcprelax_lcp" ? ContactModel::lcp : ContactModel::convex);
}

double polygon_overlap(const World& w) {
  double p = 0.0;
  for (const Contact& c : find_contacts(w, CollisionSettings{0.0})) p = std::max(p, -c.gap);
  return p;
}

struct Row {
  std::string test, engine, note;
  int bodies = 0, steps = 0;
  double alpha = 0, mu = 0, seconds_per_step = 0, cpu_per_step = 0, contacts_mean = 0, max_penetration = 0, polygon_overlap = 0,
         drift = 0, final_speed = 0, accel = 0, accel_exact = 0, accel_error = 0;
  int sticks_expected = -1, sticks_observed = -1;
  long failed = 0;
};

void write_row(std::ostream& os, const Row& r) {
  char buf[1024];
  std::snprintf(buf, sizeof buf, "%s,%s,%d,%.4g,%.4g,%d,%.6g,%.6g,%.1f,%.6g,%.6g,%.6g,%.4g,%.6g,%.6g,%.4g,%d,%d,%ld,\"%s\"\n",
                r.test.c_str(), r.engine.c_str(), r.bodies, r.alpha, r.mu, r.steps, r.seconds_per_step,
                r.cpu_per_step, r.contacts_mean, r.max_penetration, r.polygon_overlap, r.drift, r.final_speed, r.accel, r.accel_exact,
                r.accel_error, r.sticks_expected, r.sticks_observed, r.failed, r.note.c_str());
  os << buf;
  os.flush();
  std::cout << buf;
  std::cout.flush();
}

// Speed below which a pile counts as at rest for --lcp-resettle-max-steps (m/s, largest
// body point speed). run_pile_scaling's settle test (0.05 m/s) leaves piles whose first
// LCP steps still pivot; Box2D's settled piles are at 2e-5 m/s (pile_peers.csv).
constexpr double kRestSpeed = 1e-3;

// The timed window of a pile test: `steps` steps of r, with the columns of the header comment.
Row time_pile(Runner& r, const std::string& engine, int bodies, double mu, int steps, const std::string& settled) {
  Row row;
  row.test = "pile";
  row.engine = engine;
  row.bodies = bodies;
  row.mu = mu;
  row.steps = steps;
  const long failed0 = r.failed();
  double total = 0.0, cpu = 0.0, contacts = 0.0;
  std::cerr << engine << ", " << bodies << " bodies: " << steps << " timed steps" << std::endl;
  for (int k = 0; k < steps; ++k) {
    const double c0 = cpu_seconds();
    total += r.step();
    cpu += cpu_seconds() - c0;
    contacts += r.contacts();
    if ((k + 1) % 5 == 0) std::cerr << "  step " << k + 1 << ": " << total << " s so far" << std::endl;
    row.max_penetration = std::max(row.max_penetration, r.own_penetration());
    row.polygon_overlap = std::max(row.polygon_overlap, polygon_overlap(r.world()));
  }
  row.seconds_per_step = total / steps;
  row.cpu_per_step = cpu / steps;
  row.contacts_mean = contacts / steps;
  row.final_speed = max_body_speed(r.world());
  row.failed = r.failed() - failed0;
  row.note = settled + "; failed islands while settling " + std::to_string(failed0);
  return row;
}

Row run_pile(const std::string& engine, int bodies, std::uint64_t seed, int settle_steps, int steps,
             int lcp_resettle_max_steps, const std::string& lcp_scene_dir, int lcp_warmup_steps) {
  PileOptions p;
  p.bodies = bodies;
  p.seed = seed;
  std::unique_ptr<Runner> r;
  std::string settled = "settled " + std::to_string(settle_steps) + " steps";
  const std::string cached = lcp_scene_dir.empty() ? std::string()
                                                   : lcp_scene_dir + "/lcp_pile_" + std::to_string(bodies) + "_seed" +
                                                         std::to_string(seed) + "_settle" + std::to_string(settle_steps) +
                                                         ".json";
  if (engine == "lcprelax_lcp" && lcp_resettle_max_steps > 0 && !cached.empty() && std::ifstream(cached).good()) {
    // A pile re-settled by an earlier run (below), stepped lcp_warmup_steps times untimed.
    std::cerr << engine << ", " << bodies << " bodies: re-settled pile read from " << cached << std::endl;
    r = make_runner(engine, load_scene(cached));
    for (int k = 0; k < lcp_warmup_steps; ++k) r->step();
    settled = "re-settled pile read from " + cached + ", then " + std::to_string(lcp_warmup_steps) + " untimed steps";
  } else if (engine == "lcprelax_lcp" && lcp_resettle_max_steps > 0) {
    // Dropped and settled by the convex model (no speed test: exactly settle_steps steps),
    // then stepped by the LCP model until at rest: dropping a pile of 1,000 bodies with the
    // LCP model takes hours. The convex model releases open contacts: without it, bodies
    // held above their supports within the contact margin fall under the LCP model and
    // the pile rearranges (200 bodies: still 0.17 m/s after 40 LCP steps, against at rest
    // after 3 with it).
    Scene scene = make_pile_scene(p);
    scene.settings.model = ContactModel::convex;
    SimulatorSettings one_thread;
    one_thread.threads = 1;
    one_thread.convex_release_open_contacts = true;
    std::cerr << engine << ", " << bodies << " bodies: convex settle" << std::endl;
    const SettleResult convex = settle_pile(std::move(scene), one_thread, settle_steps, settle_steps, 0.0, 1e30, &std::cerr);
    r = make_runner(engine, convex.scene);
    int lcp_steps = 0;
    double speed = max_body_speed(r->world());
    while (lcp_steps < lcp_resettle_max_steps && (lcp_steps == 0 || speed > kRestSpeed)) {
      const double seconds = r->step();
      ++lcp_steps;
      speed = max_body_speed(r->world());
      std::cerr << "  LCP re-settle step " << lcp_steps << ": " << seconds << " s, speed " << speed << " m/s" << std::endl;
    }
    char buf[160];
    std::snprintf(buf, sizeof buf, " with the convex model (open contacts released; %d failed islands), then %d with the LCP model (speed %.3g m/s)",
                  static_cast<int>(convex.failed_islands), lcp_steps, speed);
    settled += buf;
    if (!cached.empty()) {
      Scene resettled = convex.scene;
      resettled.world = r->world();
      resettled.warm_start = r->warm_start_state();
      resettled.settings.model = ContactModel::lcp;
      save_scene(cached, resettled);
      std::cerr << "  re-settled pile saved to " << cached << std::endl;
    }
  } else {
    std::cerr << engine << ", " << bodies << " bodies: " << settle_steps << " settle steps" << std::endl;
    r = make_runner(engine, make_pile_scene(p));
    for (int k = 0; k < settle_steps; ++k) {
      const double seconds = r->step();
      if ((k + 1) % 50 == 0) std::cerr << "  settle step " << k + 1 << ": " << seconds << " s this step" << std::endl;
    }
  }
  return time_pile(*r, engine, bodies, p.mu, steps, settled);
}

// A pile from a scene file (--pile-scene): every engine starts from its bodies' poses and
// velocities (the file's contact model replaced by the engine's), runs `warmup` untimed
// steps (Box2D settles its skin-inflated shapes; lcprelax_lcp starts cold unless the file
// holds the simulator's warm-start state, as lcprelax pile --save-scene writes it), then the
// timed window.
Row run_pile_scene(const std::string& engine, const Scene& scene, const std::string& file, int warmup, int steps) {
  const int bodies = static_cast<int>(scene.world.bodies.size());
  std::cerr << engine << ", " << bodies << " bodies from " << file << ": " << warmup << " untimed steps" << std::endl;
  const std::unique_ptr<Runner> r = make_runner(engine, scene);
  for (int k = 0; k < warmup; ++k) r->step();
  return time_pile(*r, engine, bodies, scene.world.friction.default_mu, steps,
                   "pile read from " + file + ", then " + std::to_string(warmup) + " untimed steps");
}

Scene pyramid_scene(int base) {
  Scene s;
  for (int r = 0; r < base; ++r)
    for (int i = 0; i < base - r; ++i) {
      RigidBody b;
      b.shape.vertices = {Vec2(-0.5, -0.5), Vec2(0.5, -0.5), Vec2(0.5, 0.5), Vec2(-0.5, 0.5)};
      b.mass = 1.0;
      b.inertia = 1.0 / 6.0;  // m(w² + h²)/12
      b.pose = Vec3((i + 0.5 * r) * 1.1, 0.5 + r, 0.0);
      s.world.bodies.push_back(b);
    }
  s.world.half_planes.push_back(HalfPlane{Vec2(0.0, 1.0), 0.0, 0});
  s.world.friction.default_mu = 0.5;
  s.settings.dt = 1e-2;
  s.settings.margin = 1e-2;
  return s;
}

Row run_pyramid(const std::string& engine, int base, int steps) {
  const Scene scene = pyramid_scene(base);
  const std::unique_ptr<Runner> r = make_runner(engine, scene);
  Row row;
  row.test = "pyramid";
  row.engine = engine;
  row.bodies = static_cast<int>(scene.world.bodies.size());
  row.mu = 0.5;
  row.steps = steps;
  double total = 0.0, cpu = 0.0, contacts = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double c0 = cpu_seconds();
    total += r->step();
    cpu += cpu_seconds() - c0;
    contacts += r->contacts();
    const World w = r->world();
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
      row.drift = std::max(row.drift, (w.bodies[i].pose.head<2>() - scene.world.bodies[i].pose.head<2>()).norm());
    row.max_penetration = std::max(row.max_penetration, r->own_penetration());
    row.polygon_overlap = std::max(row.polygon_overlap, polygon_overlap(w));
  }
  row.seconds_per_step = total / steps;
  row.cpu_per_step = cpu / steps;
  row.contacts_mean = contacts / steps;
  row.final_speed = max_body_speed(r->world());
  row.failed = r->failed();
  return row;
}

Row run_incline(const std::string& engine, double alpha, double mu, int steps) {
  const double dt = 1e-2, g = 9.81;
  const std::unique_ptr<Runner> r = make_runner(engine, make_incline_scene(alpha, mu));
  const Vec2 down(-std::cos(alpha), -std::sin(alpha));
  const int first = 20;
  double v_first = 0.0, v_last = 0.0, total = 0.0, cpu = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const double c0 = cpu_seconds();
    total += r->step();
    cpu += cpu_seconds() - c0;
    const double v = r->world().bodies[0].velocity.head<2>().dot(down);
    if (k == first) v_first = v;
    v_last = v;
  }
  Row row;
  row.test = "incline";
  row.engine = engine;
  row.bodies = 1;
  row.alpha = alpha;
  row.mu = mu;
  row.steps = steps;
  row.seconds_per_step = total / steps;
  row.cpu_per_step = cpu / steps;
  row.accel = (v_last - v_first) / ((steps - first) * dt);
  row.accel_exact = std::max(0.0, g * (std::sin(alpha) - mu * std::cos(alpha)));
  row.accel_error = std::abs(row.accel - row.accel_exact);
  row.sticks_expected = std::tan(alpha) <= mu ? 1 : 0;
  row.sticks_observed = std::abs(row.accel) < 0.01 ? 1 : 0;
  row.max_penetration = r->own_penetration();
  row.polygon_overlap = polygon_overlap(r->world());
  row.final_speed = max_body_speed(r->world());
  row.failed = r->failed();
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> pile_sizes{200, 1000};
  std::vector<std::string> engines{"lcprelax_convex", "lcprelax_lcp", "box2d"};
  std::vector<std::string> inclines{"0.3:0.2", "0.3:0.3", "0.3:0.32", "0.3:0.6", "0.5:0.4", "0.5:0.54", "0.5:0.56"};
  int settle_steps = 300, steps = 50, lcp_max_bodies = 200, lcp_resettle_max_steps = 0, lcp_warmup_steps = 3,
      pyramid_base = 20, pyramid_steps = 200, incline_steps = 100;
  std::string lcp_scene_dir, pile_scene;
  int scene_warmup_steps = 3;
  bool skip_pile = false, skip_pyramid = false, skip_incline = false;
  std::uint64_t seed = 1;
  std::string csv = "pile_peers.csv";

  CLI::App app{"lcprelax vs Box2D 2.4: time per step and physical error on the same scenes"};
  app.add_option("--pile-sizes", pile_sizes, "Pile sizes (bodies)")->delimiter(',')->check(CLI::Range(1, 1000000));
  app.add_option("--settle-steps", settle_steps, "Untimed steps before the pile window")->capture_default_str();
  app.add_option("--steps", steps, "Timed steps of the settled pile")->check(CLI::Range(1, 1000000));
  app.add_option("--lcp-max-bodies", lcp_max_bodies, "Largest pile run with lcprelax_lcp")->capture_default_str();
  app.add_option("--lcp-resettle-max-steps", lcp_resettle_max_steps,
                 "lcprelax_lcp: settle the pile with the convex model, then with the LCP model until every body point "
                 "is slower than 1e-3 m/s, at most this many steps (0: the LCP model drops and settles it)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  app.add_option("--lcp-scene-dir", lcp_scene_dir,
                 "With --lcp-resettle-max-steps: save the re-settled pile in this directory, or read it from there "
                 "when an earlier run saved it");
  app.add_option("--lcp-warmup-steps", lcp_warmup_steps, "Untimed LCP steps after reading a re-settled pile")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  app.add_option("--pile-scene", pile_scene,
                 "Pile test on this scene file (lcprelax pile --save-scene) for every engine, instead of "
                 "--pile-sizes' generated piles")
      ->check(CLI::ExistingFile);
  app.add_option("--scene-warmup-steps", scene_warmup_steps, "With --pile-scene: untimed steps before the window")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  app.add_option("--engines", engines, "Engines")
      ->delimiter(',')
      ->check(CLI::IsMember({"lcprelax_convex", "lcprelax_lcp", "box2d"}));
  app.add_option("--pyramid-base", pyramid_base, "Boxes in the pyramid's bottom row")->check(CLI::Range(1, 1000));
  app.add_option("--pyramid-steps", pyramid_steps, "Pyramid steps")->check(CLI::Range(1, 1000000));
  app.add_option("--incline", inclines, "alpha:mu pairs (rad, 1)")->delimiter(',');
  app.add_option("--incline-steps", incline_steps, "Incline steps (> 20)")->check(CLI::Range(21, 1000000));
  app.add_flag("--skip-pile", skip_pile);
  app.add_flag("--skip-pyramid", skip_pyramid);
  app.add_flag("--skip-incline", skip_incline);
  app.add_option("--seed", seed, "Pile seed")->capture_default_str();
  app.add_option("--csv", csv, "CSV output file")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  std::ofstream out(csv);
  if (!out) {
    std::cerr << "cannot write " << csv << '\n';
    return 2;
  }
  const char* header =
      "test,engine,bodies,alpha,mu,steps,seconds_per_step,cpu_per_step,contacts_mean,max_penetration,polygon_overlap,drift,"
      "final_speed,accel,accel_exact,accel_error,sticks_expected,sticks_observed,failed_islands,note\n";
  out << header;
  std::cout << header;
  try {
    if (!skip_incline)
      for (const std::string& pair : inclines) {
        const std::size_t colon = pair.find(':');
        if (colon == std::string::npos) throw InputError("--incline: expected alpha:mu, got '" + pair + "'");
        const double alpha = std::stod(pair.substr(0, colon)), mu = std::stod(pair.substr(colon + 1));
        for (const std::string& e : engines) write_row(out, run_incline(e, alpha, mu, incline_steps));
      }
    if (!skip_pile && !pile_scene.empty()) {
      const Scene scene = load_scene(pile_scene);
      for (const std::string& e : engines)
        write_row(out, run_pile_scene(e, scene, pile_scene, scene_warmup_steps, steps));
    } else if (!skip_pile)
      for (const int n : pile_sizes)
        for (const std::string& e : engines) {
          if (e == "lcprelax_lcp" && n > lcp_max_bodies) continue;
          write_row(out, run_pile(e, n, seed, settle_steps, steps, lcp_resettle_max_steps, lcp_scene_dir, lcp_warmup_steps));
        }
    if (!skip_pyramid)
      for (const std::string& e : engines) write_row(out, run_pyramid(e, pyramid_base, pyramid_steps));
  } catch (const std::exception& ex) {
    std::cerr << "run_pile_peers: " << ex.what() << '\n';
    return 2;
  }
  return 0;
}
