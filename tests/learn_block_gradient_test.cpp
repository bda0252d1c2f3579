// Gradients of the block losses (learn/block_losses.hpp) against central finite differences
// of the mean loss, away from kinks (no sample within 2% of its stick/slip boundary at the
// evaluation point): hard, relaxed (every max-dissipation mode, soft options on and off) and
// convex, with respect to μ, the mass and m·g, to 1e-5 relative (step 1e-6 relative; QP
// tolerance 1e-11/1e-12). Relaxed with max dissipation ext to 2e-4: its extra term is
// differentiated through the QP's solution map (adjoint), whose accuracy the interior
// point's final iterate limits (measured 1e-4 on d/dmass at μ = 0.55).
// Also: 1 and 2 threads give bitwise-identical mean losses and gradients (memcmp), with
// per-sample warm starts on, over two successive evaluations.
#include <lcprelax/learn/block_losses.hpp>

#include "learn_block_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace lcprelax::learn {
namespace {

BlockDataset data() { return test::gradient_test_block_data(5); }

std::vector<Index> all(const BlockDataset& d) { return test::every_sample(d); }

// Distance of the closest sample to its stick/slip boundary, relative to the boundary.
double kink_distance(const BlockDataset& d, const ParameterSet& t) {
  double m = INFINITY;
  const double bound = t.value("mu") * t.value("mg") / t.value("mass");
  for (const BlockTransition& s : d.samples)
    m = std::min(m, std::abs(std::abs(s.v + s.u / t.value("mass")) - bound) / bound);
  return m;
}

void check_gradient(BlockObjective& objective, const ParameterSet& theta, double tol = 1e-5) {
  const std::vector<Index> samples = all(objective.data());
  ASSERT_GT(kink_distance(objective.data(), theta), 0.02);
  const BatchResult r = evaluate_mean(objective, theta, samples, 1);
  ASSERT_EQ(r.failed, 0) << r.first_failure;
  for (const char* name : {"mu", "mass", "mg"}) {
    const double x = theta.value(name), h = 1e-6 * x;
    ParameterSet a = theta, b = theta;
    a.set_value(name, x + h);
    b.set_value(name, x - h);
    const double fd = (evaluate_mean(objective, a, samples, 1).loss - evaluate_mean(objective, b, samples, 1).loss) / (2 * h);
    const double g = r.gradient(theta.index(name));
    EXPECT_NEAR(g, fd, tol * std::max(1e-3, std::abs(fd))) << to_string(objective.method()) << " d/d" << name;
  }
}

TEST(BlockGradient, HardMatchesFiniteDifferences) {
  auto objective = make_block_hard_objective(data(), {});
  for (double mu : {0.12, 0.3, 0.55}) check_gradient(*objective, block_parameters(mu, 1.1, 0.9, true, true));
}

TEST(BlockGradient, ConvexMatchesFiniteDifferences) {
  for (double rho : {0.0, 0.1}) {
    BlockLossSettings s;
    s.convex_rho = rho;
    s.qp.eps_abs = 1e-12;  // the interior point's bound multipliers limit the accuracy (~5e-5 at 1e-9)
    auto objective = make_block_convex_objective(data(), s);
    for (double mu : {0.12, 0.3, 0.55}) check_gradient(*objective, block_parameters(mu, 1.1, 0.9, true, true));
  }
}

TEST(BlockGradient, RelaxedMatchesFiniteDifferences) {
  for (MaxDissipation md : {MaxDissipation::none, MaxDissipation::qp, MaxDissipation::ext})
    for (int soft = 0; soft < 2; ++soft) {
      BlockLossSettings s;
      s.relaxed.max_dissipation = md;
      s.relaxed.soft_nonnegativity = soft;
      s.relaxed.soft_lambdas = soft;
      s.qp.eps_abs = 1e-11;
      SCOPED_TRACE(std::string("max dissipation ") + to_string(md) + (soft ? ", soft" : ""));
      auto objective = make_block_relaxed_objective(data(), s);
      for (double mu : {0.12, 0.55, 0.9}) {
        SCOPED_TRACE(mu);
        check_gradient(*objective, block_parameters(mu, 1.1, 0.9, true, true), md == MaxDissipation::ext ? 2e-4 : 1e-5);
      }
    }
}

TEST(BlockGradient, OneAndTwoThreadsAreBitwiseIdentical) {
  const BlockDataset d = data();
  for (BlockMethod m : {BlockMethod::hard, BlockMethod::relaxed, BlockMethod::convex}) {
    BlockLossSettings s;
    s.warm_start_qp = true;  // warm starts on everywhere: still thread-count independent
    auto one = make_block_objective(m, d, s);
    auto two = make_block_objective(m, d, s);
    const ParameterSet theta = block_parameters(0.4, 1.1, 0.9, true, true);
    for (int pass = 0; pass < 2; ++pass) {  // the second pass is warm-started
      const BatchResult a = evaluate_mean(*one, theta, all(d), 1);
      const BatchResult b = evaluate_mean(*two, theta, all(d), 2);
      EXPECT_EQ(std::memcmp(&a.loss, &b.loss, sizeof(double)), 0) << to_string(m);
      ASSERT_EQ(a.gradient.size(), b.gradient.size());
      EXPECT_EQ(std::memcmp(a.gradient.data(), b.gradient.data(), sizeof(double) * a.gradient.size()), 0)
          << to_string(m);
    }
  }
}

}  // namespace
}  // namespace lcprelax::learn
