// Parameterizations of the block's step (learn/block_param.hpp): the tangents
// ∂(M, q, P, p)/∂θ against central differences of block_step_data (1e-8 absolute, step
// 1e-6: the data are polynomial or rational in θ), and the hard and relaxed losses
// (learn/block_param_objective.hpp) against central differences of the mean loss for every
// parameterization, at a θ perturbed off the physical model (step 1e-6·max(|θ|, scale);
// 1e-5 relative, QP tolerance 1e-11; for the hard loss every sample's Lemke mode is
// checked to be the same at θ ± h, so no stick/slip kink lies in the step). Also: the physical
// parameterization gives the same loss and gradient as the block's own objectives
// (learn/block_losses.hpp), and the convex method is refused.
#include <lcprelax/learn/block_param.hpp>
#include <lcprelax/learn/block_param_objective.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include "learn_block_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace lcprelax::learn {
namespace {

constexpr BlockParam kAll[] = {BlockParam::physical, BlockParam::pair, BlockParam::elementwise, BlockParam::residual};

BlockDataset data() { return test::gradient_test_block_data(7); }

std::vector<Index> all(const BlockDataset& d) { return test::every_sample(d); }

// θ of `param` moved off the physical model: every parameter by a seeded amount.
ParameterSet perturbed(BlockParam param, std::uint64_t seed) {
  ParameterSet t = block_param_parameters(param, 0.35, 1.3, 0.8);
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (Index i = 0; i < t.size(); ++i) {
    const Parameter& p = t[i];
    double x = p.value;
    if (p.transform == Transform::log) x *= std::exp(0.2 * U(g));
    else if (p.name == "compliance") x = 0.05 + 0.05 * std::abs(U(g));
    else x += 0.03 * U(g) * std::max(std::abs(x), p.scale);
    t.set_value(p.name, x);
  }
  return t;
}

double step(const Parameter& p) { return 1e-6 * std::max(std::abs(p.value), p.scale); }

TEST(BlockParam, TangentsMatchFiniteDifferences) {
  for (BlockParam param : kAll) {
    SCOPED_TRACE(to_string(param));
    const ParameterSet theta = perturbed(param, 3);
    for (double v : {-0.4, 0.7})
      for (double u : {0.3, -1.1}) {
        const BlockStepData d = block_step_data(param, theta, 1.3, 0.8, v, u);
        for (Index k = 0; k < theta.size(); ++k) {
          const double h = step(theta[k]);
          ParameterSet a = theta, b = theta;
          a.set_value(theta[k].name, theta[k].value + h);
          b.set_value(theta[k].name, theta[k].value - h);
          const BlockStepData da = block_step_data(param, a, 1.3, 0.8, v, u);
          const BlockStepData db = block_step_data(param, b, 1.3, 0.8, v, u);
          const BlockStepData::Tangent& t = d.tangents[static_cast<std::size_t>(k)];
          EXPECT_LT(((da.M - db.M) / (2 * h) - t.dM).cwiseAbs().maxCoeff(), 1e-8) << theta[k].name;
          EXPECT_LT(((da.q - db.q) / (2 * h) - t.dq).cwiseAbs().maxCoeff(), 1e-8) << theta[k].name;
          EXPECT_LT(((da.P - db.P) / (2 * h) - t.dP).cwiseAbs().maxCoeff(), 1e-8) << theta[k].name;
          EXPECT_NEAR((da.p - db.p) / (2 * h), t.dp, 1e-8) << theta[k].name;
        }
      }
  }
}

// The Lemke modes (γ basic or not) of every sample, to keep FD points off the hard loss's kinks.
std::vector<bool> modes(BlockParam param, const ParameterSet& theta, const BlockDataset& d) {
  LemkeSolver solver;
  std::vector<bool> m;
  for (const BlockTransition& s : d.samples) m.push_back(block_param_predict(param, theta, d.mass, d.mg, s.v, s.u, solver).stick);
  return m;
}

void check_loss_gradient(BlockParam param, BlockMethod method, const ParameterSet& theta, double tol) {
  const BlockDataset d = data();
  BlockLossSettings s;
  s.qp.eps_abs = 1e-11;
  s.relaxed.nonconvex = NonconvexPolicy::shift;
  auto objective = make_block_param_objective(param, method, d, s);
  const BatchResult r = evaluate_mean(*objective, theta, all(d), 1);
  ASSERT_EQ(r.failed, 0) << r.first_failure;
  ASSERT_EQ(r.gradient.size(), theta.size());
  double norm = 0.0;
  for (Index k = 0; k < theta.size(); ++k) norm = std::max(norm, std::abs(r.gradient(k)) * std::max(std::abs(theta[k].value), theta[k].scale));
  for (Index k = 0; k < theta.size(); ++k) {
    const double h = step(theta[k]);
    ParameterSet a = theta, b = theta;
    a.set_value(theta[k].name, theta[k].value + h);
    b.set_value(theta[k].name, theta[k].value - h);
    if (method == BlockMethod::hard) {
      ASSERT_EQ(modes(param, a, d), modes(param, b, d)) << "a stick/slip kink within the FD step of " << theta[k].name;
    }
    const double fd = (evaluate_mean(*objective, a, all(d), 1).loss - evaluate_mean(*objective, b, all(d), 1).loss) / (2 * h);
    const double g = r.gradient(k);
    // relative to the parameter's own derivative, floored by 1e-3 of the largest scaled entry
    const double floor = 1e-3 * norm / std::max(std::abs(theta[k].value), theta[k].scale);
    EXPECT_NEAR(g, fd, tol * std::max(std::abs(fd), floor)) << to_string(method) << " d/d" << theta[k].name;
  }
}

TEST(BlockParam, HardGradientMatchesFiniteDifferences) {
  for (BlockParam param : kAll) {
    SCOPED_TRACE(to_string(param));
    for (std::uint64_t seed : {1, 2}) check_loss_gradient(param, BlockMethod::hard, perturbed(param, seed), 1e-5);
  }
}

TEST(BlockParam, RelaxedGradientMatchesFiniteDifferences) {
  for (BlockParam param : kAll) {
    SCOPED_TRACE(to_string(param));
    for (std::uint64_t seed : {1, 2}) check_loss_gradient(param, BlockMethod::relaxed, perturbed(param, seed), 1e-5);
  }
}

TEST(BlockParam, PhysicalAgreesWithTheBlockObjectives) {
  const BlockDataset d = data();
  for (BlockMethod method : {BlockMethod::hard, BlockMethod::relaxed}) {
    BlockLossSettings s;
    s.warm_start_lemke = false;
    auto mine = make_block_param_objective(BlockParam::physical, method, d, s);
    auto theirs = make_block_objective(method, d, s);
    const ParameterSet theta = block_param_parameters(BlockParam::physical, 0.45, d.mass, d.mg);
    const BatchResult a = evaluate_mean(*mine, theta, all(d), 1);
    const BatchResult b = evaluate_mean(*theirs, theta, all(d), 1);
    EXPECT_NEAR(a.loss, b.loss, 1e-12 * std::abs(b.loss)) << to_string(method);
    EXPECT_NEAR(a.gradient(0), b.gradient(0), 1e-9 * std::abs(b.gradient(0))) << to_string(method);
  }
}

TEST(BlockParam, AtTheTruthEveryParameterizationPredictsTheTruth) {
  const BlockDataset d = data();  // noise only in v_next; predictions compared with the exact step
  LemkeSolver solver;
  const Block1d truth{1.3, 0.8, 0.3};
  for (BlockParam param : kAll) {
    const ParameterSet theta = block_param_parameters(param, 0.3, 1.3, 0.8);
    for (const BlockTransition& s : d.samples) {
      const BlockPrediction p = block_param_predict(param, theta, 1.3, 0.8, s.v, s.u, solver);
      ASSERT_TRUE(p.ok) << p.message;
      const double exact = block1d_next_velocity(truth, s.v, s.u, block1d_exact_impulse(truth, s.v, s.u));
      EXPECT_NEAR(p.v_next, exact, 1e-12) << to_string(param);
      EXPECT_EQ(p.stick, std::abs(s.v + s.u / 1.3) <= 0.3 * 0.8 / 1.3) << to_string(param);
    }
  }
}

TEST(BlockParam, RefusesTheConvexMethodAndUnknownNames) {
  EXPECT_THROW(make_block_param_objective(BlockParam::pair, BlockMethod::convex, data()), InputError);
  EXPECT_THROW(parse_block_param("elementwize"), InputError);
  const ParameterSet physical = block_param_parameters(BlockParam::physical, 0.3, 1.0, 1.0);
  EXPECT_THROW(block_step_data(BlockParam::pair, physical, 1.0, 1.0, 0.1, 0.2), InputError);
}

}  // namespace
}  // namespace lcprelax::learn
