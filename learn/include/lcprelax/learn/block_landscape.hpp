#pragma once
// The loss landscape of the 1-D block: mean loss and mean ∂loss/∂μ of each method
// (learn/block_losses.hpp) over a log-spaced range of μ, written as CSV and drawn as a line
// plot (scenes/line_plot.hpp). It shows the seeds' point at a glance (Parmar, Halm & Posa,
// IROS 2021): the hard and convex gradients are exactly 0 for μ above the value at which
// every sample sticks, the relaxed one is not.
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

}  // namespace lcprelax::learn
