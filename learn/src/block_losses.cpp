// Block losses: method names, the parameter set, the shared base of the objectives and the
// factory (learn/block_losses.hpp).
#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>

namespace lcprelax::learn {

const char* to_string(BlockMethod m) {
  switch (m) {
    case BlockMethod::hard: return "hard";
    case BlockMethod::relaxed: return "relaxed";
    case BlockMethod::convex: return "convex";
  }
  return "unknown";
}

BlockMethod parse_block_method(const std::string& s) {
  if (s == "hard") return BlockMethod::hard;
  if (s == "relaxed") return BlockMethod::relaxed;
  if (s == "convex") return BlockMethod::convex;
  throw InputError("unknown method '" + s + "' (hard, relaxed or convex)");
}

ParameterSet block_parameters(double mu, double mass, double mg, bool learn_mass, bool learn_mg) {
  ParameterSet set;
  set.add(Parameter{"mu", mu, Transform::log, 1e-8, 1e8, true});
  set.add(Parameter{"mass", mass, Transform::log, 1e-8, 1e8, learn_mass});
  set.add(Parameter{"mg", mg, Transform::log, 1e-8, 1e8, learn_mg});
  return set;
}

BlockObjective::BlockObjective(const BlockDataset& data, const BlockLossSettings& settings)
    : data_(data), settings_(settings) {
  if (data_.samples.empty()) throw InputError("block loss: the dataset is empty");
  if (!(data_.mass > 0.0) || !(data_.mg > 0.0)) throw InputError("block loss: the dataset's mass and mg must be positive");
  const std::string relaxed = settings.relaxed.validation_error();
  if (!relaxed.empty()) throw InputError("relaxed loss options: " + relaxed);
  if (!std::isfinite(settings.convex_rho) || settings.convex_rho < 0.0)
    throw InputError("convex loss: rho must be finite and ≥ 0");
  const std::string lemke = settings.lemke.validation_error();
  if (!lemke.empty()) throw InputError("Lemke settings: " + lemke);
  const std::string qp = settings.qp.validation_error();
  if (!qp.empty()) throw InputError("QP settings: " + qp);
}

BlockObjective::~BlockObjective() = default;

Index BlockObjective::num_samples() const { return data_.size(); }

void BlockObjective::prepare(const ParameterSet& /*theta*/, int threads) {
  if (threads < 1) threads = 1;
  if (timings_.size() < static_cast<std::size_t>(threads)) timings_.resize(static_cast<std::size_t>(threads));
  make_workspaces(threads);
}

BlockLossTimings BlockObjective::timings() const {
  BlockLossTimings t;
  for (const ThreadTimings& padded : timings_) {
    const BlockLossTimings& s = padded.t;
    t.assembly += s.assembly;
    t.solve += s.solve;
    t.backward += s.backward;
    t.evaluations += s.evaluations;
  }
  return t;
}

void BlockObjective::reset_timings() {
  for (ThreadTimings& t : timings_) t.t = BlockLossTimings();
}

BlockObjective::Theta BlockObjective::read_theta(const ParameterSet& theta) const {
  Theta t;
  t.mass = data_.mass;
  t.mg = data_.mg;
  for (Index i = 0; i < theta.size(); ++i) {
    const Parameter& p = theta[i];
    if (p.name == "mu") {
      t.mu = p.value;
      t.i_mu = i;
    } else if (p.name == "mass") {
      t.mass = p.value;
      t.i_mass = i;
    } else if (p.name == "mg") {
      t.mg = p.value;
      t.i_mg = i;
    }
  }
  if (t.i_mu < 0) throw InputError("block loss: the parameter set has no 'mu'");
  return t;
}

Vector BlockObjective::gradient_vector(Index size, const Theta& t, double dmu, double dmass, double dmg) {
  Vector g = Vector::Zero(size);
  g(t.i_mu) = dmu;
  if (t.i_mass >= 0) g(t.i_mass) = dmass;
  if (t.i_mg >= 0) g(t.i_mg) = dmg;
  return g;
}

std::unique_ptr<BlockObjective> make_block_objective(BlockMethod method, const BlockDataset& data,
                                                     const BlockLossSettings& settings) {
  switch (method) {
    case BlockMethod::hard: return make_block_hard_objective(data, settings);
    case BlockMethod::relaxed: return make_block_relaxed_objective(data, settings);
    case BlockMethod::convex: return make_block_convex_objective(data, settings);
  }
  throw InputError("unknown block method");
}

}  // namespace lcprelax::learn
