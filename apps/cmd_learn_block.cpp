// `lcprelax learn block [--method hard|relaxed|convex] [--init-mu X] [--true-mu X]
//  [--epochs E] [--rel-loss-tol R] [--grad-tol G] [--patience P] [--batch B] [--threads T] [--samples S] [--seed K] [--noise σ]
//  [--slip-max X] [--data FILE.csv] [--mg X] [--mass X] [--learn-mass] [--learn-mg]
//  [--optimizer sgd|adam|lbfgs|lm] [--lr α] [--momentum β] [--soft-nonnegativity] [--soft-lambdas]
//  [--l1-softness] [--max-dissipation none|qp|ext] [--a1 … --a5] [--regularization ε]
//  [--log FILE.csv] [--checkpoint FILE] [--resume FILE]
//  [--landscape OUT] [--param physical|pair|elementwise|residual] [--json]` (docs/cli.md): learns the friction coefficient of the seeds'
// 1-D block (Parmar, Halm & Posa, IROS 2021) from transitions (v, u, v_next), generated
// from --true-mu (noise σ relative to the RMS of v_next, learn/block_dataset.hpp) or read
// from --data. --checkpoint/--resume: a run that survives a kill (cmd_learn_checkpoint.hpp).
// JSON: method, true, initial, learned (parameter name → value; true is null for a --data
// file without --true-mu), final_loss (mean loss over all samples at the learned θ),
// epochs (run: --epochs is a cap, the run ends earlier once the convergence test of
// learn::train holds, trainer.hpp), stop_reason, converged, seconds; with --epochs 0 also gradient (mean ∂loss/∂μ at the initial μ) and
// final_loss is the loss there. Also samples, failed.
// --landscape OUT: OUT.csv (μ, loss and gradient of every method over 61 log-spaced μ in
// [0.05, 50]× the true μ, or the initial μ without one) and the plots OUT.png and
// OUT_gradient.png (OUT may end in .png or .svg to choose the format; without Cairo only
// the CSV, with a message).
// --param (learn/block_param.hpp): which parameters are learned; physical (default) is
// μ (with --learn-mass/--learn-mg) on the block's own objectives; pair, elementwise and
// residual learn nonphysical parameters with --method hard or relaxed (convex, --learn-mass,
// --learn-mg and --landscape are refused with exit 2). Their initial values are the
// physical model at --init-mu. JSON also: param, and learned_groups (group → name → value,
// block_param_group); for a nonphysical param, true lists the truth in that param's terms.
// Exit 0 success, 1 when a sample's solve failed, 2 on bad input.
#include "cli_common.hpp"
#include "cmd_learn_checkpoint.hpp"

#include <lcprelax/mpi/mpi_session.hpp>

#include <lcprelax/learn/block_landscape.hpp>
#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/learn/block_param_objective.hpp>
#include <lcprelax/scenes/line_plot.hpp>
#include <lcprelax/core/errors.hpp>


#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <utility>

