// Parameterizations of the block's step: θ → (M, q, P, p) with tangents
// (learn/block_param.hpp).
#include <lcprelax/learn/block_param.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <cmath>

namespace lcprelax::learn {

namespace {

const char* const kElementM[9] = {"M.00", "M.01", "M.02", "M.10", "M.11", "M.12", "M.20", "M.21", "M.22"};
const char* const kElementQ[9] = {"q.0.v", "q.0.u", "q.0.1", "q.1.v", "q.1.u", "q.1.1", "q.2.v", "q.2.u", "q.2.1"};

Index find(const ParameterSet& theta, const std::string& name, BlockParam param) {
  for (Index i = 0; i < theta.size(); ++i)
    if (theta[i].name == name) return i;
  throw InputError(std::string("block parameterization '") + to_string(param) + "': the parameter set has no '" +
                   name + "'");
}

// The physical data (header comment) with v* given.
void physical(BlockStepData& d, double w, double vstar, double mu, double mg) {
  d.M << w, -w, 1.0, -w, w, 1.0, -1.0, -1.0, 0.0;
  d.q << vstar, -vstar, mu * mg;
  d.P << w, -w, 0.0;
  d.p = vstar;
}

}  // namespace

const char* to_string(BlockParam p) {
  switch (p) {
    case BlockParam::physical: return "physical";
    case BlockParam::pair: return "pair";
    case BlockParam::elementwise: return "elementwise";
    case BlockParam::residual: return "residual";
  }
  return "unknown";
}

BlockParam parse_block_param(const std::string& s) {
  if (s == "physical") return BlockParam::physical;
  if (s == "pair") return BlockParam::pair;
  if (s == "elementwise") return BlockParam::elementwise;
  if (s == "residual") return BlockParam::residual;
  throw InputError("unknown parameterization '" + s + "' (physical, pair, elementwise or residual)");
}

ParameterSet block_param_parameters(BlockParam param, double mu, double mass, double mg) {
  if (!(std::isfinite(mu) && mu > 0.0)) throw InputError("block parameterization: mu must be positive and finite");
  if (!(std::isfinite(mass) && mass > 0.0) || !(std::isfinite(mg) && mg > 0.0))
    throw InputError("block parameterization: mass and mg must be positive and finite");
  ParameterSet set;
  switch (param) {
    case BlockParam::physical: set.add(Parameter{"mu", mu, Transform::log, 1e-8, 1e8, true}); break;
    case BlockParam::pair:
      set.add(Parameter{"mu_pos", mu, Transform::log, 1e-8, 1e8, true});
      set.add(Parameter{"mu_neg", mu, Transform::log, 1e-8, 1e8, true});
      set.add(Parameter{"compliance", 0.0, Transform::identity, 0.0, 1e8, true, 1.0 / mass});
      set.add(Parameter{"offset", 0.0, Transform::identity, -1e8, 1e8, true, mu * mg / mass});
      break;
    case BlockParam::residual:
      set.add(Parameter{"mu", mu, Transform::log, 1e-8, 1e8, true});
      set.add(Parameter{"residual.v", 0.0, Transform::identity, -1e8, 1e8, true});
      set.add(Parameter{"residual.u", 0.0, Transform::identity, -1e8, 1e8, true, 1.0 / mass});
      set.add(Parameter{"residual.1", 0.0, Transform::identity, -1e8, 1e8, true, mu * mg / mass});
      break;
    case BlockParam::elementwise: {
      BlockStepData d;
      physical(d, 1.0 / mass, 0.0, mu, mg);
      for (int k = 0; k < 9; ++k) set.add(Parameter{kElementM[k], d.M(k / 3, k % 3), Transform::identity});
      const double w = 1.0 / mass;
      const double A[9] = {1.0, w, 0.0, -1.0, -w, 0.0, 0.0, 0.0, mu * mg};
      for (int k = 0; k < 9; ++k) set.add(Parameter{kElementQ[k], A[k], Transform::identity});
      break;
    }
  }
  return set;
}

std::string block_param_group(const std::string& name) {
  if (name.rfind("mu", 0) == 0) return "friction";
  if (name == "compliance") return "compliance";
  if (name == "offset") return "offset";
  if (name.rfind("residual.", 0) == 0) return "residual";
  if (name.rfind("M.", 0) == 0) return "M";
  if (name.rfind("q.", 0) == 0) return "q";
  return "other";
}

BlockStepData block_step_data(BlockParam param, const ParameterSet& theta, double mass, double mg, double v, double u) {
  if (!(mass > 0.0) || !(mg > 0.0)) throw InputError("block parameterization: mass and mg must be positive");
  if (!std::isfinite(v) || !std::isfinite(u)) throw InputError("block parameterization: v and u must be finite");
  const double w = 1.0 / mass;
  const double vstar = v + u * w;
  BlockStepData d;
  d.tangents.assign(static_cast<std::size_t>(theta.size()), BlockStepData::Tangent());
  auto T = [&](Index i) -> BlockStepData::Tangent& { return d.tangents[static_cast<std::size_t>(i)]; };
  switch (param) {
    case BlockParam::physical: {
      const Index i = find(theta, "mu", param);
      physical(d, w, vstar, theta[i].value, mg);
      T(i).dq(2) = mg;
      break;
    }
    case BlockParam::residual: {
      const Index i = find(theta, "mu", param);
      const Index iv = find(theta, "residual.v", param), iu = find(theta, "residual.u", param),
                  i1 = find(theta, "residual.1", param);
      const double r = theta[iv].value * v + theta[iu].value * u + theta[i1].value;
      physical(d, w, vstar + r, theta[i].value, mg);
      T(i).dq(2) = mg;
      const std::pair<Index, double> feature[3] = {{iv, v}, {iu, u}, {i1, 1.0}};
      for (const auto& [k, f] : feature) {
        T(k).dq << f, -f, 0.0;
        T(k).dp = f;
      }
      break;
    }
    case BlockParam::pair: {
      const Index ip = find(theta, "mu_pos", param), in = find(theta, "mu_neg", param);
      const Index ic = find(theta, "compliance", param), ib = find(theta, "offset", param);
      const double mp = theta[ip].value, mn = theta[in].value, c = theta[ic].value, b = theta[ib].value;
      const double bar = 0.5 * (mp + mn), ap = bar / mp, an = bar / mn;
      physical(d, w, vstar, bar, mg);
      d.M(0, 0) += c;
      d.M(1, 1) += c;
      d.M(0, 2) = ap;
      d.M(1, 2) = an;
      d.M(2, 0) = -ap;
      d.M(2, 1) = -an;
      d.q(0) += b;
      d.q(1) -= b;
      // ∂a₊/∂μ₊ = ½/μ₊ − μ̄/μ₊², ∂a₊/∂μ₋ = ½/μ₊ (and symmetrically for a₋).
      const double dap_dp = 0.5 / mp - bar / (mp * mp), dap_dn = 0.5 / mp;
      const double dan_dn = 0.5 / mn - bar / (mn * mn), dan_dp = 0.5 / mn;
      auto set_mu = [&](Index k, double dap, double dan) {
        T(k).dM(0, 2) = dap;
        T(k).dM(1, 2) = dan;
        T(k).dM(2, 0) = -dap;
        T(k).dM(2, 1) = -dan;
        T(k).dq(2) = 0.5 * mg;
      };
      set_mu(ip, dap_dp, dan_dp);
      set_mu(in, dap_dn, dan_dn);
      T(ic).dM(0, 0) = 1.0;
      T(ic).dM(1, 1) = 1.0;
      T(ib).dq << 1.0, -1.0, 0.0;
      break;
    }
    case BlockParam::elementwise: {
      physical(d, w, vstar, 0.0, mg);  // readout; M and q replaced below
      const double f[3] = {v, u, 1.0};
      for (int k = 0; k < 9; ++k) {
        const Index iM = find(theta, kElementM[k], param);
        d.M(k / 3, k % 3) = theta[iM].value;
        T(iM).dM(k / 3, k % 3) = 1.0;
      }
      d.q.setZero();
      for (int k = 0; k < 9; ++k) {
        const Index iq = find(theta, kElementQ[k], param);
        d.q(k / 3) += theta[iq].value * f[k % 3];
        T(iq).dq(k / 3) = f[k % 3];
      }
      break;
    }
  }
  return d;
}

SparseMatrix block_step_M(const BlockStepData& d) {
  std::vector<Triplet> t;
  t.reserve(9);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) t.emplace_back(i, j, d.M(i, j));
  SparseMatrix M(3, 3);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

Vector block_step_chain(const BlockStepData& d, const Eigen::Matrix3d& dM, const Eigen::Vector3d& dq,
                        const Eigen::Vector3d& dP, double dp) {
  Vector g(static_cast<Index>(d.tangents.size()));
  for (std::size_t k = 0; k < d.tangents.size(); ++k) {
    const BlockStepData::Tangent& t = d.tangents[k];
    g(static_cast<Index>(k)) = (dM.cwiseProduct(t.dM)).sum() + dq.dot(t.dq) + dP.dot(t.dP) + dp * t.dp;
  }
  return g;
}

BlockPrediction block_param_predict(BlockParam param, const ParameterSet& theta, double mass, double mg, double v,
                                    double u, LemkeSolver& solver) {
  const BlockStepData d = block_step_data(param, theta, mass, mg, v, u);
  BlockPrediction out;
  solver.setup(block_step_M(d), Vector(d.q));
  const LcpResult& r = solver.solve();
  if (!has_solution(r.info.status)) {
    out.message = std::string("Lemke: ") + to_string(r.info.status) + " (" + r.info.message + ")";
    return out;
  }
  out.ok = true;
  out.v_next = d.P.dot(Eigen::Vector3d(r.z(0), r.z(1), r.z(2))) + d.p;
  out.stick = r.z(2) <= 1e-10 * (1.0 + r.z.cwiseAbs().maxCoeff());
  return out;
}

}  // namespace lcprelax::learn
