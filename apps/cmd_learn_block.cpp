// `lcprelax learn block [--method hard|relaxed|convex] [--init-mu X] [--true-mu X]
//  [--epochs E] [--rel-loss-tol R] [--grad-tol G] [--patience P] [--batch B] [--threads T] [--samples S] [--seed K] [--noise σ]
//  [--slip-max X] [--data FILE.csv] [--mg X] [--mass X] [--learn-mass] [--learn-mg]
//  [--optimizer sgd|adam|lbfgs|lm] [--lr α] [--momentum β] [--soft-nonnegativity] [--soft-lambdas]
//  [--l1-softness] [--max-dissipation none|qp|ext] [--a1 … --a5] [--regularization ε]
//  [--log FILE.csv] [--checkpoint FILE] [--resume FILE]
//  [--landscape OUT] [--param physical|pair|elementwise|residual] [--json]` (docs/cli.md): learns the
// friction coefficient of the 1-D block of Parmar, Halm & Posa (IROS 2021; models/block1d.hpp)
// from transitions (v, u, v_next), generated
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
// Human output: a brief report (learn_report.hpp) of the same fields. --threads defaults to
// 0 (all cores), as in every command: the sums are reduced in a fixed order (batch.hpp), so
// the result is bitwise the same for every thread count (tests/cli_threads_default_test.cpp).
// Exit 0 success, 1 when a sample's solve failed, 2 on bad input.
#include "cli_common.hpp"
#include "cmd_learn_checkpoint.hpp"
#include "learn_report.hpp"

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
  int threads = 0;
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

// Writes the landscape; returns the files written (the CSV, and the plots with Cairo).
std::string run_landscape(const LearnBlockOptions& o, const learn::BlockDataset& data, const learn::BlockLossSettings& s,
                          double true_mu) {
  const auto [csv, picture] = landscape_paths(o.landscape);
  const double ref = std::isfinite(true_mu) ? true_mu : o.init_mu;
  const learn::BlockLandscape L = learn::block_landscape(
      data, s, {learn::BlockMethod::hard, learn::BlockMethod::relaxed, learn::BlockMethod::convex}, 0.05 * ref,
      50.0 * ref, 61, o.threads);
  learn::write_landscape_csv(csv, L);
  if (!line_plot_available()) {
    std::cerr << "lcprelax learn block: built without Cairo: wrote " << csv << " but no picture\n";
    return csv;
  }
  std::string files = csv;
  for (const std::string& w : learn::write_landscape_plot(picture, L, true_mu)) files += ", " + w;
  return files;
}

// The unit of a parameter of this command (a nonphysical --param's extras: docs/cli.md).
std::string block_parameter_unit(const std::string& name) {
  return name == "mass" ? "kg" : name == "mg" ? "N·s" : "";
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
  std::string landscape_files;
  if (!o.landscape.empty() && mpi::mpi_rank() == 0) landscape_files = run_landscape(o, data, s, true_mu);

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
    BriefReport r;
    add_training_status(r, j, failed > 0);
    if (failed > 0)
      r.add("first failure", final_eval.first_failure.empty() ? result.first_failure : final_eval.first_failure);
    r.add("method", o.method + " loss, " + o.param + " parameters");
    r.add("samples", std::to_string(data.size()) + (o.data.empty() ? " generated" : " from " + o.data) +
                         (failed > 0 ? ", " + std::to_string(failed) + " failed solves" : ""));
    add_parameter_lines(r, j, block_parameter_unit);
    r.add("final loss", final_eval.evaluated > 0 ? final_eval.loss : std::nan(""),
          method == learn::BlockMethod::relaxed ? "(mean relaxed-problem value per sample)"
                                                : "(m/s)² (mean squared velocity error per sample)");
    if (o.epochs == 0 && physical) r.add("gradient", j["gradient"].is_number() ? j["gradient"].get<double>() : std::nan(""), "d(loss)/d(mu)");
    if (o.epochs == 0 && !physical)
      for (const auto& [name, g] : j["gradient"].items())
        r.add("gradient " + name, g.is_number() ? g.get<double>() : std::nan(""));
    add_training_effort(r, j, o.epochs);
    if (!landscape_files.empty()) r.add("landscape", landscape_files);
    r.print();
  }
  return failed > 0 ? kExitSolveFailed : kExitSuccess;
}

