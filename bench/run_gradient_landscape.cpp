// Issue 20, experiment 3: the gradient landscape. On which fraction of a parameter box does
// each loss (hard, relaxed, convex; the convex one with each normal softening of
// models/normal_softening.hpp) have a nonzero gradient that points toward the truth?
//
//   run_gradient_landscape [--csv bench/results/gradient_landscape.csv]
//       [--plots bench/results/plots] [--block-points 61] [--grid 9] [--bodies 8]
//       [--steps 40] [--box 10] [--threads 2] [--zero-tol 1e-6] > bench/results/gradient_landscape.txt
//
// block: the seeds' 1-D block (learn/block_losses.hpp; Parmar, Halm & Posa, IROS 2021):
//   200 samples of generate_block_dataset (μ* = 0.1, m = mg = 1), μ log-spaced over
//   [0.05 μ*, 50 μ*] as `lcprelax learn block --landscape` (learn/block_landscape.hpp).
//   Its convex model has no normal direction, so no softening.
// scene: a learning pile (learn/scene_dataset.hpp make_learning_pile: `bodies` squares of
//   class 0, μ* = 0.5) simulated for `steps` steps with random pushes, by the model of the
//   loss (lcp for hard and relaxed, convex with the softening for convex), so that the truth
//   is each loss's own model. θ = (μ, class0.mass) on a grid × grid box log-spaced over
//   [θ*/box, box·θ*] per coordinate (the truth itself excluded); inertia and vertices fixed.
//   settle: the same without pushes (the pile settles from its drop: contacts mostly stick).
//   Relaxed: the proximal centres are reset at every point (SceneObjective::reset_centers),
//   so each point's value does not depend on the order of the scan.
// A point counts as "correct" when −∇ℓ points toward the truth in log coordinates,
// g_ξ·(ξ* − ξ) < 0 with ξ = log θ, "zero" when every |∂ℓ/∂log θ_k| ≤ zero_tol·|ℓ|
// (learn/block_landscape.hpp classify_gradient), "failed" when a sample failed or the mean
// gradient is not finite.
//
// The scene plot shows the μ-alone fraction (the θ one is dominated by the mass gradient).
// CSV: problem,loss,softening,mu,mass,loss_value,grad_mu,grad_mass,sign,sign_mu (mass empty
// for the block; sign_mu classifies ∂ℓ/∂μ alone against μ*, the friction gradient that the
// hard loss loses where contacts stick; "-" at μ = μ*, where it is not counted).
// Plots (Cairo): plots/gradient_landscape_scene.png (fraction of the mass axis with a
// correct ∂ℓ/∂μ, against μ), the same for settle, plots/gradient_landscape_block.png and its
// _gradient twin.
#include <lcprelax/learn/block_landscape.hpp>
#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/scenes/line_plot.hpp>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace {

using namespace lcprelax;
using namespace lcprelax::learn;

struct Loss {
  LossMethod method;
  NormalSoftening softening;  // scene convex only
  bool softened = true;       // false for the block (its convex model has no normal direction)
  std::string name() const { return to_string(method); }
  std::string softening_name() const {
    return softened && method == LossMethod::convex ? to_string(softening) : "-";
  }
};

Vector vec2(double a, double b) {
  Vector v(2);
  v << a, b;
  return v;
}

std::vector<double> log_grid(double lo, double hi, int n) {
  std::vector<double> x;
  for (int k = 0; k < n; ++k) x.push_back(lo * std::pow(hi / lo, static_cast<double>(k) / (n - 1)));
  return x;
}

// `c` over θ, `mu` over ∂ℓ/∂μ alone.
void print_counts(const std::string& problem, const Loss& loss, const GradientSignCounts& c,
                  const GradientSignCounts& mu) {
  std::printf("%-6s %-8s %-17s %6d %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f\n", problem.c_str(), loss.name().c_str(),
              loss.softening_name().c_str(), c.points(), c.fraction(GradientSign::correct),
              c.fraction(GradientSign::wrong), c.fraction(GradientSign::zero), c.fraction(GradientSign::failed),
              mu.fraction(GradientSign::correct), mu.fraction(GradientSign::zero));
}

