// run_pile_scaling: time per step of lcprelax's Simulator against the number of bodies
// and contacts of a settled pile, for both contact models and 1 vs T OpenMP threads.
//
//   run_pile_scaling [--sizes 10,20,...] [--steps 10] [--warmup 2] [--models lcp,convex,convex-fresh,convex-newton]
//                    [--threads 1,2] [--lcp-max-bodies 100] [--budget 60]
//                    [--settle-max-steps 150] [--settle-speed 0.05] [--settle-budget 1200]
//                    [--resettle-max-steps 0] [--release-open-contacts] [--lu-pivot-tolerance U]
//                    [--seed 1] [--csv pile_scaling.csv]
//
// Per size N (bodies): make_pile_scene(bodies = N, seed, other PileOptions at their
// defaults: polygons of 3-8 vertices, circumradius 0.05-0.15 m, 1000 kg/m², μ = 0.5,
// Δt = 0.01 s, container ≈ five layers deep) is dropped and settled with the convex model
// (pile_timing.hpp settle_pile: until every body point moves slower than --settle-speed
// m/s, at least 100 steps, at most --settle-max-steps or --settle-budget s); its stats are
// the CSV row with phase = settle (they are what `lcprelax pile --json` reports for those
// steps). Then, from that same settled state, for every model and thread count
// (SimulatorSettings::threads), a fresh Simulator runs --warmup untimed steps and
// --steps timed steps (phase = window; pile_timing.hpp time_window). Model convex-fresh is
// the convex model without SimulatorSettings::reuse_convex_solvers (fresh phase solvers and
// symbolic analyses every step), for before/after timings in one run; the printed "solver
// reuse" is the share of phase solvers updated in place. With --resettle-max-steps K > 0 the
// LCP model's window starts from the pile settled a second time, by the LCP model itself
// (same speed test and budget, at most K steps; row phase = resettle): a pile at rest under
// the slightly soft convex model is not at rest under the exact one, and some of its bodies
// tip and slide for a few dozen steps (200 bodies, seed 2: 27–46 bodies faster than 0.1 m/s
// in the first steps, every body at rest to 1e-14 m/s after 40). The LCP model is run
// only up to --lcp-max-bodies bodies (row with steps = 0 and a note above), and every
// window stops once its timed steps used --budget s (budget_hit = 1).
// --release-open-contacts: the convex settle runs with SimulatorSettings::
// convex_release_open_contacts (no body left held above its supports: a pile that is then
// nearly at rest under the LCP model too); the windows keep their models' defaults.
// --lu-pivot-tolerance U: the windows' LemkeSettings::lu_pivot_tolerance (KLU's partial-
// pivoting threshold of the lcp model's sparse Lemke basis; default that setting's).
// inaccurate_islands: islands whose answer is not the model's exact solution (the lcp model's
// perturbed or regularized LCP, models/contact_step.hpp), summed over the window's steps.
// speedup_vs_1 = (s/step with 1 thread) / (s/step with this many threads), same run, same
// settled state. Printed at the end: per model and thread count, the least-squares slope
// of log(s/step) against log(mean contacts) over the sizes measured (all, and those with
// ≥ 500 mean contacts), for wall time and for process CPU time (cpu_per_step). Units: seconds (wall, steady_clock), metres.
// Exit status: 0 after a run, 2 on bad arguments.
#include "pile_timing.hpp"

#include <lcprelax/scenes/pile_scene.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;
using namespace lcprelax::bench;

std::string csv_quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += (c == '\n' ? ' ' : c);
  }
  return out + "\"";
}

struct Row {
  std::string phase, model;
  int bodies = 0, threads = 0;
  WindowStats w;
  bool settled = false;
  double max_energy_gain = 0.0;
  double speedup = 0.0;  // 0: not applicable
  std::string note;
};

void write_row(std::ostream& os, const Row& r) {
  char buf[1024];
  std::snprintf(buf, sizeof buf, "%s,%d,%s,%d,%d,%d,%d,%.6g,%.1f,%d,%d,%d,%.1f,%.6g,%.6g,%.6g,%.6g,%.4g,%ld,%.6g,%.6g,%ld,%ld,", r.phase.c_str(),
                r.bodies, r.model.c_str(), r.threads, r.w.steps, r.w.budget_hit ? 1 : 0, r.settled ? 1 : 0,
                r.w.final_speed, r.w.contacts_mean, r.w.contacts_max, r.w.islands_max, r.w.unknowns_max, r.w.work_mean,
                r.w.seconds_per_step, r.w.cpu_per_step, r.w.collision_mean, r.w.solve_mean, r.speedup, r.w.failed_islands, r.w.max_penetration, r.max_energy_gain, r.w.newton_fallbacks,
                r.w.inaccurate_islands);
  os << buf << csv_quote(r.note.empty() ? r.w.first_failure : r.note) << '\n';
  os.flush();
}

}  // namespace

