// The convex block loss: the convex block model by the interior point, ℓ = (v⁺ − v̄)²,
// gradient by QpSolver::backward (learn/block_losses.hpp).
#include "elapsed.hpp"

#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/models/block1d.hpp>

#include <chrono>

namespace lcprelax::learn {

namespace {

using detail::Clock;
using detail::since;

struct ConvexWorkspace {
  QpSolver solver;
  bool ready = false;
};

struct ConvexWarm {
  Vector x, z_bounds;
};

class BlockConvexObjective final : public BlockObjective {
 public:
  using BlockObjective::BlockObjective;
  BlockMethod method() const override { return BlockMethod::convex; }

  // Checkpoints (trainer.hpp): the per-sample QP warm starts (empty unless warm_start_qp).
  void save_state(StateWriter& out) const override {
    out.put_string("block convex: QP warm starts");
    out.put_u64(warm_.size());
    for (const ConvexWarm& w : warm_) {
      out.put_vector(w.x);
      out.put_vector(w.z_bounds);
    }
  }
  void load_state(StateReader& in) override {
    in.expect_tag("block convex: QP warm starts");
    const std::size_t n = in.get_count(data_.samples.size(), true, "samples");
    warm_.assign(n, ConvexWarm());
    for (ConvexWarm& w : warm_) {
      w.x = in.get_vector();
      w.z_bounds = in.get_vector();
    }
  }

  SampleResult evaluate(Index sample, const ParameterSet& theta, int thread) override {
    const Theta th = read_theta(theta);
    const BlockTransition& tr = data_.samples[static_cast<std::size_t>(sample)];
    BlockLossTimings& timer = timing(thread);
    std::unique_ptr<ConvexWorkspace>& slot = workspaces_[static_cast<std::size_t>(thread)];
    if (!slot) {  // on its thread (block_losses.hpp)
      slot = std::make_unique<ConvexWorkspace>();
      slot->solver.set_settings(settings_.qp);
    }
    ConvexWorkspace& ws = *slot;
    const double rho = settings_.convex_rho;
    const auto t0 = Clock::now();
    const Block1d block{th.mass, th.mg, th.mu};
    const QpProblem p = block1d_convex_qp(block, tr.v, tr.u, rho);
    timer.assembly += since(t0);

    const auto t1 = Clock::now();
    if (ws.ready) {
      ws.solver.update(p);
    } else {
      ws.solver.setup(p);
      ws.ready = true;
    }
    ConvexWarm& warm = warm_[static_cast<std::size_t>(sample)];
    if (settings_.warm_start_qp && warm.x.size() == 1) ws.solver.warm_start(warm.x, Vector(), Vector(), warm.z_bounds);
    const QpResult& r = ws.solver.solve();
    timer.solve += since(t1);
    SampleResult out;
    if (!has_solution(r.info.status)) {
      out.ok = false;
      out.message = std::string("convex QP: ") + to_string(r.info.status) + " (" + r.info.message + ")";
      return out;
    }
    warm.x = r.x;
    warm.z_bounds = r.z_bounds;

    const auto t2 = Clock::now();
    const double w = 1.0 / th.mass;
    const double lambda = r.x(0);
    const double res = block1d_next_velocity(block, tr.v, tr.u, lambda) - tr.v_next;
    out.loss = res * res;
    const QpGradient g = ws.solver.backward(Vector::Constant(1, 2.0 * res * w));
    const double dbound = g.dxu(0) - g.dxl(0);  // ∂ℓ/∂(μmg): xu = μmg, xl = −μmg
    double dmass = 0.0;
    if (th.i_mass >= 0)
      dmass = -(1.0 + rho) * w * w * g.dP.coeff(0, 0) - tr.u * w * w * g.dq(0) - 2.0 * res * (tr.u + lambda) * w * w;
    out.gradient = gradient_vector(theta.size(), th, dbound * th.mg, dmass, dbound * th.mu);
    timer.backward += since(t2);
    ++timer.evaluations;
    return out;
  }

 protected:
  void make_workspaces(int threads) override {
    if (workspaces_.size() < static_cast<std::size_t>(threads)) workspaces_.resize(static_cast<std::size_t>(threads));
    if (warm_.size() != data_.samples.size()) warm_.assign(data_.samples.size(), ConvexWarm());
  }

 private:
  std::vector<std::unique_ptr<ConvexWorkspace>> workspaces_;
  std::vector<ConvexWarm> warm_;
};

}  // namespace

std::unique_ptr<BlockObjective> make_block_convex_objective(const BlockDataset& data,
                                                            const BlockLossSettings& settings) {
  return std::make_unique<BlockConvexObjective>(data, settings);
}

}  // namespace lcprelax::learn
