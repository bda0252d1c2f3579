#pragma once
// The learning problems of the benchmark runners (header-only), the same data as
// bench_learn_block.cpp / bench_learn_polygon.cpp and the CLI (apps/cmd_learn_*.cpp):
//
// - block: generate_block_dataset with truth μ = 0.1, m = m·g = 1, `samples` transitions
//   (seed 1, noise-free); θ = block_parameters(μ, 1, 1) (only μ learned).
// - polygon: the CLI's ground truth (quadrilateral (−0.30, −0.22), (0.34, −0.18),
//   (0.26, 0.24), (−0.22, 0.20) m recentred, μ = 0.4, mass 1.5 kg, inertia 0.06 kg·m²),
//   transitions of generate_polygon_dataset (LCP model, contact steps only) with
//   `trajectories` throws of 60 steps and `seed`; initial θ = perturb_polygon_model(truth,
//   default flags (μ, mass, inertia, vertices), fraction, seed).
// - error measures: block |μ − μ*|/μ*; polygon the largest polygon_relative_error over the
//   learned parameters (and μ's own).
// - sample index lists 0..n−1.
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/learn/polygon_objective.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace lcprelax::bench {

constexpr double kBlockTrueMu = 0.1;

inline learn::BlockDataset block_dataset(Index samples, std::uint64_t seed = 1) {
  learn::BlockDataSettings s;
  s.truth = Block1d{1.0, 1.0, kBlockTrueMu};
  s.samples = samples;
  s.seed = seed;
  return learn::generate_block_dataset(s);
}

inline learn::PolygonDataset polygon_dataset(int trajectories, std::uint64_t seed) {
  learn::PolygonDataSettings s;
  s.trajectories = trajectories;
  s.steps = 60;
  s.seed = seed;
  return learn::generate_polygon_dataset(learn::reference_polygon_model(), s);
}

/// Initial θ: the truth perturbed by `fraction` (default learn flags).
inline learn::ParameterSet polygon_start(double fraction, std::uint64_t seed) {
  const learn::PolygonLearnFlags flags;
  return learn::make_polygon_parameters(learn::perturb_polygon_model(learn::reference_polygon_model(), flags, fraction, seed), flags);
}

inline learn::ParameterSet polygon_true_parameters() {
  return learn::make_polygon_parameters(learn::reference_polygon_model(), learn::PolygonLearnFlags{});
}

/// Largest relative error over the learned parameters (polygon_relative_error).
inline double polygon_max_error(const learn::ParameterSet& estimate, const learn::ParameterSet& truth) {
  double e = 0.0;
  for (Index k = 0; k < truth.size(); ++k)
    if (truth[k].learn) e = std::max(e, learn::polygon_relative_error(estimate, truth, k));
  return e;
}

inline std::vector<Index> all_samples(Index n) {
  std::vector<Index> v(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = i;
  return v;
}

}  // namespace lcprelax::bench
