// Learning curves on the scene learning path (issue 20): the polygon on the ground and a
// 30-body pile; held-out next-state error and stick/slip mode error against the number of
// training transitions, per parameterization, 5 seeds each. The block's are
// run_learning_curves.cpp.
//
//   run_learning_curves_scene --scene polygon|pile30 [--sizes 10,30,100,300,1000] [--seeds 5] [--first-seed 1]
//                             [--truth-loss]
//     [--params physical,structured,residual,block,block_tied,softness] [--loss relaxed|hard]
//     [--noise 0.02] [--true-compliance C --true-erp E]
//     [--optimizer adam|lbfgs|adam+lbfgs]
//     [--epochs 300] [--test 400] [--sanity-size 30] [--csv OUT.csv] [--plot OUT.png] > OUT.txt
//
// Truth: polygon = reference_polygon_model() (polygon_params.hpp) with the data of
// generate_polygon_dataset (throws with random forces, contact transitions only; LCP model);
// pile30 = make_learning_pile(30 bodies, 3 classes, seed 1, LCP model), transitions of
// generate_scene_dataset (pushes every step, SceneDatasetSettings defaults). A transition
// is one simulator step of the whole scene (30 bodies for pile30). Training set (N, seed s):
// the first N transitions generated with seed 1000 s + N, plus N(0, (σ·RMS)²) noise on every
// dynamic body's recorded next velocity, RMS taken over the set per kind (vx and vy
// together in m/s; ω in rad/s), σ = --noise. Held-out set: the first --test noise-free
// transitions of seed 777777 + s. --true-compliance C, --true-erp E: the data come from a
// truth with that normal softness (an implicit spring–damper, world.hpp FrictionTable; default
// 0, rigid), while every parameterization's scene is rigid (softness learned from 0): the
// physical model is then misspecified. The sanity lines' "true θ" is the rigid one.
// Parameterizations (learn/scene_params.hpp; θ₀ = the physical parameters perturbed by
// --perturb as perturb_scene_parameters does with seed s, the nonphysical terms at 0):
//   physical   μ (global), mass, inertia, vertices per shape class (the scene path's default);
//   structured physical + μ per listed material pair (neither scene lists one: none is
//              added) + gap offset + linear residual W per class;
//   residual   only W per class, the physical parameters held at their perturbed θ₀;
//   block      physical + the lcp model's per-contact LCP correction (World::lcp_block) with
//              all 20 entries free (elementwise: nothing of the LCP's structure imposed);
//   block_tied physical + the same correction with the friction rows' antisymmetry imposed
//              (7 entries); both start at 0 and need --loss hard;
//   softness   physical + the friction table's normal compliance and erp (per listed material
//              pair, world.hpp FrictionTable: an implicit spring–damper), from 0 (the rigid
//              truth); --loss relaxed or hard.
// --start relaxed: a two-stage fit, θ₀ = the physical parameters learned first by the relaxed
// loss (L-BFGS, 100 iterations, from the perturbed start, same data; shared by every
// parameterization of a (N, seed)), then the parameterization by --loss from there (the
// reported seconds and epochs are the second stage's).
// Training: the relaxed step loss (or --loss hard: the hard loss, Lemke's adjoint) (SceneLossSettings defaults; the polygon's candidate margin
// 0.05 m, polygon_objective.hpp), full batch, 1 thread: by default Adam as the CLIs (lr 0.02,
// decay 0.003, at most --epochs epochs, the trainer's convergence test); lbfgs: L-BFGS (lr
// 1); adam+lbfgs: Adam, then at most --polish L-BFGS iterations.
// --batch B (Adam's steps; adam+lbfgs polishes on the full batch): at sizes N > B,
// mini-batches of B and round(--epochs·B/N) epochs, so
// that every size takes about the same number of optimizer steps (--epochs; exactly where B
// divides N) on the same number of samples per step as a full-batch run at N = B (at N ≤ B:
// full batch, as without it); the decay schedule counts steps, so it is the same too. With
// mini-batches every epoch runs (the trainer's convergence test, TrainSettings::patience,
// would cost a pass over the whole training set per epoch; the full-batch pile runs all ran
// to their cap). --threads T: the batch's evaluations on T threads (sums in a fixed order:
// the same numbers as on 1 thread). --truth-loss prints, per (N, seed), the training loss at
// the learned θ and at the data's true θ (is the fit limited by the optimizer or the loss?).
// Reported per run: test_error = sqrt(Σ‖v̂⁺ − v⁺‖² / Σ‖v⁺‖²) over the held-out transitions'
// dynamic bodies (v = (vx, vy, ω), SI), v⁺ the recorded next velocity, v̂⁺ that of one
// Simulator::step (the data's settings, LCP model, no warm start) of the world at the
// learned θ from the recorded state; mode_error = fraction of held-out active contacts
// (contacts of the true step with Jn v⁺ + max(φ,0)/Δt ≤ 1e-6 m/s) whose mode is predicted
// wrongly: stick means |tangential relative velocity| ≤ --stick-tol (1e-3 m/s), for the truth
// at its contact on v⁺, for the learned model at its own contact of the same feature (body
// pair, static shape, narrow-phase feature) on v̂⁺; no such contact counts as wrong. A
// prediction whose step has a failed island counts in `failed`, is left out of test_error and
// its contacts count as wrong; train_failed = failed sample evaluations in training. Sanity
// lines: the true θ's predictions against the recorded held-out data, and training from the
// true θ on --sanity-size noise-free transitions by L-BFGS and by the chosen optimizer (the
// first two must give test_error ≈ 0).
#include <lcprelax/learn/polygon_objective.hpp>
#include <lcprelax/learn/polygon_scene.hpp>
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/line_plot.hpp>

