#pragma once
// The block dataset of the block-loss gradient tests (learn_block_gradient_test,
// learn_param_gradient_test): 24 noisy transitions (noise 0.05) of the block with μ = 1.3,
// mass 0.8, m·g = 0.3 (Block1d), and the index list of all its samples.
#include <lcprelax/learn/block_dataset.hpp>

#include <cstdint>
#include <vector>

namespace lcprelax::learn::test {

inline BlockDataset gradient_test_block_data(std::uint64_t seed) {
  BlockDataSettings s;
  s.truth = Block1d{1.3, 0.8, 0.3};
  s.samples = 24;
  s.seed = seed;
  s.noise = 0.05;
  return generate_block_dataset(s);
}

inline std::vector<Index> every_sample(const BlockDataset& d) {
  std::vector<Index> v;
  for (Index i = 0; i < d.size(); ++i) v.push_back(i);
  return v;
}

}  // namespace lcprelax::learn::test
