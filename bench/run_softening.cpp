// Physical error of the convex model's normal softening methods (models/normal_softening.hpp):
// penetration and energy on a falling pile and on a resting stack, for exp_phi (ρ),
// linear_penalty (ρ) and mujoco_impedance (MuJoCo's default solimp/solref), convex model.
//
//   run_softening [--csv bench/results/softening.csv] [--pile-bodies 30] [--steps 200]
//                 [--rho 1e-3] [--passes 1] > bench/results/softening.txt
//
// --passes: SimulatorSettings::post_stabilization_passes. 1 by default (not the simulator's
// 5): the further passes re-detect overlaps and project them to the slop, which would hide
// how deep each softening lets the pile overlap.
//
// Per scene and method: the largest penetration at the start of a step (StepStats, m; the
// post-stabilization removes overlap beyond the slop after each step), the largest
// one-step gain of total (kinetic + potential) energy (J; contacts should never add
// energy), the final energy minus the initial (J), the final kinetic energy (J), failed
// islands, and seconds.
//   pile:  PileOptions{bodies, seed 1} settling from its drop for `steps` steps;
//   stack: 10 boxes of 0.5 m at rest, `steps` steps (ideal: no motion, ΔE = 0).
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>

namespace {

using namespace lcprelax;

struct Row {
  double penetration = 0.0, energy_gain = 0.0, energy_change = 0.0, seconds = 0.0, kinetic = 0.0;
  int failed = 0;
};

Row run(const Scene& scene, const SimulatorSettings& base, int steps) {
  Simulator sim = make_simulator(scene, base);
  Row r;
  const double e0 = sim.total_energy();
  double e_prev = e0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    const StepStats st = sim.step();
    r.penetration = std::max(r.penetration, st.max_penetration);
    r.failed += st.failed_islands;
    const double e = sim.total_energy();
    r.energy_gain = std::max(r.energy_gain, e - e_prev);
    e_prev = e;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.energy_change = sim.total_energy() - e0;
  r.kinetic = sim.kinetic_energy();
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Penetration and energy error of the convex model's normal softening methods");
  std::string csv_path = "bench/results/softening.csv";
  int pile_bodies = 30, steps = 200;
  double rho = 1e-3;
  int passes = 1;
  app.add_option("--csv", csv_path, "CSV output");
  app.add_option("--pile-bodies", pile_bodies, "bodies of the pile");
  app.add_option("--steps", steps, "steps per run");
  app.add_option("--rho", rho, "ρ of exp_phi and linear_penalty");
  app.add_option("--passes", passes, "post-stabilization passes per step")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);

  std::ofstream csv(csv_path);
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", csv_path.c_str());
    return 1;
  }
  csv << "scene,softening,rho,steps,max_penetration,max_step_energy_gain,energy_change,final_kinetic,failed_islands,seconds\n";

  PileOptions po;
  po.bodies = pile_bodies;
  po.seed = 1;
  po.model = ContactModel::convex;
  const Scene pile = make_pile_scene(po);
  Scene stack = make_box_stack_scene(10, 0.5, 0.5);
  stack.settings.model = ContactModel::convex;  // make_simulator takes the model from the scene

  std::printf("Convex model, Δt = %g s, ρ = %g, %d steps each, %d post-stabilization pass(es) (penetration: "
              "largest −φ at a step's start)\n\n",
              pile.settings.dt, rho, steps, passes);
  std::printf("%-6s %-17s %14s %16s %14s %14s %7s %8s\n", "scene", "softening", "max pen. (m)", "max step ΔE⁺ (J)",
              "E − E0 (J)", "final KE (J)", "failed", "seconds");
  for (const auto& [name, scene] : {std::pair<const char*, const Scene*>{"pile", &pile}, {"stack", &stack}})
    for (NormalSoftening m :
         {NormalSoftening::exp_phi, NormalSoftening::linear_penalty, NormalSoftening::mujoco_impedance}) {
      // make_simulator takes dt, model, margin and the softening from the scene, ρ from s.
      Scene with = *scene;
      with.settings.model = ContactModel::convex;
      with.settings.convex_softening.method = m;
      SimulatorSettings s = with.settings;
      s.convex_rho = rho;
      s.post_stabilization_passes = passes;
      const Row r = run(with, s, steps);
      std::printf("%-6s %-17s %14.4e %16.4e %14.4e %14.4e %7d %8.2f\n", name, to_string(m), r.penetration,
                  r.energy_gain, r.energy_change, r.kinetic, r.failed, r.seconds);
      char line[400];
      std::snprintf(line, sizeof line, "%s,%s,%g,%d,%.6e,%.6e,%.6e,%.6e,%d,%.3f\n", name, to_string(m), rho, steps,
                    r.penetration, r.energy_gain, r.energy_change, r.kinetic, r.failed, r.seconds);
      csv << line;
    }
  return 0;
}
