// Hard and relaxed block losses on a parameterization's step data
// (learn/block_param_objective.hpp).
#include <lcprelax/learn/block_param_objective.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <string>
#include <vector>

namespace lcprelax::learn {

namespace {

class BlockParamObjective final : public Objective {
 public:
  BlockParamObjective(BlockParam param, BlockMethod method, const BlockDataset& data, const BlockLossSettings& s)
      : param_(param), method_(method), data_(data), settings_(s) {
    if (method == BlockMethod::convex)
      throw InputError(std::string("the convex loss has no LCP data to parameterize: --param ") + to_string(param) +
                       " needs --method hard or relaxed");
    if (data_.samples.empty()) throw InputError("block loss: the dataset is empty");
    if (!(data_.mass > 0.0) || !(data_.mg > 0.0)) throw InputError("block loss: the dataset's mass and mg must be positive");
    const std::string relaxed = s.relaxed.validation_error();
    if (!relaxed.empty()) throw InputError("relaxed loss options: " + relaxed);
    const std::string lemke = s.lemke.validation_error();
    if (!lemke.empty()) throw InputError("Lemke settings: " + lemke);
    const std::string qp = s.qp.validation_error();
    if (!qp.empty()) throw InputError("QP settings: " + qp);
  }

  Index num_samples() const override { return data_.size(); }

  void prepare(const ParameterSet& /*theta*/, int threads) override {
    const std::size_t n = static_cast<std::size_t>(threads < 1 ? 1 : threads);
    if (lemke_.size() < n) lemke_.resize(n);
    if (relaxed_.size() < n) relaxed_.resize(n);
  }

  SampleResult evaluate(Index sample, const ParameterSet& theta, int thread) override {
    const BlockTransition& tr = data_.samples[static_cast<std::size_t>(sample)];
    const BlockStepData d = block_step_data(param_, theta, data_.mass, data_.mg, tr.v, tr.u);
    return method_ == BlockMethod::hard ? hard(d, tr, thread) : relaxed(d, tr, thread);
  }

 private:
  SampleResult hard(const BlockStepData& d, const BlockTransition& tr, int thread) {
    std::unique_ptr<LemkeSolver>& slot = lemke_[static_cast<std::size_t>(thread)];
    if (!slot) slot = std::make_unique<LemkeSolver>(settings_.lemke);
    slot->setup(block_step_M(d), Vector(d.q));
    const LcpResult& r = slot->solve();
    SampleResult out;
    if (!has_solution(r.info.status)) {
      out.ok = false;
      out.message = std::string("Lemke: ") + to_string(r.info.status) + " (" + r.info.message + ")";
      return out;
    }
    const Eigen::Vector3d z(r.z(0), r.z(1), r.z(2));
    const double res = d.P.dot(z) + d.p - tr.v_next;
    out.loss = res * res;
    const Vector dl_dz = 2.0 * res * d.P;
    const LcpGradient g = slot->backward(dl_dz);
    const Eigen::Matrix3d dM = Eigen::Matrix3d(g.dM);
    out.gradient = block_step_chain(d, dM, g.dq, 2.0 * res * z, 2.0 * res);
    return out;
  }

  SampleResult relaxed(const BlockStepData& d, const BlockTransition& tr, int thread) {
    std::unique_ptr<RelaxedLcpSolver>& slot = relaxed_[static_cast<std::size_t>(thread)];
    if (!slot) slot = std::make_unique<RelaxedLcpSolver>(settings_.relaxed, settings_.qp);
    RelaxedLcpData x;
    x.M = block_step_M(d);
    x.q = d.q;
    const Triplet tp[] = {{0, 0, d.P(0)}, {0, 1, d.P(1)}, {0, 2, d.P(2)}};
    x.P.resize(1, 3);
    x.P.setFromTriplets(std::begin(tp), std::end(tp));
    x.p = Vector::Constant(1, d.p);
    x.target = Vector::Constant(1, tr.v_next);
    const Triplet te[] = {{0, 0, 1.0}, {0, 1, 1.0}};
    x.E.resize(1, 3);
    x.E.setFromTriplets(std::begin(te), std::end(te));
    x.e = Vector::Constant(1, d.q(2));
    const RelaxedLcpResult& r = slot->solve(x, true);
    SampleResult out;
    if (r.status != RelaxedLcpStatus::solved) {
      out.ok = false;
      out.message = std::string("relaxed QP: ") + to_string(r.status) + ": " + r.message;
      return out;
    }
    out.loss = r.cost;
    const RelaxedLcpGradient& g = r.gradient;
    const Eigen::Matrix3d dM = Eigen::Matrix3d(g.dM);
    Eigen::Vector3d dq = g.dq;
    if (g.de.size() == 1) dq(2) += g.de(0);  // e = q₂
    const Eigen::Vector3d dP = Eigen::Matrix<double, 1, 3>(Eigen::MatrixXd(g.dP)).transpose();
    out.gradient = block_step_chain(d, dM, dq, dP, g.dp(0));
    return out;
  }

  BlockParam param_;
  BlockMethod method_;
  BlockDataset data_;
  BlockLossSettings settings_;
  std::vector<std::unique_ptr<LemkeSolver>> lemke_;
  std::vector<std::unique_ptr<RelaxedLcpSolver>> relaxed_;
};

}  // namespace

std::unique_ptr<Objective> make_block_param_objective(BlockParam param, BlockMethod method, const BlockDataset& data,
                                                      const BlockLossSettings& settings) {
  return std::make_unique<BlockParamObjective>(param, method, data, settings);
}

}  // namespace lcprelax::learn
