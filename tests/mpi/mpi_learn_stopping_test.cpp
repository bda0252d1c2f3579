// The convergence test of train() (learn/trainer.hpp) under data-parallel training over 2
// MPI ranks: per-sample least squares ℓᵢ(θ) = (θ₀·aᵢ + θ₁·bᵢ − yᵢ)² on 23 samples. A
// distributed run that converges (full batch with SGD; mini-batches of 5 with Adam and a
// decaying learning rate, grad_tol 1e-5) stops at the same epoch with the same stop reason
// and bitwise the same θ on both ranks and as the same run by one process (each rank also
// trains alone, distributed = false, and compares).
#include <lcprelax/learn/trainer.hpp>
#include <lcprelax/mpi/mpi_session.hpp>

#include "mpi_main.hpp"

#include <cmath>
#include <cstring>

namespace {

using namespace lcprelax;
using namespace lcprelax::learn;

class LeastSquares : public Objective {
 public:
  Index num_samples() const override { return 23; }
  SampleResult evaluate(Index i, const ParameterSet& theta, int) override {
    const double a = std::sin(1.3 * i), b = std::cos(0.7 * i), y = 0.7 * a - 1.3 * b + 0.05 * std::sin(11.0 * i);
    const double e = theta[0].value * a + theta[1].value * b - y;
    SampleResult out;
    out.loss = e * e;
    out.gradient = Vector(2);
    out.gradient << 2 * e * a, 2 * e * b;
    return out;
  }
};

void check_same_stop(TrainSettings settings) {
  ASSERT_EQ(mpi::mpi_size(), 2) << "run under mpiexec -n 2";
  std::vector<Index> training;
  for (Index i = 0; i < 23; ++i) training.push_back(i);
  settings.threads = 1;
  LeastSquares objective;
  ParameterSet distributed({{"a", 0.0}, {"b", 0.0}}), local = distributed;
  settings.distributed = true;
  const TrainResult rd = train(objective, distributed, training, {}, settings);
  settings.distributed = false;
  const TrainResult rl = train(objective, local, training, {}, settings);
  EXPECT_TRUE(rd.converged) << rd.stop_reason;
  EXPECT_LT(static_cast<int>(rd.history.size()), settings.epochs);
  EXPECT_EQ(rd.history.size(), rl.history.size());
  EXPECT_EQ(rd.stop_reason, rl.stop_reason);
  const Vector td = distributed.values(), tl = local.values();
  EXPECT_EQ(std::memcmp(td.data(), tl.data(), 2 * sizeof(double)), 0) << td.transpose() << " vs " << tl.transpose();
  const std::vector<double> both = mpi::allgather({static_cast<double>(rd.history.size()), td(0), td(1)});
  EXPECT_EQ(std::memcmp(both.data(), both.data() + 3, 3 * sizeof(double)), 0);
}

TEST(DistributedStopping, FullBatchStopsAtTheSameEpochOnEveryRank) {
  TrainSettings s;
  s.epochs = 5000;
  s.optimizer.learning_rate = 0.05;
  check_same_stop(s);
}

TEST(DistributedStopping, MiniBatchesStopAtTheSameEpochOnEveryRank) {
  TrainSettings s;
  s.epochs = 20000;
  s.batch = 5;
  s.grad_tol = 1e-5;
  s.optimizer.kind = OptimizerKind::adam;
  s.optimizer.learning_rate = 0.05;
  s.optimizer.decay = 0.05;
  check_same_stop(s);
}

}  // namespace

LCPRELAX_MPI_TEST_MAIN()
