// SGD with momentum and Adam (optimizer.hpp).
#include <lcprelax/learn/optimizer.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <stdexcept>

namespace lcprelax::learn {

const char* to_string(OptimizerKind k) { return k == OptimizerKind::sgd ? "sgd" : "adam"; }

OptimizerKind parse_optimizer_kind(const std::string& s) {
  if (s == "sgd") return OptimizerKind::sgd;
  if (s == "adam") return OptimizerKind::adam;
  throw InputError("unknown optimizer '" + s + "' (sgd or adam)");
}

std::string OptimizerSettings::validation_error() const {
  if (!(learning_rate > 0.0) || !std::isfinite(learning_rate)) return "learning_rate must be positive and finite";
  if (!(momentum >= 0.0 && momentum < 1.0)) return "momentum must be in [0, 1)";
  if (!(beta1 >= 0.0 && beta1 < 1.0)) return "beta1 must be in [0, 1)";
  if (!(beta2 >= 0.0 && beta2 < 1.0)) return "beta2 must be in [0, 1)";
  if (!(epsilon > 0.0)) return "epsilon must be positive";
  if (!(decay >= 0.0) || !std::isfinite(decay)) return "decay must be non-negative and finite";
  if (!(clip_norm > 0.0)) return "clip_norm must be positive";
  return {};
}

Optimizer::Optimizer(const OptimizerSettings& settings) : settings_(settings) {
  const std::string error = settings.validation_error();
  if (!error.empty()) throw InputError("optimizer settings: " + error);
}

void Optimizer::reset() {
  m_.resize(0);
  s_.resize(0);
  steps_ = 0;
}

void Optimizer::restore(const OptimizerState& state) {
  if (state.m.size() != state.s.size()) throw InputError("optimizer state: moments of different sizes");
  if (state.steps < 0) throw InputError("optimizer state: negative step count");
  if (!state.m.allFinite() || !state.s.allFinite()) throw InputError("optimizer state: a moment is not finite");
  m_ = state.m;
  s_ = state.s;
  steps_ = state.steps;
}

double Optimizer::learning_rate() const {
  return settings_.learning_rate / (1.0 + settings_.decay * static_cast<double>(steps_));
}

void Optimizer::step(Vector& xi, const Vector& gradient) {
  if (gradient.size() != xi.size()) throw InputError("optimizer: gradient and parameters differ in size");
  if (!gradient.allFinite()) throw std::runtime_error("optimizer: the gradient is not finite");
  if (m_.size() != xi.size()) {
    m_ = Vector::Zero(xi.size());
    s_ = Vector::Zero(xi.size());
  }
  Vector g = gradient;
  const double norm = g.norm();
  if (norm > settings_.clip_norm) g *= settings_.clip_norm / norm;
  const double alpha = learning_rate();
  ++steps_;
  if (settings_.kind == OptimizerKind::sgd) {
    m_ = settings_.momentum * m_ + g;
    xi -= alpha * m_;
    return;
  }
  m_ = settings_.beta1 * m_ + (1.0 - settings_.beta1) * g;
  s_ = settings_.beta2 * s_ + (1.0 - settings_.beta2) * g.cwiseAbs2();
  const double k = static_cast<double>(steps_);
  const double c1 = 1.0 - std::pow(settings_.beta1, k), c2 = 1.0 - std::pow(settings_.beta2, k);
  xi -= alpha * ((m_ / c1).array() / ((s_ / c2).array().sqrt() + settings_.epsilon)).matrix();
}

}  // namespace lcprelax::learn
