#pragma once
// The loss landscape of the 1-D block: mean loss and mean ∂loss/∂μ of each method
// (learn/block_losses.hpp) over a log-spaced range of μ, written as CSV and drawn as a line
// plot (scenes/line_plot.hpp). It shows the seeds' point at a glance (Parmar, Halm & Posa,
// IROS 2021): the hard and convex gradients are exactly 0 for μ above the value at which
// every sample sticks, the relaxed one is not. classify_gradient / count_gradient_signs turn
// a landscape (this one, or a scene's over a box of parameters: bench/run_gradient_landscape)
// into the fraction of points with a nonzero gradient of the right sign.
#include <lcprelax/learn/block_losses.hpp>

#include <string>
#include <vector>

namespace lcprelax::learn {

struct BlockLandscape {
  std::vector<double> mu;                    ///< the μ grid
  std::vector<BlockMethod> methods;
  std::vector<std::vector<double>> loss;     ///< [method][point] mean loss
  std::vector<std::vector<double>> gradient; ///< [method][point] mean ∂loss/∂μ
  std::vector<std::vector<int>> failed;      ///< [method][point] failed samples
};

/// `points` ≥ 2 values of μ log-spaced over [mu_min, mu_max] (0 < mu_min < mu_max), every
/// method evaluated on every sample (mass and mg fixed at the dataset's). Throws InputError
/// on a bad range.
BlockLandscape block_landscape(const BlockDataset& data, const BlockLossSettings& settings,
                               const std::vector<BlockMethod>& methods, double mu_min, double mu_max, int points,
                               int threads);

/// CSV with the header "mu,<method>_loss,<method>_gradient,..." (17 significant digits).
void write_landscape_csv(const std::string& path, const BlockLandscape& landscape);

/// Writes two plots (.png or .svg by `path`'s extension): `path` with the mean losses on
/// log-log axes (the true μ as a dashed vertical line when finite), and
/// `<stem>_gradient.<ext>` with the mean gradients on a linear y axis (a gradient of exactly
/// 0 cannot be drawn on a log axis). Returns the paths written. Throws std::runtime_error
/// without Cairo.
std::vector<std::string> write_landscape_plot(const std::string& path, const BlockLandscape& landscape,
                                              double true_mu);

/// Where a loss gradient points at one point of a parameter box (issue 20, experiment 3:
/// the fraction of the box on which gradient descent moves toward the truth).
enum class GradientSign {
  correct,  ///< nonzero and −g points toward the truth: g·(θ* − θ) < 0
  wrong,    ///< nonzero, but −g points away from (or across) the truth
  zero,     ///< |∂ℓ/∂log θ| ≤ zero_tolerance·|ℓ| in every coordinate (flat: no usable gradient)
  failed    ///< the loss or gradient is not finite (failed samples)
};
const char* to_string(GradientSign s);

/// Classifies one point. `theta`, `truth` > 0 and `gradient` = ∂ℓ/∂θ have one entry per
/// parameter; the test is made in log coordinates ξ = log θ (the learning's own: a step of
/// ξ is a relative step of θ), g_ξ = θ ⊙ ∂ℓ/∂θ, "correct" when g_ξ·(ξ* − ξ) < 0. One
/// parameter: sign(∂ℓ/∂θ) = sign(θ − θ*). Throws InputError on sizes that differ.
GradientSign classify_gradient(const Vector& theta, const Vector& truth, const Vector& gradient, double loss,
                               double zero_tolerance);

struct GradientSignCounts {
  int correct = 0, wrong = 0, zero = 0, failed = 0;
  int points() const { return correct + wrong + zero + failed; }
  double fraction(GradientSign s) const;  ///< of points(); NaN when there are none
  void add(GradientSign s);
};

/// The counts of method `j` of a block landscape against the true μ (points within a
/// relative 1e-9 of the truth are skipped: no direction is correct there).
GradientSignCounts count_gradient_signs(const BlockLandscape& landscape, std::size_t j, double true_mu,
                                        double zero_tolerance);

}  // namespace lcprelax::learn