Command add_learn_block_command(CLI::App& learn) {
  auto o = std::make_shared<LearnBlockOptions>();
  CLI::App* app = learn.add_subcommand(
      "block", "learn the friction coefficient of a block sliding on the ground (1-D) from its velocity transitions");
  app->add_option("--method", o->method,
                  "loss: hard (error of the exact model's prediction), relaxed (the relaxed complementarity "
                  "problem of Parmar, Halm & Posa 2021, which keeps a gradient where hard has none) or convex "
                  "(error of the convex model's prediction)")
      ->capture_default_str();
  app->add_option("--init-mu", o->init_mu, "initial friction coefficient (the start of training)")->capture_default_str();
  app->add_option("--true-mu", o->true_mu,
                  "true friction coefficient of the generated data (default 0.1); with --data only reported");
  app->add_option("--epochs", o->epochs,
                  "most training epochs (passes over the data); 0: only evaluate the loss and its gradient")
      ->capture_default_str();
  add_learn_stop_options(*app, o->stop);
  app->add_option("--batch", o->batch, "samples per optimizer step (0: all samples)")->capture_default_str();
  add_threads_option(*app, o->threads, "samples");
  app->add_option("--samples", o->samples, "number of generated transitions (half sticking, half sliding)")
      ->capture_default_str();
  app->add_option("--seed", o->seed, "random seed of the generated data and of the sample order")->capture_default_str();
  app->add_option("--noise", o->noise,
                  "Gaussian noise added to v_next: standard deviation relative to the RMS of v_next (0.01 = 1%)")
      ->capture_default_str();
  app->add_option("--slip-max", o->slip_max,
                  "largest |v + u/m| of the generated sliding samples, in units of mu*mg/m (the most friction can "
                  "change the velocity in one step)")
      ->capture_default_str();
  app->add_option("--data", o->data,
                  "read the transitions from this CSV file (columns v, v_next, u; docs/formats.md) instead of "
                  "generating them");
  app->add_option("--mg", o->mg, "normal impulse of one step, m*g*dt, in N*s")->capture_default_str();
  app->add_option("--mass", o->mass, "mass of the block, kg")->capture_default_str();
  app->add_flag("--learn-mass", o->learn_mass, "learn the mass too");
  app->add_flag("--learn-mg", o->learn_mg, "learn the normal impulse m*g*dt too");
  app->add_option("--optimizer", o->optimizer,
                  "sgd (with --momentum), adam or lbfgs (quasi-Newton with a line search; needs --batch 0)")
      ->capture_default_str();
  app->add_option("--lr", o->lr, "learning rate (the optimizer steps on log mu)")->capture_default_str();
  app->add_option("--momentum", o->momentum, "sgd: momentum")->capture_default_str();
  app->add_flag("--soft-nonnegativity", o->soft_nonnegativity,
                "relaxed: let M*lambda + q go negative at a cost (slack s weighted by --a3)");
  app->add_flag("--soft-lambdas", o->soft_lambdas, "relaxed: let the impulses lambda go negative at a cost (slack t weighted by --a4)");
  app->add_flag("--l1-softness", o->l1_softness,
                "relaxed: penalize those slacks linearly (a3*sum(s), a4*sum(t)) instead of quadratically");
  app->add_option("--max-dissipation", o->max_dissipation,
                  "relaxed: add the maximum-dissipation term weighted by --a5: none, qp (inside the relaxed "
                  "problem) or ext (after it, at its solution)")
      ->capture_default_str();
  static const char* const kWeights[5] = {
      "relaxed: weight a1 of the prediction error |v_predicted - v_next|^2",
      "relaxed: weight a2 of the complementarity violation lambda'(M*lambda + q), which is 0 for an exact "
      "contact solution",
      "relaxed: weight a3 of the slack s of --soft-nonnegativity ((a3/2)|s|^2)",
      "relaxed: weight a4 of the slack t of --soft-lambdas ((a4/2)|t|^2)",
      "relaxed: weight a5 of the maximum-dissipation term |friction impulse - mu*mg|^2 of --max-dissipation"};
  for (int i = 0; i < 5; ++i)
    app->add_option("--a" + std::to_string(i + 1), o->a[i], kWeights[i])->capture_default_str();
  app->add_option("--regularization", o->regularization,
                  "relaxed: weight e of the term (e/2)|x|^2 that keeps the relaxed problem strictly convex")
      ->capture_default_str();
  app->add_option("--log", o->log, "write one CSV line per epoch (loss, gradient norm, parameters) to this file");
  app->add_option("--param", o->param,
                  "what is learned: physical (mu; the default), pair (a friction coefficient per direction, a "
                  "compliance, a velocity offset), elementwise (every entry of the contact problem) or residual "
                  "(mu and a linear correction of the velocity); the last three need --method hard or relaxed")
      ->capture_default_str();
  app->add_option("--landscape", o->landscape,
                  "write OUT.csv and plots of every method's loss and gradient over mu, from 0.05 to 50 times the "
                  "true mu (OUT may end in .png or .svg)");
  add_learn_checkpoint_options(*app, o->checkpoint);
  add_json_flag(*app, o->json);
  app->footer(exit_codes_help("trained (or evaluated, with --epochs 0)",
                              "a sample's contact solve failed (status failed, see \"first failure\")"));
  return Command{app, [o, app]() { return run_learn_block(*o, *app); }};
}

const bool registered = register_learn_application(&add_learn_block_command);

}  // namespace
}  // namespace lcprelax::cli