void run_block(std::ofstream& csv, const std::string& plots, int points, int threads, double zero_tol) {
  BlockDataSettings g;
  g.truth = Block1d{1.0, 1.0, 0.1};
  const BlockDataset data = generate_block_dataset(g);
  const std::vector<BlockMethod> methods = {BlockMethod::hard, BlockMethod::relaxed, BlockMethod::convex};
  const BlockLandscape L = block_landscape(data, BlockLossSettings{}, methods, 0.05 * g.truth.mu, 50.0 * g.truth.mu,
                                           points, threads);
  for (std::size_t j = 0; j < methods.size(); ++j) {
    const Loss loss{parse_loss_method(to_string(methods[j])), NormalSoftening::exp_phi, false};
    for (std::size_t k = 0; k < L.mu.size(); ++k) {
      const GradientSign s =
          L.failed[j][k] > 0 ? GradientSign::failed
                             : classify_gradient(Vector::Constant(1, L.mu[k]), Vector::Constant(1, g.truth.mu),
                                                 Vector::Constant(1, L.gradient[j][k]), L.loss[j][k], zero_tol);
      char line[300];
      std::snprintf(line, sizeof line, "block,%s,-,%.9g,,%.9e,%.9e,,%s,%s\n", loss.name().c_str(), L.mu[k],
                    L.loss[j][k], L.gradient[j][k], to_string(s), to_string(s));
      csv << line;
    }
    const GradientSignCounts c = count_gradient_signs(L, j, g.truth.mu, zero_tol);
    print_counts("block", loss, c, c);
  }
  if (!plots.empty() && line_plot_available())
    write_landscape_plot(plots + "/gradient_landscape_block.png", L, g.truth.mu);
}

// One loss over the μ × mass box; returns the plot's series: against μ, the fraction of the
// mass axis where ∂ℓ/∂μ alone is nonzero and of the right sign.
struct SceneCase {
  std::string name;       // "scene" (pushed) or "settle" (no pushes)
  double push_fraction;   // SceneDatasetSettings::push_fraction
};

