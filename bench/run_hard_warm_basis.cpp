// Training with the hard loss on a pile scene, each island's Lemke started from the
// transition's stored final basis (SceneLossSettings::hard_warm_basis, learn/scene_objective.hpp)
// against cold starts: the same training run twice in one process, time and pivots per run.
//
//   run_hard_warm_basis [--bodies 30] [--transitions 100] [--epochs 20] [--seed 1] [--lr 0.01]
//
// Data: make_learning_pile(bodies, 3 classes, seed, LCP model), generate_scene_dataset with
// its defaults (pushes every step) for `transitions` steps. θ₀: the physical parameters
// (μ, mass, inertia, vertices per class) 5% off the truth (perturb_scene_parameters, seed 7).
// Training: Adam at --lr, full batch, one thread, no shuffle, `epochs` epochs exactly
// (convergence test off). Printed per run: wall seconds, Lemke pivots in all
// (SceneObjectiveStats::solver_work), contacts evaluated without a stored basis, islands
// solved inaccurately (on a perturbed q or M + εI), failed evaluations, the last epoch's
// training loss; then the time ratio cold / warm and the largest |θ_warm − θ_cold| relative
// to |θ₀|, which is 0 unless a degenerate LCP solution made the two runs take different
// one-sided gradients.
#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/learn/scene_params.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

using namespace lcprelax;
using namespace lcprelax::learn;

namespace {

struct RunOutcome {
  double seconds = 0.0, last_loss = 0.0;
  long pivots = 0, cold_contacts = 0, contacts = 0, inaccurate = 0;
  int failed = 0;
  Vector theta;
};

RunOutcome train_once(const SceneDataset& data, const SceneParameterMap& map, const ParameterSet& theta0, bool warm,
                      int epochs, double lr) {
  SceneLossSettings ls;
  ls.method = LossMethod::hard;
  ls.hard_warm_basis = warm;
  SceneObjective objective(data, map, ls);
  ParameterSet theta = theta0;
  std::vector<Index> training(data.transitions.size());
  std::iota(training.begin(), training.end(), Index{0});
  TrainSettings ts;
  ts.epochs = epochs;
  ts.threads = 1;
  ts.shuffle = false;
  ts.patience = 0;
  ts.optimizer.kind = OptimizerKind::adam;
  ts.optimizer.learning_rate = lr;
  const TrainResult tr = train(objective, theta, training, {}, ts);
  RunOutcome out;
  out.seconds = tr.seconds;
  out.failed = tr.failed;
  out.last_loss = tr.history.empty() ? 0.0 : tr.history.back().loss;
  const SceneObjectiveStats st = objective.stats();
  out.pivots = st.solver_work;
  out.cold_contacts = st.cold_contacts;
  out.contacts = st.contacts;
  out.inaccurate = st.inaccurate_islands;
  out.theta = theta.values();
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hard-loss training with and without stored Lemke bases"};
  int bodies = 30, transitions = 100, epochs = 20;
  unsigned long long seed = 1;
  double lr = 0.01;
  app.add_option("--bodies", bodies, "bodies of the learning pile")->check(CLI::PositiveNumber);
  app.add_option("--transitions", transitions, "transitions (simulator steps) in the training set")->check(CLI::PositiveNumber);
  app.add_option("--epochs", epochs, "training epochs")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "seed of the pile");
  app.add_option("--lr", lr, "Adam learning rate")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);

  LearningPileOptions po;
  po.bodies = bodies;
  po.seed = seed;
  po.model = ContactModel::lcp;
  SceneDatasetSettings ds;
  ds.steps = transitions;
  const SceneDataset data = generate_scene_dataset(make_learning_pile(po), ds);
  const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
  const ParameterSet theta0 = perturb_scene_parameters(map.parameters(data.scene.world), map, 0.05, 7);
  std::printf("# run_hard_warm_basis --bodies %d --transitions %d --epochs %d --seed %llu --lr %g: %zu transitions kept\n",
              bodies, transitions, epochs, seed, lr, data.transitions.size());
  std::printf("%-6s %10s %12s %14s %10s %11s %7s %14s\n", "start", "seconds", "pivots", "cold_contacts", "contacts",
              "inaccurate", "failed", "last_loss");
  const RunOutcome warm = train_once(data, map, theta0, true, epochs, lr);
  const RunOutcome cold = train_once(data, map, theta0, false, epochs, lr);
  for (const auto& [name, r] : {std::pair<const char*, const RunOutcome&>{"stored", warm}, {"cold", cold}})
    std::printf("%-6s %10.3f %12ld %14ld %10ld %11ld %7d %14.6e\n", name, r.seconds, r.pivots, r.cold_contacts,
                r.contacts, r.inaccurate, r.failed, r.last_loss);
  const double scale = std::max(1e-300, theta0.values().cwiseAbs().maxCoeff());
  std::printf("time cold / stored: %.2f; pivots cold / stored: %.2f; max |theta_stored - theta_cold| / |theta0| = %.3g\n",
              cold.seconds / std::max(1e-12, warm.seconds),
              static_cast<double>(cold.pivots) / std::max<double>(1.0, static_cast<double>(warm.pivots)),
              (warm.theta - cold.theta).cwiseAbs().maxCoeff() / scale);
  return 0;
}
