// Example: learn the friction coefficient μ of the 1-D block from observed transitions.
//
// The block (models/block1d.hpp; Parmar, Halm & Posa, IROS 2021) slides on the ground and
// is pushed horizontally; one time step maps (v, u) to v⁺ = v + (u + λ)/m with the
// Coulomb friction impulse |λ| ≤ μ·mg. Units: v, v⁺ in m/s (positive to the right), the
// push u and λ in N·s, m in kg, mg the weight impulse of one step (m·g·Δt, N·s).
//
// 1. Generate 200 transitions (v, u, v⁺) from a true block with μ = 0.3 (half of them
//    sticking, half slipping; 1% Gaussian noise on v⁺): learn/block_dataset.hpp.
// 2. Start from μ = 3, ten times too high. There every sample sticks in the model, and the
//    "hard" loss (v⁺(μ) − v̄)², differentiated through Lemke, has exactly zero gradient
//    in μ (the paper's point), so it cannot learn. The "relaxed" loss
//    (learn/relaxed_lcp.hpp) penalizes violated complementarity instead and still points
//    towards the data.
// 3. Train the relaxed loss with Adam on log μ over the full batch (learn/trainer.hpp)
//    until its convergence test holds, and compare with the truth.
// Exit status 1 unless the learned μ is within 2% of the true one (measured: 0.35% off,
// the bias of the noise and of the relaxed loss's small regularization), or a solve fails.
#include <lcprelax/learn/block_dataset.hpp>
#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace lcprelax;

int main() {
  const double true_mu = 0.3, initial_mu = 3.0, tolerance = 0.02;  // tolerance: relative

  learn::BlockDataSettings gen;
  gen.truth = Block1d{/*mass (kg)*/ 1.0, /*mg (N·s)*/ 1.0, true_mu};
  gen.samples = 200;
  gen.seed = 7;
  gen.noise = 0.01;  // σ relative to the RMS of v⁺
  const learn::BlockDataset data = learn::generate_block_dataset(gen);
  std::printf("%d transitions, %d of them stick under the true block\n", data.size(),
              learn::count_sticking(data, gen.truth));

  // θ = {mu} (log-transformed, so μ stays positive); mass and mg are known.
  learn::ParameterSet theta = learn::block_parameters(initial_mu, data.mass, data.mg);
  std::vector<Index> all(static_cast<std::size_t>(data.size()));
  for (Index i = 0; i < data.size(); ++i) all[static_cast<std::size_t>(i)] = i;
  const int threads = 1;  // evaluations are bitwise identical for any thread count

  // Step 2: mean loss and ∂loss/∂μ of both losses at the wrong initial μ.
  auto hard = learn::make_block_objective(learn::BlockMethod::hard, data);
  auto relaxed = learn::make_block_objective(learn::BlockMethod::relaxed, data);
  const Index i_mu = theta.index("mu");
  int failed = 0;  // sample solves that failed (none expected)
  for (auto* objective : {hard.get(), relaxed.get()}) {
    const learn::BatchResult r = learn::evaluate_mean(*objective, theta, all, threads);
    failed += r.failed;
    std::printf("%-7s loss at mu = %.1f: %.4f, dloss/dmu = %.3g\n", learn::to_string(objective->method()),
                initial_mu, r.loss, r.gradient(i_mu));
  }

  // Step 3: train on the relaxed loss.
  learn::TrainSettings train;
  train.epochs = 2000;  // a cap: the run stops once the convergence test holds
  train.batch = 0;      // full batch
  train.threads = threads;
  train.optimizer.kind = learn::OptimizerKind::adam;
  train.optimizer.learning_rate = 0.05;  // on ξ = log μ
  const learn::TrainResult result = learn::train(*relaxed, theta, all, {}, train);

  const double mu = theta.value("mu");
  const double error = std::abs(mu - true_mu) / true_mu;
  std::printf("learned mu %.5f (true %.2f, relative error %.2e) after %zu epochs, %.2f s: %s\n", mu, true_mu, error,
              result.history.size(), result.seconds, result.stop_reason.c_str());
  const bool ok = failed + result.failed == 0 && error <= tolerance;
  std::printf("%s\n", ok ? "OK: within tolerance" : "FAILED");
  return ok ? 0 : 1;
}
