#pragma once
// A convex toy objective for the training-loop tests: ℓᵢ(x) = (x − cᵢ)², cᵢ = 1 + 0.01 i for
// i = 0..39, whose mean is minimal at x = mean(cᵢ) = 1.195.
#include <lcprelax/learn/trainer.hpp>

#include <vector>

namespace lcprelax::learn::test {

class Quadratic : public Objective {
 public:
  Index num_samples() const override { return 40; }
  SampleResult evaluate(Index i, const ParameterSet& theta, int) override {
    const double c = 1.0 + 0.01 * static_cast<double>(i), x = theta[0].value;
    SampleResult r;
    r.loss = (x - c) * (x - c);
    r.gradient = Vector::Constant(1, 2.0 * (x - c));
    return r;
  }
};

constexpr double kQuadraticMinimum = 1.195;  // mean of 1 + 0.01 i, i = 0..39

inline std::vector<Index> all_samples() {
  std::vector<Index> all;
  for (Index i = 0; i < 40; ++i) all.push_back(i);
  return all;
}

}  // namespace lcprelax::learn::test