LineSeries run_scene_loss(std::ofstream& csv, const SceneCase& sc, const Loss& loss, int bodies, int steps, int n,
                          double box, int threads, double zero_tol) {
  LearningPileOptions pile;
  pile.bodies = bodies;
  pile.classes = 1;
  pile.model = loss.method == LossMethod::convex ? ContactModel::convex : ContactModel::lcp;
  Scene scene = make_learning_pile(pile);
  scene.settings.convex_softening.method = loss.softening;
  SceneDatasetSettings ds;
  ds.steps = steps;
  ds.push_fraction = sc.push_fraction;
  const SceneDataset data = generate_scene_dataset(scene, ds);
  SceneParameterSettings ps;
  ps.learn = parse_scene_learn_flags("mu,mass");
  const SceneParameterMap map(data.scene.world, ps);
  const ParameterSet truth = map.parameters(data.scene.world);
  SceneLossSettings ls;
  ls.method = loss.method;
  ls.convex.softening.method = loss.softening;
  SceneObjective objective(data, map, ls);
  std::vector<Index> all(static_cast<std::size_t>(objective.num_samples()));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
  const Index i_mu = truth.index("mu"), i_mass = truth.index("class0.mass");
  const double mu0 = truth[i_mu].value, mass0 = truth[i_mass].value;
  const Vector theta_truth = vec2(mu0, mass0);
  GradientSignCounts counts, counts_mu;
  LineSeries series{loss.method == LossMethod::convex ? "convex " + loss.softening_name() : loss.name(), {}, {}};
  series.markers = true;
  for (double mu : log_grid(mu0 / box, box * mu0, n)) {
    int correct = 0, used = 0;
    for (double mass : log_grid(mass0 / box, box * mass0, n)) {
      if (std::abs(mu / mu0 - 1) < 1e-9 && std::abs(mass / mass0 - 1) < 1e-9) continue;  // the truth
      ParameterSet theta = truth;
      theta.set_value("mu", mu);
      theta.set_value("class0.mass", mass);
      objective.reset_centers();
      const BatchResult r = evaluate_mean(objective, theta, all, threads);
      const Vector g = vec2(r.gradient(i_mu), r.gradient(i_mass));
      const GradientSign s = r.failed > 0 ? GradientSign::failed
                                          : classify_gradient(vec2(mu, mass), theta_truth, g, r.loss, zero_tol);
      // μ alone: the friction gradient, which the hard loss loses where contacts stick. Not
      // classified at μ = μ* (no direction in μ is correct there).
      const bool at_mu0 = std::abs(mu / mu0 - 1) < 1e-9;
      const GradientSign s_mu =
          s == GradientSign::failed
              ? GradientSign::failed
              : classify_gradient(Vector::Constant(1, mu), Vector::Constant(1, mu0), Vector::Constant(1, g(0)), r.loss,
                                  zero_tol);
      counts.add(s);
      if (!at_mu0) counts_mu.add(s_mu), correct += s_mu == GradientSign::correct, ++used;
      char line[400];
      std::snprintf(line, sizeof line, "%s,%s,%s,%.9g,%.9g,%.9e,%.9e,%.9e,%s,%s\n", sc.name.c_str(),
                    loss.name().c_str(), loss.softening_name().c_str(), mu, mass, r.loss, g(0), g(1), to_string(s),
                    at_mu0 ? "-" : to_string(s_mu));
      csv << line;
    }
    series.x.push_back(mu);
    series.y.push_back(used > 0 ? static_cast<double>(correct) / used : std::nan(""));
  }
  print_counts(sc.name, loss, counts, counts_mu);
  std::fflush(stdout);
  return series;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Fraction of a parameter box with a nonzero, correctly signed loss gradient (issue 20, experiment 3)");
  std::string csv_path = "bench/results/gradient_landscape.csv", plots = "bench/results/plots";
  int block_points = 61, grid = 9, bodies = 8, steps = 40, threads = 2;
  double zero_tol = 1e-6, box = 10.0;
  app.add_option("--csv", csv_path, "CSV output (one row per point)");
  app.add_option("--plots", plots, "directory of the PNG plots (empty: none)");
  app.add_option("--block-points", block_points, "μ values of the block scan")->check(CLI::Range(2, 100000));
  app.add_option("--grid", grid, "points per axis of the scene's μ × mass box")->check(CLI::Range(2, 1000));
  app.add_option("--bodies", bodies, "squares in the scene's learning pile")->check(CLI::Range(1, 10000));
  app.add_option("--steps", steps, "simulated steps of the scene's data")->check(CLI::Range(1, 100000));
  app.add_option("--box", box, "the scene's box is [theta*/box, box*theta*] per coordinate")
      ->check(CLI::Range(1.0001, 1e6));
  app.add_option("--threads", threads, "OpenMP threads over samples");
  app.add_option("--zero-tol", zero_tol, "a gradient is zero when every |dl/dlog theta| <= zero_tol*|l|");
  CLI11_PARSE(app, argc, argv);

  std::ofstream csv(csv_path);
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", csv_path.c_str());
    return 1;
  }
  csv << "problem,loss,softening,mu,mass,loss_value,grad_mu,grad_mass,sign,sign_mu\n";
  std::printf("Fraction of the box whose gradient is nonzero and points toward the truth (zero: |dl/dlog theta| <= "
              "%g |l|)\n",
              zero_tol);
  std::printf("block: mu in [0.005, 5] (mu* = 0.1), %d points; scene: %d squares, %d steps, mu x mass in "
              "[theta*/%g, %g theta*]^2, %d x %d grid\n\n",
              block_points, bodies, steps, box, box, grid, grid);
  std::printf("over theta: correct, wrong, zero, failed; over dl/dmu alone: mu corr., mu zero\n");
  std::printf("%-6s %-8s %-17s %6s %9s %9s %9s %9s %9s %9s\n", "case", "loss", "softening", "points", "correct",
              "wrong", "zero", "failed", "mu corr.", "mu zero");
  run_block(csv, plots, block_points, threads, zero_tol);
  const std::vector<Loss> losses = {{LossMethod::hard, NormalSoftening::exp_phi},
                                    {LossMethod::relaxed, NormalSoftening::exp_phi},
                                    {LossMethod::convex, NormalSoftening::exp_phi},
                                    {LossMethod::convex, NormalSoftening::linear_penalty},
                                    {LossMethod::convex, NormalSoftening::mujoco_impedance}};
  for (const SceneCase& sc : {SceneCase{"scene", SceneDatasetSettings{}.push_fraction}, SceneCase{"settle", 0.0}}) {
    std::vector<LineSeries> series;
    for (const Loss& loss : losses)
      series.push_back(run_scene_loss(csv, sc, loss, bodies, steps, grid, box, threads, zero_tol));
    if (plots.empty() || !line_plot_available()) continue;
    LinePlotOptions o;
    o.title = sc.name + ": fraction of the mass axis where dl/dmu is nonzero and points toward mu*";
    o.x_label = "mu (truth 0.5)";
    o.y_label = "fraction with correct dl/dmu";
    o.log_x = true;
    o.y_min = -0.05, o.y_max = 1.05;
    write_line_plot(plots + "/gradient_landscape_" + sc.name + ".png", series, o);
  }
  return 0;
}