namespace lcprelax::cli {
namespace {

struct LearnBlockOptions {
  std::string method = "relaxed";
  double init_mu = 1.0;
  double true_mu = std::numeric_limits<double>::quiet_NaN();  // default 0.1 for generated data
  // A cap: `--method relaxed --init-mu 1` with the other defaults converges (the test of
  // learn::train) after 278 epochs at μ = 0.100146 (measured), well within the cap.
  int epochs = 1000;
  LearnStopOptions stop;
  int batch = 0;
  int threads = 1;
  int samples = 200;
  std::uint64_t seed = 1;
  double noise = 0.0;
  double slip_max = 9.0;
  std::string data;
  double mg = 1.0, mass = 1.0;
  bool learn_mass = false, learn_mg = false;
  std::string optimizer = "adam";
  double lr = 0.05, momentum = 0.9;
  bool soft_nonnegativity = false, soft_lambdas = false, l1_softness = false;
  std::string max_dissipation = "none";
  double a[5] = {1.0, 1.0, 20.0, 20.0, 0.1};
  double regularization = 1e-3;
  std::string log, landscape;
  std::string param = "physical";
  bool json = false;
  LearnCheckpointOptions checkpoint;
};

Json parameter_object(const learn::ParameterSet& theta) {
  Json j = Json::object();
  for (Index i = 0; i < theta.size(); ++i)
    if (theta[i].learn) j[theta[i].name] = number_or_null(theta[i].value);
  return j;
}

// The learned parameters by group (block_param_group): group → name → value.
Json parameter_groups(const learn::ParameterSet& theta) {
  Json j = Json::object();
  for (Index i = 0; i < theta.size(); ++i)
    if (theta[i].learn) j[learn::block_param_group(theta[i].name)][theta[i].name] = number_or_null(theta[i].value);
  return j;
}

// Most generated samples (--samples): 10⁸ reached 5.1 GB and then bad_alloc; 10⁷ take
// about 0.5 GB.
constexpr int kMaxBlockSamples = 10'000'000;

// --landscape OUT → the CSV and picture paths it writes (see the header comment).
std::pair<std::string, std::string> landscape_paths(const std::string& landscape) {
  namespace fs = std::filesystem;
  std::string ext = fs::path(landscape).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool has_ext = ext == ".png" || ext == ".svg";
  return {has_ext ? fs::path(landscape).replace_extension(".csv").string() : landscape + ".csv",
          has_ext ? landscape : landscape + ".png"};
}

void run_landscape(const LearnBlockOptions& o, const learn::BlockDataset& data, const learn::BlockLossSettings& s,
                   double true_mu) {
  const auto [csv, picture] = landscape_paths(o.landscape);
  const double ref = std::isfinite(true_mu) ? true_mu : o.init_mu;
  const learn::BlockLandscape L = learn::block_landscape(
      data, s, {learn::BlockMethod::hard, learn::BlockMethod::relaxed, learn::BlockMethod::convex}, 0.05 * ref,
      50.0 * ref, 61, o.threads);
  learn::write_landscape_csv(csv, L);
  if (!line_plot_available()) {
    std::cerr << "lcprelax learn block: built without Cairo: wrote " << csv << " but no picture\n";
    return;
  }
  const std::vector<std::string> written = learn::write_landscape_plot(picture, L, true_mu);
  if (!o.json) {
    std::cout << "landscape: " << csv;
    for (const std::string& w : written) std::cout << ", " << w;
    std::cout << '\n';
  }
}

int run_learn_block(const LearnBlockOptions& o, const CLI::App& app) {
  const learn::BlockMethod method = learn::parse_block_method(o.method);
  learn::BlockParam param = learn::BlockParam::physical;
  try {
    param = learn::parse_block_param(o.param);
  } catch (const InputError& e) {
    throw InputError(std::string("--param: ") + e.what());
  }
  const bool physical = param == learn::BlockParam::physical;
  require_option(physical || method != learn::BlockMethod::convex, "--param",
                 o.param + " needs --method hard or relaxed (the convex loss has no LCP data to parameterize)");
  require_option(physical || (!o.learn_mass && !o.learn_mg), "--param",
                 o.param + " learns its own parameters; --learn-mass and --learn-mg go with --param physical");
  require_option(physical || o.landscape.empty(), "--param", o.param + ": --landscape goes with --param physical");
  require_option(std::isfinite(o.init_mu) && o.init_mu > 0.0, "--init-mu", "must be positive and finite");
  require_option(std::isnan(o.true_mu) || (std::isfinite(o.true_mu) && o.true_mu > 0.0), "--true-mu",
                 "must be positive and finite");
  require_option(o.epochs >= 0, "--epochs", "must be ≥ 0");
  require_option(o.batch >= 0, "--batch", "must be ≥ 0 (0: all samples)");
  require_threads(o.threads);
  require_option(o.samples >= 1 && o.samples <= kMaxBlockSamples, "--samples",
                 "must be in [1, " + std::to_string(kMaxBlockSamples) + "] (the limit: ~50 bytes per sample and epoch)");
  require_option(std::isfinite(o.noise) && o.noise >= 0.0, "--noise", "must be finite and ≥ 0");
  require_option(std::isfinite(o.mg) && o.mg > 0.0, "--mg", "must be positive and finite");
  require_option(std::isfinite(o.mass) && o.mass > 0.0, "--mass", "must be positive and finite");
  if (!o.landscape.empty()) {  // checked before the training, not after it
    const auto [csv, picture] = landscape_paths(o.landscape);
    require_writable_file("--landscape", csv);
    if (line_plot_available()) require_writable_file("--landscape", picture);
  }

  learn::TrainSettings t =
      learn_train_settings(o.epochs, o.batch, o.threads, o.seed, o.optimizer, o.lr, o.momentum, o.json, o.log, o.stop);
  apply_learn_checkpoint_options(app, o.checkpoint, t);  // before any work

  learn::BlockLossSettings s;
  s.relaxed.soft_nonnegativity = o.soft_nonnegativity;
  s.relaxed.soft_lambdas = o.soft_lambdas;
  s.relaxed.l1_softness = o.l1_softness;
  s.relaxed.max_dissipation = learn::parse_max_dissipation(o.max_dissipation);
  s.relaxed.a1 = o.a[0];
  s.relaxed.a2 = o.a[1];
  s.relaxed.a3 = o.a[2];
  s.relaxed.a4 = o.a[3];
  s.relaxed.a5 = o.a[4];
  s.relaxed.regularization = o.regularization;
  const std::string bad = s.relaxed.validation_error();
  if (!bad.empty()) throw InputError("--a1 … --a5, --regularization: " + bad);

  double true_mu = o.true_mu;
  learn::BlockDataset data;
  if (!o.data.empty()) {
    data = learn::read_block_csv(o.data, o.mass, o.mg);
  } else {
    if (std::isnan(true_mu)) true_mu = 0.1;
    learn::BlockDataSettings g;
    g.truth = Block1d{o.mass, o.mg, true_mu};
    g.samples = o.samples;
    g.seed = o.seed;
    g.noise = o.noise;
    g.slip_max = o.slip_max;
    data = learn::generate_block_dataset(g);
  }
  if (!physical) s.relaxed.nonconvex = learn::NonconvexPolicy::shift;  // an elementwise M may be indefinite
  std::unique_ptr<learn::Objective> objective =
      physical ? std::unique_ptr<learn::Objective>(learn::make_block_objective(method, data, s))
               : learn::make_block_param_objective(param, method, data, s);
  learn::ParameterSet theta = physical ? learn::block_parameters(o.init_mu, o.mass, o.mg, o.learn_mass, o.learn_mg)
                                       : learn::block_param_parameters(param, o.init_mu, data.mass, data.mg);
  const learn::ParameterSet initial = theta;

  std::vector<Index> all(static_cast<std::size_t>(data.size()));
  for (Index i = 0; i < data.size(); ++i) all[static_cast<std::size_t>(i)] = i;
  Stopwatch clock;
  int failed = 0;
  learn::TrainResult result;
  if (o.epochs > 0) result = learn::train(*objective, theta, all, {}, t);
  failed += result.failed;
  const learn::BatchResult final_eval = learn::evaluate_mean(*objective, theta, all, o.threads, t.distributed);
  failed += final_eval.failed;
  const double seconds = clock.seconds();
  if (!o.landscape.empty() && mpi::mpi_rank() == 0) run_landscape(o, data, s, true_mu);

  Json j;
  j["method"] = learn::to_string(method);
  j["param"] = learn::to_string(param);
  Json truth = Json::object();
  if (physical) {
    truth["mu"] = number_or_null(true_mu);
    if (o.learn_mass) truth["mass"] = o.data.empty() ? number_or_null(o.mass) : Json(nullptr);
    if (o.learn_mg) truth["mg"] = o.data.empty() ? number_or_null(o.mg) : Json(nullptr);
  } else if (std::isfinite(true_mu)) {
    truth = parameter_object(learn::block_param_parameters(param, true_mu, data.mass, data.mg));
  } else {
    truth = parameter_object(initial);
    for (auto& [name, value] : truth.items()) value = nullptr;
  }
  j["true"] = truth;
  j["initial"] = parameter_object(initial);
  j["learned"] = parameter_object(theta);
  j["learned_groups"] = parameter_groups(theta);
  j["final_loss"] = number_or_null(final_eval.evaluated > 0 ? final_eval.loss : std::nan(""));
  add_train_outcome(j, result, o.epochs);
  j["seconds"] = seconds;
  if (o.epochs == 0 && physical)
    j["gradient"] = number_or_null(final_eval.evaluated > 0 ? final_eval.gradient(theta.index("mu")) : std::nan(""));
  if (o.epochs == 0 && !physical) {
    Json g = Json::object();
    for (Index i = 0; i < theta.size(); ++i)
      g[theta[i].name] = number_or_null(final_eval.evaluated > 0 ? final_eval.gradient(i) : std::nan(""));
    j["gradient"] = g;
  }
  j["samples"] = data.size();
  j["failed"] = failed;
  if (o.json) {
    print_json(j);
  } else {
    std::cout << "method " << j["method"].get<std::string>();
    if (physical) {
      std::cout << ": mu " << o.init_mu << " -> " << theta.value("mu");
      if (std::isfinite(true_mu)) std::cout << " (true " << true_mu << ")";
    } else {
      std::cout << ", param " << o.param << ": learned " << j["learned_groups"].dump();
    }
    std::cout << ", final loss " << j["final_loss"].dump() << ", " << j["epochs"].get<int>() << " epochs ("
              << j["stop_reason"].get<std::string>() << "), " << seconds << " s";
    if (o.epochs == 0) std::cout << ", gradient " << j["gradient"].dump();
    std::cout << '\n';
    if (failed > 0)
      std::cout << failed << " failed sample solves ("
                << (final_eval.first_failure.empty() ? result.first_failure : final_eval.first_failure) << ")\n";
  }
  return failed > 0 ? kExitSolveFailed : kExitSuccess;
}

Command add_learn_block_command(CLI::App& learn) {
  auto o = std::make_shared<LearnBlockOptions>();
  CLI::App* app = learn.add_subcommand("block", "learn the friction of the seeds' 1-D block (hard|relaxed|convex)");
  app->add_option("--method", o->method, "hard, relaxed or convex")->capture_default_str();
  app->add_option("--init-mu", o->init_mu, "initial friction coefficient")->capture_default_str();
  app->add_option("--true-mu", o->true_mu, "true friction coefficient of generated data (default 0.1)");
  app->add_option("--epochs", o->epochs, "most training epochs (0: evaluate loss and gradient only)")->capture_default_str();
  add_learn_stop_options(*app, o->stop);
  app->add_option("--batch", o->batch, "mini-batch size (0: all samples)")->capture_default_str();
  app->add_option("--threads", o->threads, "OpenMP threads (0: default)")->capture_default_str();
  app->add_option("--samples", o->samples, "generated transitions")->capture_default_str();
  app->add_option("--seed", o->seed, "seed of the data and the shuffle")->capture_default_str();
  app->add_option("--noise", o->noise, "Gaussian noise on v_next, relative to its RMS")->capture_default_str();
  app->add_option("--slip-max", o->slip_max, "largest |v*| of slipping samples, in units of μ·mg/m")
      ->capture_default_str();
  app->add_option("--data", o->data, "CSV of transitions (columns v, v_next, u)");
  app->add_option("--mg", o->mg, "weight impulse m·g per step, N·s")->capture_default_str();
  app->add_option("--mass", o->mass, "mass, kg")->capture_default_str();
  app->add_flag("--learn-mass", o->learn_mass, "learn the mass too");
  app->add_flag("--learn-mg", o->learn_mg, "learn m·g too");
  app->add_option("--optimizer", o->optimizer, "sgd, adam, lbfgs (L-BFGS with a line search; full batch only) or lm (Levenberg-Marquardt on the convex loss's residuals; learn scene, full batch only)")->capture_default_str();
  app->add_option("--lr", o->lr, "learning rate (on log μ)")->capture_default_str();
  app->add_option("--momentum", o->momentum, "SGD momentum")->capture_default_str();
  app->add_flag("--soft-nonnegativity", o->soft_nonnegativity, "relaxed: Mλ + q + s ≥ 0");
  app->add_flag("--soft-lambdas", o->soft_lambdas, "relaxed: λ + t ≥ 0");
  app->add_flag("--l1-softness", o->l1_softness, "relaxed: linear slack penalties");
  app->add_option("--max-dissipation", o->max_dissipation, "relaxed: none, qp or ext")->capture_default_str();
  for (int i = 0; i < 5; ++i)
    app->add_option("--a" + std::to_string(i + 1), o->a[i], "relaxed weight a" + std::to_string(i + 1))
        ->capture_default_str();
  app->add_option("--regularization", o->regularization, "relaxed: ε of (ε/2)‖x‖² (the seeds' 1e-3·I)")
      ->capture_default_str();
  app->add_option("--log", o->log, "CSV log of every epoch");
  app->add_option("--param", o->param, "parameterization: physical, pair, elementwise or residual (learn/block_param.hpp)")
      ->capture_default_str();
  app->add_option("--landscape", o->landscape, "write OUT.csv and plots of every method's loss over μ");
  add_learn_checkpoint_options(*app, o->checkpoint);
  add_json_flag(*app, o->json);
  return Command{app, [o, app]() { return run_learn_block(*o, *app); }};
}

const bool registered = register_learn_application(&add_learn_block_command);

}  // namespace
}  // namespace lcprelax::cli