// The CSV row of a settle phase (threads 0: SimulatorSettings' default).
Row settle_row(const std::string& phase, int bodies, const std::string& model, const SettleResult& s,
               double settle_budget) {
  Row r;
  r.phase = phase;
  r.bodies = bodies;
  r.model = model;
  r.threads = 0;
  r.w.steps = s.steps;
  r.w.budget_hit = !s.settled && s.seconds > settle_budget;
  r.settled = s.settled;
  r.w.final_speed = s.final_speed;
  r.w.contacts_max = s.contacts_max;
  r.w.seconds_per_step = s.seconds / std::max(1, s.steps);
  r.w.failed_islands = s.failed_islands;
  r.w.max_penetration = s.max_penetration;
  r.w.first_failure = s.first_failure;
  r.max_energy_gain = s.max_energy_gain;
  return r;
}

int main(int argc, char** argv) {
  std::vector<int> sizes{10, 20, 50, 100, 200, 500, 1000, 2000};
  std::vector<std::string> models{"lcp", "convex"};
  std::vector<int> threads{1, 2};
  int steps = 10, warmup = 2, lcp_max_bodies = 100, settle_max_steps = 150, resettle_max_steps = 0;
  bool release_open_contacts = false;
  double budget = 60, settle_speed = 0.05, settle_budget = 1200;
  std::uint64_t seed = 1;
  std::string csv = "pile_scaling.csv";

  CLI::App app{"Time per step of a settled pile against its size, both contact models, 1 vs T threads"};
  app.add_option("--sizes", sizes, "Numbers of bodies")->delimiter(',')->check(CLI::Range(1, 1000000));
  app.add_option("--steps", steps, "Timed steps per window")->check(CLI::Range(1, 1000000))->capture_default_str();
  app.add_option("--warmup", warmup, "Untimed steps before each window")->check(CLI::Range(0, 1000))->capture_default_str();
  app.add_option("--models", models, "Contact models")->delimiter(',')->check(CLI::IsMember({"lcp", "convex", "convex-fresh", "convex-newton"}));
  app.add_option("--threads", threads, "Thread counts (1 is needed for speedup_vs_1)")
      ->delimiter(',')
      ->check(CLI::Range(1, 1024));
  app.add_option("--lcp-max-bodies", lcp_max_bodies, "Largest pile run with the LCP model")->capture_default_str();
  app.add_option("--budget", budget, "Wall-time budget of one timed window (s)")->capture_default_str();
  app.add_option("--settle-max-steps", settle_max_steps, "Most settle steps")->check(CLI::Range(100, 1000000));
  app.add_option("--resettle-max-steps", resettle_max_steps,
                 "LCP model: most steps of a second settle with the LCP model before its window (0: none)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  app.add_flag("--release-open-contacts", release_open_contacts,
               "Convex settle: release open contacts (SimulatorSettings::convex_release_open_contacts)");
  app.add_option("--settle-speed", settle_speed, "Settled when every body point is slower (m/s)")->capture_default_str();
  app.add_option("--settle-budget", settle_budget, "Wall-time budget of one settle (s)")->capture_default_str();
  double lu_pivot_tolerance = LemkeSettings{}.lu_pivot_tolerance;
  app.add_option("--lu-pivot-tolerance", lu_pivot_tolerance,
                 "Windows: LemkeSettings::lu_pivot_tolerance of the lcp model's sparse basis")
      ->check(CLI::Range(1e-12, 1.0))
      ->capture_default_str();
  app.add_option("--seed", seed, "Pile seed")->capture_default_str();
  app.add_option("--csv", csv, "CSV output file")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  std::ofstream out(csv);
  if (!out) {
    std::cerr << "cannot write " << csv << '\n';
    return 2;
  }
  out << "phase,bodies,model,threads,steps,budget_hit,settled,final_speed,contacts_mean,contacts_max,islands_max,"
         "unknowns_max,work_mean,seconds_per_step,cpu_per_step,collision_s,solve_s,speedup_vs_1,failed_islands,max_penetration,max_energy_gain,newton_fallbacks,inaccurate_islands,note\n";

  // per (model, threads): (mean contacts, s/step) over the sizes
  std::map<std::pair<std::string, int>, std::pair<std::vector<double>, std::vector<double>>> series, cpu_series;
  for (const int n : sizes) {
    PileOptions p;
    p.bodies = n;
    p.seed = seed;
    p.model = ContactModel::convex;
    SimulatorSettings settle_settings;
    settle_settings.convex_release_open_contacts = release_open_contacts;
    SettleResult s = settle_pile(make_pile_scene(p), settle_settings, 100, settle_max_steps, settle_speed,
                                 settle_budget);
    const Row sr = settle_row("settle", n, "convex", s, settle_budget);
    write_row(out, sr);
    std::printf("N=%d settle: %d steps, settled %d (speed %.3g m/s), contacts_max %d, %.4g s/step, failed %ld, "
                "max_pen %.3g m, max_energy_gain %.3g\n",
                n, s.steps, s.settled ? 1 : 0, s.final_speed, s.contacts_max, sr.w.seconds_per_step, s.failed_islands,
                s.max_penetration, s.max_energy_gain);
    std::fflush(stdout);

    for (const std::string& m : models) {
      Scene scene = s.scene;
      // convex-fresh: the convex model with fresh phase solvers every step (no reuse).
      const bool fresh = m == "convex-fresh", newton = m == "convex-newton";
      scene.settings.model = parse_contact_model(fresh || newton ? "convex" : m);
      if (resettle_max_steps > 0 && m == "lcp" && n <= lcp_max_bodies) {
        // A pile at rest under the convex model is not at rest under the exact model: let it
        // settle again with the window's model before timing (row phase = resettle).
        SettleResult rs = settle_pile(scene, SimulatorSettings{}, 1, resettle_max_steps, settle_speed, settle_budget);
        Row rr = settle_row("resettle", n, m, rs, settle_budget);
        write_row(out, rr);
        std::printf("N=%d resettle %s: %d steps, settled %d (speed %.3g m/s), contacts_max %d, %.4g s/step, failed %ld, "
                    "max_pen %.3g m, max_energy_gain %.3g\n",
                    n, m.c_str(), rs.steps, rs.settled ? 1 : 0, rs.final_speed, rs.contacts_max, rr.w.seconds_per_step,
                    rs.failed_islands, rs.max_penetration, rs.max_energy_gain);
        std::fflush(stdout);
        scene = std::move(rs.scene);
      }
      double t1 = 0.0;
      for (const int t : threads) {
        Row r;
        r.phase = "window";
        r.bodies = n;
        r.model = m;
        r.threads = t;
        if (m == "lcp" && n > lcp_max_bodies) {
          r.note = "skipped: bodies > --lcp-max-bodies";
          write_row(out, r);
          continue;
        }
        SimulatorSettings settings;
        settings.threads = t;
        settings.reuse_convex_solvers = !fresh;
        settings.lemke.lu_pivot_tolerance = lu_pivot_tolerance;
        if (newton) settings.convex_solver = ConvexSolver::active_set_newton;
        r.w = time_window(scene, settings, warmup, steps, budget);
        if (t == 1) t1 = r.w.seconds_per_step;
        if (t1 > 0 && r.w.seconds_per_step > 0) r.speedup = t1 / r.w.seconds_per_step;
        write_row(out, r);
        series[{m, t}].first.push_back(r.w.contacts_mean);
        series[{m, t}].second.push_back(r.w.seconds_per_step);
        cpu_series[{m, t}].first.push_back(r.w.contacts_mean);
        cpu_series[{m, t}].second.push_back(r.w.cpu_per_step);
        std::printf("N=%d %s T=%d: %d steps%s, contacts %.1f (max %d), islands %d, unknowns %d, work %.1f, "
                    "%.4g s/step (cpu %.4g s, collision %.3g, solve %.3g), speedup %.3g, failed %ld, inaccurate %ld, max_pen %.3g m, "
                    "newton fallbacks %ld, solver reuse %.2f, qp assemble %.3g, setup/update %.3g, solve %.3g (factor %.3g)%s%s\n",
                    n, m.c_str(), t, r.w.steps, r.w.budget_hit ? " (budget hit)" : "", r.w.contacts_mean,
                    r.w.contacts_max, r.w.islands_max, r.w.unknowns_max, r.w.work_mean, r.w.seconds_per_step,
                    r.w.cpu_per_step, r.w.collision_mean, r.w.solve_mean, r.speedup, r.w.failed_islands, r.w.inaccurate_islands, r.w.max_penetration, r.w.newton_fallbacks, r.w.solver_reuse, r.w.qp_assemble, r.w.qp_prepare, r.w.qp_solve, r.w.qp_factor, r.w.first_failure.empty() ? "" : ": ",
                    r.w.first_failure.c_str());
        std::fflush(stdout);
      }
    }
  }
  for (const auto* which : {&series, &cpu_series})
    for (const auto& [key, xy] : *which) {
      std::vector<double> bx, by;
      for (std::size_t i = 0; i < xy.first.size(); ++i)
        if (xy.first[i] >= 500) bx.push_back(xy.first[i]), by.push_back(xy.second[i]);
      std::printf("slope log(%s/step) vs log(contacts), %s T=%d: all sizes %.3f (%zu points), contacts >= 500 %.3f "
                  "(%zu points)\n",
                  which == &series ? "wall s" : "cpu s", key.first.c_str(), key.second,
                  loglog_slope(xy.first, xy.second), xy.first.size(), loglog_slope(bx, by), bx.size());
    }
  return 0;
}
