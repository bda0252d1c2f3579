// The relaxed block loss: the soft-LCP QP of learn/relaxed_lcp.hpp per transition, gradient
// by the envelope theorem (learn/block_losses.hpp).
#include "elapsed.hpp"

#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/models/block1d.hpp>

#include <chrono>

namespace lcprelax::learn {

namespace {

using detail::Clock;
using detail::since;

class BlockRelaxedObjective final : public BlockObjective {
 public:
  using BlockObjective::BlockObjective;
  BlockMethod method() const override { return BlockMethod::relaxed; }

  // Checkpoints (trainer.hpp): the per-sample QP warm starts (empty unless warm_start_qp).
  void save_state(StateWriter& out) const override {
    out.put_string("block relaxed: QP warm starts");
    out.put_u64(warm_.size());
    for (const RelaxedLcpResult& w : warm_) {
      out.put_vector(w.qp_x);
      out.put_vector(w.qp_z);
      out.put_vector(w.qp_z_bounds);
    }
  }
  void load_state(StateReader& in) override {
    in.expect_tag("block relaxed: QP warm starts");
    const std::size_t n = in.get_count(data_.samples.size(), true, "samples");
    warm_.assign(n, RelaxedLcpResult());
    for (RelaxedLcpResult& w : warm_) {
      w.qp_x = in.get_vector();
      w.qp_z = in.get_vector();
      w.qp_z_bounds = in.get_vector();
    }
  }

  SampleResult evaluate(Index sample, const ParameterSet& theta, int thread) override {
    const Theta th = read_theta(theta);
    const BlockTransition& tr = data_.samples[static_cast<std::size_t>(sample)];
    BlockLossTimings& timer = timing(thread);
    std::unique_ptr<RelaxedLcpSolver>& slot = solvers_[static_cast<std::size_t>(thread)];
    if (!slot) slot = std::make_unique<RelaxedLcpSolver>(settings_.relaxed, settings_.qp);  // on its thread
    RelaxedLcpSolver& solver = *slot;
    const auto t0 = Clock::now();
    const double w = 1.0 / th.mass;
    const Block1dLcp lcp = block1d_lcp(Block1d{th.mass, th.mg, th.mu}, tr.v, tr.u);
    RelaxedLcpData d;
    d.M = lcp.M;
    d.q = lcp.q;
    const Triplet tp[] = {{0, 0, w}, {0, 1, -w}};
    d.P.resize(1, 3);
    d.P.setFromTriplets(std::begin(tp), std::end(tp));
    d.p = Vector::Constant(1, tr.v + tr.u * w);
    d.target = Vector::Constant(1, tr.v_next);
    const Triplet te[] = {{0, 0, 1.0}, {0, 1, 1.0}};
    d.E.resize(1, 3);
    d.E.setFromTriplets(std::begin(te), std::end(te));
    d.e = Vector::Constant(1, th.mu * th.mg);
    timer.assembly += since(t0);

    RelaxedLcpResult& warm = warm_[static_cast<std::size_t>(sample)];
    if (settings_.warm_start_qp && warm.qp_x.size() > 0) solver.warm_start(warm);
    const RelaxedLcpResult& r = solver.solve(d, true);
    timer.assembly += r.assembly_seconds;
    timer.solve += r.solve_seconds;
    timer.backward += r.gradient_seconds;
    SampleResult out;
    if (r.status != RelaxedLcpStatus::solved) {
      out.ok = false;
      out.message = std::string("relaxed QP: ") + to_string(r.status) + ": " + r.message;
      return out;
    }
    warm.qp_x = r.qp_x;
    warm.qp_z = r.qp_z;
    warm.qp_z_bounds = r.qp_z_bounds;

    const auto t2 = Clock::now();
    out.loss = r.cost;
    const RelaxedLcpGradient& g = r.gradient;
    const double dmu = g.dq(2) * th.mg + g.de(0) * th.mg;
    const double dmg = g.dq(2) * th.mu + g.de(0) * th.mu;
    double dmass = 0.0;
    if (th.i_mass >= 0) {
      const double dM = g.dM.coeff(0, 0) - g.dM.coeff(0, 1) - g.dM.coeff(1, 0) + g.dM.coeff(1, 1);
      const double dP = g.dP.coeff(0, 0) - g.dP.coeff(0, 1);
      dmass = -w * w * (dM + dP) - tr.u * w * w * (g.dq(0) - g.dq(1) + g.dp(0));
    }
    out.gradient = gradient_vector(theta.size(), th, dmu, dmass, dmg);
    timer.backward += since(t2);
    ++timer.evaluations;
    return out;
  }

 protected:
  void make_workspaces(int threads) override {
    if (solvers_.size() < static_cast<std::size_t>(threads)) solvers_.resize(static_cast<std::size_t>(threads));
    if (warm_.size() != data_.samples.size()) warm_.assign(data_.samples.size(), RelaxedLcpResult());
  }

 private:
  std::vector<std::unique_ptr<RelaxedLcpSolver>> solvers_;
  std::vector<RelaxedLcpResult> warm_;  // per sample: the last QP solution (qp_x, qp_z, qp_z_bounds)
};

}  // namespace

std::unique_ptr<BlockObjective> make_block_relaxed_objective(const BlockDataset& data,
                                                             const BlockLossSettings& settings) {
  return std::make_unique<BlockRelaxedObjective>(data, settings);
}

}  // namespace lcprelax::learn
