// Data-parallel training over 2 MPI ranks (learn/trainer.hpp, TrainSettings::distributed).
// Objective: per-sample least squares ℓᵢ(θ) = (θ₀·aᵢ + θ₁·bᵢ + exp(θ₂)·cᵢ − yᵢ)², 37
// samples generated from θ* = (0.7, −1.3, log 2), θ₂ log-transformed (a positive
// parameter). Expected: training 30 epochs with mini-batches of 8 (SGD with momentum) and
// with Adam, distributed over the 2 ranks, gives parameters that are (a) bitwise identical
// on both ranks and (b) bitwise identical to the same training run by one process (each
// rank also trains alone, distributed = false, and compares); each rank evaluated only
// its shard (sample i on rank i mod 2: counted); the validation loss is the same too.
#include <lcprelax/learn/trainer.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include "mpi_main.hpp"

#include <atomic>
#include <cmath>
#include <cstring>

namespace {

using namespace lcprelax;
using namespace lcprelax::learn;

class LeastSquares : public Objective {
 public:
  LeastSquares() {
    for (int i = 0; i < 37; ++i) {
      const double a = std::sin(1.3 * i), b = std::cos(0.7 * i), c = 0.1 * (i % 5), y = 0.7 * a - 1.3 * b + 2.0 * c;
      rows_.push_back({a, b, c, y + 1e-3 * std::sin(11.0 * i)});
    }
  }
  Index num_samples() const override { return static_cast<Index>(rows_.size()); }
  SampleResult evaluate(Index i, const ParameterSet& theta, int) override {
    ++evaluations;
    const auto& r = rows_[static_cast<std::size_t>(i)];
    const double e = theta[0].value * r[0] + theta[1].value * r[1] + theta[2].value * r[2] - r[3];
    SampleResult out;
    out.loss = e * e;
    out.gradient = Vector(3);
    out.gradient << 2 * e * r[0], 2 * e * r[1], 2 * e * r[2];
    return out;
  }
  std::atomic<long> evaluations{0};

 private:
  std::vector<std::array<double, 4>> rows_;
};

ParameterSet initial() {
  return ParameterSet({{"a", 0.0}, {"b", 0.0}, {"scale", 1.0, Transform::log, 1e-3, 1e3}});
}

void check_same_as_one_process(OptimizerKind kind) {
  ASSERT_EQ(mpi::mpi_size(), 2) << "run under mpiexec -n 2";
  std::vector<Index> training, validation;
  split_samples(37, 0.2, 3, training, validation);
  TrainSettings settings;
  settings.epochs = 30;
  settings.batch = 8;
  settings.threads = 1;
  settings.optimizer.kind = kind;
  settings.optimizer.learning_rate = kind == OptimizerKind::sgd ? 0.05 : 0.05;

  LeastSquares distributed_objective, local_objective;
  ParameterSet distributed = initial(), local = initial();
  settings.distributed = true;
  const TrainResult rd = train(distributed_objective, distributed, training, validation, settings);
  settings.distributed = false;
  const TrainResult rl = train(local_objective, local, training, validation, settings);

  const Vector td = distributed.values(), tl = local.values();
  EXPECT_EQ(std::memcmp(td.data(), tl.data(), 3 * sizeof(double)), 0) << td.transpose() << " vs " << tl.transpose();
  EXPECT_EQ(rd.history.back().validation_loss, rl.history.back().validation_loss);
  const std::vector<double> both = mpi::allgather({td(0), td(1), td(2)});
  EXPECT_EQ(std::memcmp(both.data(), both.data() + 3, 3 * sizeof(double)), 0);
  // Sharding: each rank evaluated about half of what one process evaluates.
  EXPECT_LT(distributed_objective.evaluations.load(), local_objective.evaluations.load() * 3 / 4);
  EXPECT_GT(distributed_objective.evaluations.load(), 0);
  EXPECT_NEAR(td(0), 0.7, 0.2);  // it learned something (loose: 30 epochs)
}

TEST(DistributedTraining, SgdMatchesOneProcessBitwise) { check_same_as_one_process(OptimizerKind::sgd); }
TEST(DistributedTraining, AdamMatchesOneProcessBitwise) { check_same_as_one_process(OptimizerKind::adam); }

}  // namespace

LCPRELAX_MPI_TEST_MAIN()
