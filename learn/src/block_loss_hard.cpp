// The hard block loss: Lemke on the block's LCP, gradient by LemkeSolver::backward
// (learn/block_losses.hpp).
#include "elapsed.hpp"

#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/block1d.hpp>

#include <chrono>

namespace lcprelax::learn {

namespace {

using detail::Clock;
using detail::since;

class BlockHardObjective final : public BlockObjective {
 public:
  using BlockObjective::BlockObjective;
  BlockMethod method() const override { return BlockMethod::hard; }

  // Checkpoints (trainer.hpp): the per-sample Lemke bases.
  void save_state(StateWriter& out) const override {
    out.put_string("block hard: Lemke bases");
    out.put_u64(warm_.size());
    for (const std::vector<bool>& w : warm_) out.put_bools(w);
  }
  void load_state(StateReader& in) override {
    in.expect_tag("block hard: Lemke bases");
    const std::size_t n = in.get_count(data_.samples.size(), true, "samples");
    warm_.assign(n, {});
    for (std::vector<bool>& w : warm_) {
      w = in.get_bools();
      if (!w.empty() && w.size() != 3) in.fail("a Lemke basis of " + std::to_string(w.size()) + " entries");
    }
  }

  SampleResult evaluate(Index sample, const ParameterSet& theta, int thread) override {
    const Theta th = read_theta(theta);
    const BlockTransition& tr = data_.samples[static_cast<std::size_t>(sample)];
    BlockLossTimings& timer = timing(thread);
    std::unique_ptr<LemkeSolver>& slot = solvers_[static_cast<std::size_t>(thread)];
    if (!slot) slot = std::make_unique<LemkeSolver>(settings_.lemke);  // on its thread (block_losses.hpp)
    LemkeSolver& solver = *slot;
    const auto t0 = Clock::now();
    const Block1d block{th.mass, th.mg, th.mu};
    const Block1dLcp lcp = block1d_lcp(block, tr.v, tr.u);
    timer.assembly += since(t0);

    const auto t1 = Clock::now();
    solver.setup(lcp.M, lcp.q);
    std::vector<bool>& warm = warm_[static_cast<std::size_t>(sample)];
    if (settings_.warm_start_lemke && warm.size() == 3) solver.warm_start(warm);
    const LcpResult& r = solver.solve();
    timer.solve += since(t1);
    SampleResult out;
    if (!has_solution(r.info.status)) {
      out.ok = false;
      out.message = std::string("Lemke: ") + to_string(r.info.status) + " (" + r.info.message + ")";
      return out;
    }
    warm = r.z_basic;

    const auto t2 = Clock::now();
    const double w = 1.0 / th.mass;
    const double lambda = r.z(0) - r.z(1);
    const double res = block1d_next_velocity(block, tr.v, tr.u, lambda) - tr.v_next;
    out.loss = res * res;
    Vector dl_dz(3);
    dl_dz << 2.0 * res * w, -2.0 * res * w, 0.0;
    const LcpGradient g = solver.backward(dl_dz);
    const double dq2 = g.dq(2);
    double dmass = 0.0;
    if (th.i_mass >= 0) {
      const double dM = g.dM.coeff(0, 0) - g.dM.coeff(0, 1) - g.dM.coeff(1, 0) + g.dM.coeff(1, 1);
      dmass = -w * w * dM - tr.u * w * w * (g.dq(0) - g.dq(1)) - 2.0 * res * (tr.u + lambda) * w * w;
    }
    out.gradient = gradient_vector(theta.size(), th, dq2 * th.mg, dmass, dq2 * th.mu);
    timer.backward += since(t2);
    ++timer.evaluations;
    return out;
  }

 protected:
  void make_workspaces(int threads) override {
    if (solvers_.size() < static_cast<std::size_t>(threads)) solvers_.resize(static_cast<std::size_t>(threads));
    if (warm_.size() != data_.samples.size()) warm_.assign(data_.samples.size(), {});
  }

 private:
  std::vector<std::unique_ptr<LemkeSolver>> solvers_;
  std::vector<std::vector<bool>> warm_;  // per sample: the last final basis
};

}  // namespace

std::unique_ptr<BlockObjective> make_block_hard_objective(const BlockDataset& data, const BlockLossSettings& settings) {
  return std::make_unique<BlockHardObjective>(data, settings);
}

}  // namespace lcprelax::learn
