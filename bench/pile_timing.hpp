#pragma once
// Timing of lcprelax's Simulator on a settled pile (bench/run_pile_scaling.cpp,
// bench/run_pile_peers.cpp, bench/bench_pile.cpp). Header-only.
//
// What is measured (SI units: s, m, J):
// - settle_pile: a pile of make_pile_scene drops under gravity and is stepped until the
//   largest body speed |v| + |ω|·r (r: circumradius) falls below `speed_tol` m/s, or
//   `max_steps` steps, or `budget` s of wall time. It records, like `lcprelax pile`, the
//   most contacts of a step, wall time per step, the largest start-of-step penetration,
//   failed islands and the largest one-step increase of kinetic + potential energy
//   divided by |initial total energy|.
// - time_window: from a (settled) scene, a fresh Simulator with the given settings runs
//   `warmup` untimed steps (so that per-contact warm starts exist), then `steps` timed
//   steps; wall time per step (std::chrono::steady_clock around Simulator::step only),
//   process CPU time per step (all threads; robust against other load on a shared
//   machine, and with 1 thread the cost of the step itself), mean and max contacts, islands, largest island unknowns, work (Lemke pivots +
//   interior-point iterations), failed islands, max penetration. It stops early once the
//   timed steps have used `budget` s (budget_hit = true; seconds_per_step is then over the
//   steps actually run).
// - loglog_slope: least-squares slope of log y against log x.
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace lcprelax::bench {

/// Process CPU time (s), all threads: robust against other load on a shared machine.
inline double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

inline double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Largest speed of a material point of any dynamic body (m/s): |v| + |ω|·r.
inline double max_body_speed(const World& world) {
  double s = 0.0;
  for (const RigidBody& b : world.bodies) {
    if (b.is_static) continue;
    double r = 0.0;
    for (const Vec2& v : b.shape.vertices) r = std::max(r, v.norm());
    s = std::max(s, b.velocity.head<2>().norm() + std::abs(b.velocity(2)) * r);
  }
  return s;
}

struct SettleResult {
  Scene scene;                 ///< the world after the last settle step
  int steps = 0;               ///< steps taken
  bool settled = false;        ///< max_body_speed ≤ speed_tol reached
  double final_speed = 0.0;    ///< max_body_speed at the end (m/s)
  double seconds = 0.0;        ///< wall time of all steps (s)
  int contacts_max = 0;
  double max_penetration = 0.0;  ///< m
  double max_residual = 0.0;
  double max_energy_gain = -std::numeric_limits<double>::infinity();  ///< relative to |E0|
  long failed_islands = 0;
  std::string first_failure;
};

/// Drops `scene` and steps it with `settings` until it settles (see the file comment).
/// `min_steps` steps are always taken (the bodies start at rest-ish speeds in the air).
/// With `progress`, one line every 50 steps (step, wall seconds, contacts, speed).
inline SettleResult settle_pile(Scene scene, const SimulatorSettings& settings, int min_steps, int max_steps,
                                double speed_tol, double budget, std::ostream* progress = nullptr) {
  Simulator sim = make_simulator(scene, settings);
  SettleResult r;
  const double e0 = sim.total_energy();
  double energy = e0;
  const double t0 = now_seconds();
  for (int k = 0; k < max_steps; ++k) {
    const StepStats st = sim.step();
    ++r.steps;
    const double e = sim.total_energy();
    r.max_energy_gain = std::max(r.max_energy_gain, (e - energy) / std::abs(e0));
    energy = e;
    r.contacts_max = std::max(r.contacts_max, st.contacts);
    r.max_penetration = std::max(r.max_penetration, st.max_penetration);
    r.max_residual = std::max(r.max_residual, st.max_residual);
    if (st.failed_islands > 0 && r.failed_islands == 0) r.first_failure = st.first_failure;
    r.failed_islands += st.failed_islands;
    r.final_speed = max_body_speed(sim.world());
    if (progress && (k + 1) % 50 == 0)
      *progress << "  settle step " << k + 1 << ": " << now_seconds() - t0 << " s, " << st.contacts << " contacts, speed "
                << r.final_speed << " m/s" << std::endl;
    if (k + 1 >= min_steps && r.final_speed <= speed_tol) {
      r.settled = true;
      break;
    }
    if (now_seconds() - t0 > budget) break;
  }
  r.seconds = now_seconds() - t0;
  r.scene = std::move(scene);
  r.scene.world = sim.world();
  return r;
}

struct WindowStats {
  int steps = 0;                 ///< timed steps actually run
  bool budget_hit = false;       ///< stopped early by the time budget
  double seconds_per_step = 0.0; ///< wall (s)
  double cpu_per_step = 0.0;     ///< process CPU time of all threads (s)
  double contacts_mean = 0.0;
  int contacts_max = 0;
  int islands_max = 0;
  int unknowns_max = 0;          ///< largest island unknowns (max over the steps)
  double work_mean = 0.0;        ///< Lemke pivots + IPM iterations per step
  double collision_mean = 0.0;   ///< StepStats::collision_seconds per step (s)
  double solve_mean = 0.0;       ///< StepStats::solve_seconds per step (s)
  long failed_islands = 0;
  /// StepStats::inaccurate_islands summed: answers that are not the model's exact solution
  /// (lcp model: the perturbed or regularized LCP's, contact_step.hpp steps 3–4)
  long inaccurate_islands = 0;
  long newton_fallbacks = 0;     ///< StepStats::newton_fallbacks summed (convex active-set Newton)
  double max_penetration = 0.0;  ///< m
  double final_speed = 0.0;      ///< max_body_speed after the window (m/s)
  /// Convex model: phase solvers updated in place / all phase solvers prepared (the share of
  /// symbolic analyses saved by SimulatorSettings::reuse_convex_solvers); 0 without.
  double solver_reuse = 0.0;
  /// Convex model with reuse_convex_solvers, per step (s): StepStats::qp_assemble_seconds,
  /// qp_prepare_seconds (setup/update incl. symbolic analysis), qp_solve_seconds and the
  /// numeric factorizations within it (qp_factor_seconds).
  double qp_assemble = 0.0, qp_prepare = 0.0, qp_solve = 0.0, qp_factor = 0.0;
  std::string first_failure;
};

/// Times `steps` steps of `scene` after `warmup` untimed ones (see the file comment).
inline WindowStats time_window(const Scene& scene, const SimulatorSettings& settings, int warmup, int steps,
                               double budget) {
  Simulator sim = make_simulator(scene, settings);
  for (int k = 0; k < warmup; ++k) sim.step();
  WindowStats w;
  double total = 0.0, cpu = 0.0, contacts = 0.0, work = 0.0, collision = 0.0, solve = 0.0;
  long updates = 0, prepared = 0;
  for (int k = 0; k < steps; ++k) {
    const double t0 = now_seconds(), c0 = cpu_seconds();
    const StepStats st = sim.step();
    total += now_seconds() - t0;
    cpu += cpu_seconds() - c0;
    ++w.steps;
    contacts += st.contacts;
    work += static_cast<double>(st.work);
    collision += st.collision_seconds;
    solve += st.solve_seconds;
    updates += st.solver_updates;
    w.qp_assemble += st.qp_assemble_seconds;
    w.qp_prepare += st.qp_prepare_seconds;
    w.qp_solve += st.qp_solve_seconds;
    w.qp_factor += st.qp_factor_seconds;
    prepared += st.solver_updates + st.solver_setups;
    w.contacts_max = std::max(w.contacts_max, st.contacts);
    w.islands_max = std::max(w.islands_max, st.islands);
    w.unknowns_max = std::max(w.unknowns_max, st.largest_island_unknowns);
    w.max_penetration = std::max(w.max_penetration, st.max_penetration);
    if (st.failed_islands > 0 && w.failed_islands == 0) w.first_failure = st.first_failure;
    w.failed_islands += st.failed_islands;
    w.inaccurate_islands += st.inaccurate_islands;
    w.newton_fallbacks += st.newton_fallbacks;
    if (total > budget && k + 1 < steps) {
      w.budget_hit = true;
      break;
    }
  }
  w.seconds_per_step = w.steps > 0 ? total / w.steps : 0.0;
  w.cpu_per_step = w.steps > 0 ? cpu / w.steps : 0.0;
  w.contacts_mean = w.steps > 0 ? contacts / w.steps : 0.0;
  w.work_mean = w.steps > 0 ? work / w.steps : 0.0;
  w.collision_mean = w.steps > 0 ? collision / w.steps : 0.0;
  w.solve_mean = w.steps > 0 ? solve / w.steps : 0.0;
  for (double* x : {&w.qp_assemble, &w.qp_prepare, &w.qp_solve, &w.qp_factor}) *x = w.steps > 0 ? *x / w.steps : 0.0;
  w.solver_reuse = prepared > 0 ? static_cast<double>(updates) / static_cast<double>(prepared) : 0.0;
  w.final_speed = max_body_speed(sim.world());
  return w;
}

/// Least-squares slope of log(y) against log(x) over the pairs with x, y > 0; NaN when
/// fewer than two such pairs or all x are equal.
inline double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> lx, ly;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i)
    if (x[i] > 0 && y[i] > 0) {
      lx.push_back(std::log(x[i]));
      ly.push_back(std::log(y[i]));
    }
  const double n = static_cast<double>(lx.size());
  if (lx.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < lx.size(); ++i) mx += lx[i] / n, my += ly[i] / n;
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < lx.size(); ++i) {
    sxx += (lx[i] - mx) * (lx[i] - mx);
    sxy += (lx[i] - mx) * (ly[i] - my);
  }
  return sxx > 0 ? sxy / sxx : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace lcprelax::bench
