// The gradient-landscape classification of issue 20, experiment 3 (learn/block_landscape.hpp
// classify_gradient, count_gradient_signs; bench/run_gradient_landscape.cpp). Expected:
// - one parameter: correct iff sign(∂ℓ/∂θ) = sign(θ − θ*); zero within the tolerance
//   relative to |ℓ|; NaN is failed;
// - several: correct iff −g points toward the truth in log coordinates (a component of the
//   wrong sign is allowed when the others outweigh it), sizes must agree;
// - on the seeds' block (Parmar, Halm & Posa, IROS 2021) the hard loss is flat (exactly 0)
//   for every μ above the value at which every sample sticks; the relaxed loss still points
//   toward the truth over part of that range and on a larger fraction of the scan.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/block_landscape.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace lcprelax::learn {
namespace {

Vector v1(double a) { return Vector::Constant(1, a); }
Vector v2(double a, double b) {
  Vector v(2);
  v << a, b;
  return v;
}

TEST(GradientLandscape, OneParameterSignAgainstTheTruth) {
  EXPECT_EQ(classify_gradient(v1(2.0), v1(1.0), v1(0.3), 1.0, 1e-6), GradientSign::correct);
  EXPECT_EQ(classify_gradient(v1(2.0), v1(1.0), v1(-0.3), 1.0, 1e-6), GradientSign::wrong);
  EXPECT_EQ(classify_gradient(v1(0.5), v1(1.0), v1(-0.3), 1.0, 1e-6), GradientSign::correct);
  EXPECT_EQ(classify_gradient(v1(0.5), v1(1.0), v1(0.0), 1.0, 1e-6), GradientSign::zero);
  // |∂ℓ/∂log θ| = 2·4e-7 = 8e-7 ≤ 1e-6·|ℓ|: flat; 10× larger is not.
  EXPECT_EQ(classify_gradient(v1(2.0), v1(1.0), v1(4e-7), 1.0, 1e-6), GradientSign::zero);
  EXPECT_EQ(classify_gradient(v1(2.0), v1(1.0), v1(4e-6), 1.0, 1e-6), GradientSign::correct);
  EXPECT_EQ(classify_gradient(v1(2.0), v1(1.0), v1(std::nan("")), 1.0, 1e-6), GradientSign::failed);
  EXPECT_EQ(classify_gradient(v1(2.0), v1(1.0), v1(1.0), INFINITY, 1e-6), GradientSign::failed);
}

TEST(GradientLandscape, SeveralParametersUseTheDirectionInLogCoordinates) {
  // θ = (2, 2), θ* = (1, 1): ξ* − ξ = −log 2·(1, 1). g_ξ = θ⊙g = (2, −1): g_ξ·(ξ* − ξ) =
  // −log 2 < 0, correct although the second component alone points away.
  EXPECT_EQ(classify_gradient(v2(2, 2), v2(1, 1), v2(1.0, -0.5), 1.0, 1e-6), GradientSign::correct);
  EXPECT_EQ(classify_gradient(v2(2, 2), v2(1, 1), v2(0.5, -1.0), 1.0, 1e-6), GradientSign::wrong);
  EXPECT_THROW(classify_gradient(v2(2, 2), v1(1), v2(1, 1), 1.0, 1e-6), InputError);
  GradientSignCounts c;
  c.add(GradientSign::correct), c.add(GradientSign::correct), c.add(GradientSign::zero), c.add(GradientSign::wrong);
  EXPECT_EQ(c.points(), 4);
  EXPECT_DOUBLE_EQ(c.fraction(GradientSign::correct), 0.5);
  EXPECT_TRUE(std::isnan(GradientSignCounts{}.fraction(GradientSign::correct)));
}

TEST(GradientLandscape, BlockHardLossIsFlatWhereEverySampleSticksAndRelaxedIsNot) {
  BlockDataSettings g;
  g.truth = Block1d{1.0, 1.0, 0.1};
  g.samples = 60;
  const BlockDataset data = generate_block_dataset(g);
  const std::vector<BlockMethod> methods = {BlockMethod::hard, BlockMethod::relaxed};
  const BlockLandscape L = block_landscape(data, BlockLossSettings{}, methods, 0.005, 5.0, 25, 1);
  // The largest |v*| of the samples: above μ = m·max|v*|/mg every sample sticks.
  double fastest = 0.0;
  for (const BlockTransition& t : data.samples) fastest = std::max(fastest, std::abs(t.v + t.u / data.mass));
  const double all_stick = data.mass * fastest / data.mg;
  int flat_checked = 0;
  for (std::size_t k = 0; k < L.mu.size(); ++k)
    if (L.mu[k] > 1.01 * all_stick) {
      EXPECT_EQ(L.gradient[0][k], 0.0) << "hard, mu = " << L.mu[k];
      ++flat_checked;
    }
  ASSERT_GT(flat_checked, 3);
  const GradientSignCounts hard = count_gradient_signs(L, 0, g.truth.mu, 1e-6);
  const GradientSignCounts relaxed = count_gradient_signs(L, 1, g.truth.mu, 1e-6);
  EXPECT_EQ(hard.points(), 25);
  EXPECT_GE(hard.zero, flat_checked);
  // The relaxed loss flattens too, but only far above (μ ≳ 25μ*, measured), so it has points
  // where hard is exactly 0 and relaxed is correct, and fewer flat points in all.
  int rescued = 0;
  for (std::size_t k = 0; k < L.mu.size(); ++k)
    rescued += L.gradient[0][k] == 0.0 && classify_gradient(v1(L.mu[k]), v1(g.truth.mu), v1(L.gradient[1][k]),
                                                            L.loss[1][k], 1e-6) == GradientSign::correct;
  EXPECT_GE(rescued, 2);
  EXPECT_LT(relaxed.zero, hard.zero);
  EXPECT_EQ(relaxed.failed, 0);
  EXPECT_EQ(relaxed.wrong, 0);
  EXPECT_GT(relaxed.fraction(GradientSign::correct), hard.fraction(GradientSign::correct));
  EXPECT_THROW(count_gradient_signs(L, 2, g.truth.mu, 1e-6), InputError);
}

}  // namespace
}  // namespace lcprelax::learn