#include "csv_table.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>

using namespace lcprelax;
using namespace lcprelax::learn;

namespace {

struct Problem {
  SceneDataset data;        // learning scene (polygon: candidate margin added) and transitions
  SimulatorSettings sim;    // the data's simulator settings (prediction)
};

struct RunResult {
  double test_error = 0, mode_error = 0, train_loss = 0, seconds = 0;
  int failed = 0, train_failed = 0, epochs = 0, contacts = 0;
  bool converged = false;
};

// The truth's normal softness (--true-compliance, --true-erp); the learners' scene stays rigid.
struct TrueSoftness {
  double compliance = 0.0, erp = 0.0;
};

Problem make_problem(const std::string& scene, int n, std::uint64_t seed, const TrueSoftness& soft) {
  Problem p;
  if (scene == "polygon") {
    PolygonDataSettings g;
    g.seed = seed;
    g.compliance = soft.compliance;
    g.erp = soft.erp;
    g.trajectories = std::max(2, n / 30 + 2);  // ~45 contact transitions per throw of 60 steps
    PolygonDataset d = generate_polygon_dataset(reference_polygon_model(), g);
    if (static_cast<int>(d.transitions.size()) < n) throw std::runtime_error("polygon: too few transitions");
    d.transitions.resize(static_cast<std::size_t>(n));
    p.data = polygon_scene_dataset(reference_polygon_model(), d, PolygonLossSettings{}.candidate_margin);
    p.sim = p.data.scene.settings;
    p.sim.margin = d.margin;
  } else {
    LearningPileOptions po;
    po.bodies = 30;
    SceneDatasetSettings g;
    g.steps = n;
    g.seed = seed;
    Scene truth = make_learning_pile(po);
    truth.world.friction.default_compliance = soft.compliance;
    truth.world.friction.default_erp = soft.erp;
    p.data = generate_scene_dataset(truth, g);
    p.data.scene.world.friction.default_compliance = p.data.scene.world.friction.default_erp = 0.0;
    if (static_cast<int>(p.data.transitions.size()) > n) p.data.transitions.resize(static_cast<std::size_t>(n));
    p.sim = p.data.scene.settings;
  }
  p.sim.threads = 1;
  return p;
}

void add_noise(SceneDataset& d, double sigma, std::uint64_t seed) {
  double lin = 0, ang = 0;
  long count = 0;
  for (const SceneTransition& t : d.transitions)
    for (std::size_t b = 0; b < t.next_velocity.size(); ++b)
      if (!d.scene.world.bodies[b].is_static)
        lin += t.next_velocity[b].head<2>().squaredNorm() / 2, ang += t.next_velocity[b][2] * t.next_velocity[b][2], ++count;
  const double s_lin = sigma * std::sqrt(lin / count), s_ang = sigma * std::sqrt(ang / count);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  for (SceneTransition& t : d.transitions)
    for (std::size_t b = 0; b < t.next_velocity.size(); ++b)
      if (!d.scene.world.bodies[b].is_static)
        for (int i = 0; i < 3; ++i) t.next_velocity[b][i] += (i < 2 ? s_lin : s_ang) * normal(rng);
}

SceneParameterSettings param_settings(const std::string& name) {
  SceneParameterSettings s;
  if (name == "structured") s.learn.gap = s.learn.residual = true, s.mu_per_pair = true;
  else if (name == "residual") s.learn = SceneLearnFlags{false, false, false, false, false, false, true};
  else if (name == "block") s.learn.block = true;
  else if (name == "block_tied") s.learn.block_tied = true;
  else if (name == "softness") s.learn.softness = true, s.mu_per_pair = true;
  else if (name != "physical")
    throw InputError("--params: unknown '" + name + "' (physical, structured, residual, block, block_tied, softness)");
  return s;
}

bool physical_kind(SceneParameterMap::Kind k) {
  using K = SceneParameterMap::Kind;
  return k == K::mu || k == K::mass || k == K::inertia || k == K::vertex || k == K::angle || k == K::offset ||
         k == K::segment_end;
}

// θ₀: the physical parameters perturbed (the physical layout's draws), the other terms at the truth (0).
ParameterSet initial_theta(const World& world, const SceneParameterMap& map, double perturb, std::uint64_t seed) {
  const SceneParameterMap phys(world, SceneParameterSettings{});
  const ParameterSet p0 = perturb_scene_parameters(phys.parameters(world), phys, perturb, seed);
  ParameterSet theta = map.parameters(world);
  for (Index k = 0; k < theta.size(); ++k) {
    const std::string& name = theta[k].name;
    if (name.rfind("mu[", 0) == 0) theta.set_value(name, p0.value("mu"));
    else if (physical_kind(map.kind(k)))  // the nonphysical terms keep the truth
      theta.set_value(name, p0.value(name));
  }
  return theta;
}

double tangent_speed(const World& w, const Contact& c, const std::vector<Vec3>& v, const Vec2& dir) {
  auto point_velocity = [&](int b) -> Vec2 {
    if (b < 0 || w.bodies[b].is_static) return Vec2::Zero();
    const Vec2 r = c.point - w.bodies[b].pose.head<2>();
    return v[b].head<2>() + v[b][2] * Vec2(-r.y(), r.x());
  };
  return dir.dot(point_velocity(c.body_a) - point_velocity(c.body_b));
}

std::array<int, 9> contact_key(const Contact& c) {
  const Contact::Feature& f = c.feature;
  return {c.body_a, c.body_b, static_cast<int>(c.static_kind), c.static_index, static_cast<int>(f.kind), f.face_on_a,
          f.edge, f.vertex, f.side};
}

// Held-out errors of θ (map on the problem's world) against the recorded next velocities.
RunResult evaluate_test(const Problem& test, const SceneParameterMap& map, const ParameterSet& theta, double stick_tol) {
  RunResult r;
  World learned = test.data.scene.world;
  map.apply(theta, learned);
  double err2 = 0, ref2 = 0;
  int wrong = 0;
  for (const SceneTransition& t : test.data.transitions) {
    World truth = test.data.scene.world, model = learned;
    for (World* w : {&truth, &model})
      for (std::size_t b = 0; b < w->bodies.size(); ++b) w->bodies[b].pose = t.pose[b], w->bodies[b].velocity = t.velocity[b];
    // The true step's contacts (geometry at the recorded state), active ones only.
    const StepContacts found = find_step_contacts(truth, test.sim, t.applied);
    std::vector<const Contact*> active;
    for (const Contact& c : found.contacts)
      if (tangent_speed(truth, c, t.next_velocity, c.normal) + std::max(c.gap, 0.0) / test.sim.dt <= 1e-6)
        active.push_back(&c);
    r.contacts += static_cast<int>(active.size());
    Simulator sim(model, test.sim);
    const StepStats st = sim.step(t.applied);
    if (st.failed_islands > 0) {
      ++r.failed;
      wrong += static_cast<int>(active.size());
      continue;
    }
    std::vector<Vec3> v_hat(model.bodies.size());
    for (std::size_t b = 0; b < v_hat.size(); ++b) {
      v_hat[b] = sim.world().bodies[b].velocity;
      if (model.bodies[b].is_static) continue;
      err2 += (v_hat[b] - t.next_velocity[b]).squaredNorm();
      ref2 += t.next_velocity[b].squaredNorm();
    }
    // The learned step's own contact at the same feature, its tangential speed on v̂⁺ (none: wrong).
    for (const Contact* c : active) {
      const Vec2 tan(-c->normal.y(), c->normal.x());
      const bool stick = std::abs(tangent_speed(truth, *c, t.next_velocity, tan)) <= stick_tol;
      const auto same = std::find_if(sim.contacts().begin(), sim.contacts().end(), [&](const Contact& d) {
        return contact_key(d) == contact_key(*c);
      });
      if (same == sim.contacts().end()) {
        ++wrong;
        continue;
      }
      const Vec2 tan_hat(-same->normal.y(), same->normal.x());
      if (stick != (std::abs(tangent_speed(model, *same, v_hat, tan_hat)) <= stick_tol)) ++wrong;
    }
  }
  r.test_error = std::sqrt(err2 / ref2);
  r.mode_error = r.contacts > 0 ? static_cast<double>(wrong) / r.contacts : 0.0;
  return r;
}

// --batch and --threads (header comment).
struct Protocol {
  int batch = 0;
  int threads = 1;
};
Protocol g_protocol;

RunResult run(const Problem& train_data, const Problem& test, const std::string& param, ParameterSet* start_override,
              double perturb, std::uint64_t seed, int epochs, double stick_tol, const std::string& optimizer, double lr,
              int polish, LossMethod loss, ParameterSet* theta_out = nullptr) {
  const auto t0 = std::chrono::steady_clock::now();
  const World& world = train_data.data.scene.world;
  const SceneParameterMap map(world, param_settings(param));
  ParameterSet theta = start_override ? *start_override : initial_theta(world, map, perturb, seed);
  SceneLossSettings ls;
  ls.method = loss;
  SceneObjective objective(train_data.data, map, ls);
  TrainSettings t;
  const Index n = static_cast<Index>(train_data.data.transitions.size());
  t.epochs = epochs;
  t.threads = g_protocol.threads;
  if (g_protocol.batch > 0 && n > g_protocol.batch && optimizer != "lbfgs") {  // Adam's steps
    t.batch = g_protocol.batch;
    t.epochs = std::max(1, static_cast<int>(std::lround(static_cast<double>(epochs) * g_protocol.batch / n)));
    t.patience = 0;  // every epoch (no convergence test: with mini-batches it costs a full pass per epoch)
  }
  if (optimizer == "lbfgs") {
    t.optimizer.kind = OptimizerKind::lbfgs;
    t.optimizer.learning_rate = 1.0;
  } else {  // the CLI's default (lcprelax learn polygon|scene): Adam, lr 0.02, decay 0.003
    t.optimizer.kind = OptimizerKind::adam;
    t.optimizer.learning_rate = lr;
    t.optimizer.decay = 0.003;
  }
  std::vector<Index> all(train_data.data.transitions.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
  TrainResult tr = epochs > 0 ? train(objective, theta, all, {}, t) : TrainResult{};
  if (optimizer == "adam+lbfgs" && polish > 0) {  // L-BFGS from Adam's end point (Adam's step floor)
    t.epochs = polish;
    t.batch = TrainSettings{}.batch;  // full batch
    t.patience = TrainSettings{}.patience;
    t.optimizer = OptimizerSettings{};
    t.optimizer.kind = OptimizerKind::lbfgs;
    t.optimizer.learning_rate = 1.0;
    const TrainResult p = train(objective, theta, all, {}, t);
    tr.history.insert(tr.history.end(), p.history.begin(), p.history.end());
    tr.failed += p.failed, tr.converged = p.converged, tr.stop_reason += "; then " + p.stop_reason;
  }
  RunResult r = evaluate_test(test, map, theta, stick_tol);
  if (theta_out) *theta_out = theta;
  r.epochs = static_cast<int>(tr.history.size());
  r.converged = tr.converged;
  r.train_failed = tr.failed;
  r.train_loss = evaluate_mean(objective, theta, all, g_protocol.threads).loss;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

// The training loss at the data's true θ (param's layout; the nonphysical terms at 0): the
// value a consistent loss would have at its minimizer, to compare with the learned θ's.
double loss_at_truth(const Problem& train_data, const std::string& param, LossMethod loss) {
  const World& world = train_data.data.scene.world;
  const SceneParameterMap map(world, param_settings(param));
  SceneLossSettings ls;
  ls.method = loss;
  SceneObjective objective(train_data.data, map, ls);
  std::vector<Index> all(train_data.data.transitions.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
  return evaluate_mean(objective, map.parameters(world), all, g_protocol.threads).loss;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("learning curves of the scene path's parameterizations: polygon, 30-body pile (issue 20)");
  std::string scene = "polygon", params_list = "physical,structured,residual", sizes_list = "10,30,100,300,1000";
  std::string csv_path, plot, optimizer = "adam", loss_name = "relaxed";
  double lr = 0.02;
  int polish = 100;
  int seeds = 5, first_seed = 1, test_size = 400, epochs = 300, sanity_size = 30;
  double noise = 0.02, perturb = 0.25, stick_tol = 1e-3;
  app.add_option("--scene", scene, "polygon or pile30")->check(CLI::IsMember({"polygon", "pile30"}));
  app.add_option("--sizes", sizes_list, "training set sizes (transitions)");
  app.add_option("--params", params_list, "parameterizations: physical, structured, residual, block, block_tied, softness");
  app.add_option("--loss", loss_name, "training loss: relaxed or hard")->check(CLI::IsMember({"relaxed", "hard"}));
  std::string start = "perturbed";
  app.add_option("--start", start,
                 "perturbed (theta0 = the physical parameters perturbed by --perturb) or relaxed (theta0 = the "
                 "physical parameters learned first by the relaxed loss with L-BFGS, 100 iterations, from that "
                 "start on the same data; the nonphysical terms at 0)")
      ->check(CLI::IsMember({"perturbed", "relaxed"}));
  app.add_option("--seeds", seeds, "seeds per size");
  app.add_option("--first-seed", first_seed,
                 "first seed (seeds first..first+seeds-1; a seed's data and start do not depend on the others)")
      ->check(CLI::PositiveNumber);
  app.add_option("--test", test_size, "held-out transitions");
  app.add_option("--epochs", epochs, "L-BFGS iteration cap");
  app.add_option("--optimizer", optimizer, "adam (lr --lr, decay 0.003: the CLI's), lbfgs (lr 1) or adam+lbfgs")
      ->check(CLI::IsMember({"adam", "lbfgs", "adam+lbfgs"}));
  app.add_option("--polish", polish, "adam+lbfgs: L-BFGS iteration cap after the --epochs of Adam");
  app.add_option("--lr", lr, "Adam learning rate");
  app.add_option("--noise", noise, "relative noise on the training next velocities");
  app.add_option("--perturb", perturb, "relative perturbation of the initial physical parameters");
  TrueSoftness soft;
  app.add_option("--true-compliance", soft.compliance,
                 "normal compliance (1/kg) of the data's truth (world.hpp FrictionTable); the models start rigid");
  app.add_option("--true-erp", soft.erp, "erp of the data's truth, in [0, 1]");
  app.add_option("--stick-tol", stick_tol, "tangential speed (m/s) below which a contact sticks");
  app.add_option("--sanity-size", sanity_size, "training transitions of the sanity run from the truth (0: skip)");
  app.add_option("--csv", csv_path, "CSV of every run (none without this option)");
  app.add_option("--plot", plot, "plot of the median test error (.png/.svg); also _mode");
  app.add_option("--batch", g_protocol.batch,
                 "Adam (also adam+lbfgs's Adam): mini-batches of this size above it, epochs scaled to the same number of "
                 "steps (0: full batch)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--threads", g_protocol.threads, "threads of the batch evaluations")->check(CLI::PositiveNumber);
  bool truth_loss = false;
  app.add_flag("--truth-loss", truth_loss,
               "also print the training loss at the true theta of each (N, seed) (one more pass over the data)");
  CLI11_PARSE(app, argc, argv);
  if (g_protocol.batch > 0 && optimizer == "lbfgs") {
    std::fprintf(stderr, "--batch needs --optimizer adam or adam+lbfgs (L-BFGS is full batch)\n");
    return 2;
  }
  const std::vector<std::string> params = bench::split_list(params_list);
  std::vector<int> sizes;
  for (const std::string& s : bench::split_list(sizes_list)) sizes.push_back(std::stoi(s));

  const LossMethod loss = loss_name == "hard" ? LossMethod::hard : LossMethod::relaxed;
  // The CSV's scene column: "<scene>_soft" for data from a soft truth (a different problem).
  const std::string scene_label = soft.compliance != 0.0 || soft.erp != 0.0 ? scene + "_soft" : scene;
  if (scene_label != scene)
    std::printf("Data from a soft truth: normal compliance %g 1/kg, erp %g (the models start rigid)\n", soft.compliance,
                soft.erp);
  std::printf("Learning curves, %s (%s loss, %s: %d epochs, lr %g, L-BFGS polish <= %d; noise %g relative on "
              "v+, perturb %g, %d held-out transitions, stick: |Jt v+| <= %g m/s)\n",
              scene.c_str(), loss_name.c_str(), optimizer.c_str(), epochs, optimizer == "lbfgs" ? 1.0 : lr, optimizer == "adam+lbfgs" ? polish : 0, noise, perturb,
              test_size, stick_tol);
  if (g_protocol.batch > 0)
    std::printf("mini-batches of %d above N = %d, epochs scaled to round(%d*%d/N) (the same %d steps); %d threads\n",
                g_protocol.batch, g_protocol.batch, epochs, g_protocol.batch, epochs, g_protocol.threads);
  std::map<int, Problem> tests;
  const int last_seed = first_seed + seeds - 1;
  for (int s = first_seed; s <= last_seed; ++s) tests[s] = make_problem(scene, test_size, 777777 + s, soft);
  {
    const Problem& test = tests[first_seed];
    std::printf("held-out set of seed %d: %zu transitions, %zu bodies\n", first_seed, test.data.transitions.size(),
                test.data.scene.world.bodies.size());
    for (const std::string& param : params) {
      const SceneParameterMap map(test.data.scene.world, param_settings(param));
      const RunResult r = evaluate_test(test, map, map.parameters(test.data.scene.world), stick_tol);
      std::printf("sanity: %-10s (%ld parameters) true theta vs recorded held-out: test_error %.3g, mode_error %.3g, "
                  "failed %d, %d active contacts\n",
                  param.c_str(), static_cast<long>(map.size()), r.test_error, r.mode_error, r.failed, r.contacts);
      if (sanity_size > 0) {
        const Problem clean = make_problem(scene, sanity_size, 1000 + sanity_size, soft);
        ParameterSet truth = map.parameters(clean.data.scene.world);
        for (const std::string& opt : {std::string("lbfgs"), optimizer}) {
          const RunResult q = run(clean, test, param, &truth, perturb, 1, epochs, stick_tol, opt, lr, polish, loss);
          std::printf("sanity: %-10s trained by %s from the true theta on %d noise-free transitions: test_error %.3g, "
                      "mode_error %.3g, train_loss %.3g, %d epochs, %.1f s\n",
                      param.c_str(), opt.c_str(), sanity_size, q.test_error, q.mode_error, q.train_loss, q.epochs,
                      q.seconds);
          if (opt == optimizer) break;
        }
      }
      std::fflush(stdout);
    }
  }

  std::ofstream csv;
  if (!bench::open_optional_csv(csv_path, csv)) return 2;
  csv << "scene,param,method,samples,seed,epochs,converged,train_loss,test_error,mode_error,contacts,failed,"
         "train_failed,seconds\n";
  std::printf("%-12s %7s %12s %12s %12s %8s %8s %9s\n", "param", "N", "median_err", "max_err", "mode_err", "failed",
              "trfail", "seconds");
  struct Cell {
    std::vector<double> err, mode;
    int failed = 0, train_failed = 0;
    double seconds = 0;
  };
  std::map<std::string, std::map<int, Cell>> cells;
  std::string method = optimizer == "adam" ? loss_name : loss_name + "/" + optimizer;  // CSV: loss/optimizer
  if (start == "relaxed") method = "relaxed+" + method;
  // --start relaxed: the first stage per (N, seed), shared by every parameterization.
  std::map<std::pair<int, int>, ParameterSet> stage1;
  auto first_stage = [&](const Problem& train_data, int n, int s) -> ParameterSet* {
    if (start != "relaxed") return nullptr;
    auto it = stage1.find({n, s});
    if (it == stage1.end()) {
      ParameterSet phys;
      run(train_data, tests[s], "physical", nullptr, perturb, static_cast<std::uint64_t>(s), 100, stick_tol, "lbfgs",
          lr, 0, LossMethod::relaxed, &phys);
      it = stage1.emplace(std::make_pair(n, s), phys).first;
    }
    return &it->second;
  };
  for (const std::string& param : params)
    for (int n : sizes) {
      Cell& c = cells[param][n];
      for (int s = first_seed; s <= last_seed; ++s) {
        Problem train_data = make_problem(scene, n, static_cast<std::uint64_t>(1000 * s + n), soft);
        add_noise(train_data.data, noise, static_cast<std::uint64_t>(31 * s + n));
        ParameterSet* physical_start = first_stage(train_data, n, s);
        ParameterSet start_theta;
        if (physical_start) {  // the param's layout at the truth, its physical entries from stage 1
          const SceneParameterMap map(train_data.data.scene.world, param_settings(param));
          start_theta = map.parameters(train_data.data.scene.world);
          for (Index k = 0; k < physical_start->size(); ++k)
            start_theta.set_value((*physical_start)[k].name, (*physical_start)[k].value);
        }
        const RunResult r = run(train_data, tests[s], param, physical_start ? &start_theta : nullptr, perturb,
                                static_cast<std::uint64_t>(s), epochs, stick_tol, optimizer, lr, polish, loss);
        if (truth_loss)
          std::printf("%s N = %d seed %d: training loss %.6g at the learned theta, %.6g at the true theta\n",
                      param.c_str(), n, s, r.train_loss, loss_at_truth(train_data, param, loss));
        csv << scene_label << ',' << param << ',' << method << ',' << n << ',' << s << ',' << r.epochs << ',' << r.converged << ','
            << r.train_loss << ',' << r.test_error << ',' << r.mode_error << ',' << r.contacts << ',' << r.failed << ','
            << r.train_failed << ',' << r.seconds << '\n';
        csv.flush();
        c.err.push_back(r.test_error);
        c.mode.push_back(r.mode_error);
        c.failed += r.failed;
        c.train_failed += r.train_failed;
        c.seconds += r.seconds;
      }
      double mode = 0;
      for (double m : c.mode) mode += m / c.mode.size();
      std::printf("%-12s %7d %12.4g %12.4g %12.4g %8d %8d %9.1f\n", param.c_str(), n, bench::median(c.err),
                  *std::max_element(c.err.begin(), c.err.end()), mode, c.failed, c.train_failed, c.seconds);
      std::fflush(stdout);
    }
  std::printf("\nSummary: smallest N with median test error <= 1%%; mean mode error at the largest N (%d)\n", sizes.back());
  for (const std::string& param : params) {
    std::string reach = "> " + std::to_string(sizes.back());
    for (int n : sizes)
      if (bench::median(cells[param][n].err) <= 0.01) {
        reach = std::to_string(n);
        break;
      }
    double m = 0;
    for (double x : cells[param][sizes.back()].mode) m += x / cells[param][sizes.back()].mode.size();
    std::printf("%-12s %10s %12.4g\n", param.c_str(), reach.c_str(), m);
  }
  if (!plot.empty() && line_plot_available()) {
    const std::size_t dot = plot.rfind('.');
    for (int which = 0; which < 2; ++which) {
      std::vector<LineSeries> series;
      for (const std::string& param : params) {
        LineSeries l{param, {}, {}};
        l.markers = true;
        for (int n : sizes) {
          const Cell& c = cells[param][n];
          double m = 0;
          for (double x : c.mode) m += x / c.mode.size();
          l.x.push_back(n);
          l.y.push_back(which == 0 ? bench::median(c.err) : m);
        }
        series.push_back(l);
      }
      LinePlotOptions o;
      o.x_label = "training transitions";
      o.log_x = true;
      o.log_y = which == 0;
      o.title = scene + (which == 0 ? ": held-out next-state error (median of seeds)"
                                    : ": held-out stick/slip mode error (mean of seeds)");
      o.y_label = which == 0 ? "relative RMS error of v+" : "fraction of wrong modes";
      write_line_plot(which == 0 ? plot : plot.substr(0, dot) + "_mode" + plot.substr(dot), series, o);
    }
  }
  return 0;
}
