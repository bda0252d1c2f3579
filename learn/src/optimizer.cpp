// SGD with momentum, Adam and L-BFGS's direction and memory (optimizer.hpp).
#include <lcprelax/learn/optimizer.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <stdexcept>

namespace lcprelax::learn {

const char* to_string(OptimizerKind k) {
  switch (k) {
    case OptimizerKind::sgd: return "sgd";
    case OptimizerKind::adam: return "adam";
    case OptimizerKind::lbfgs: return "lbfgs";
    case OptimizerKind::lm: return "lm";
  }
  return "unknown";
}

OptimizerKind parse_optimizer_kind(const std::string& s) {
  if (s == "sgd") return OptimizerKind::sgd;
  if (s == "adam") return OptimizerKind::adam;
  if (s == "lbfgs") return OptimizerKind::lbfgs;
  if (s == "lm") return OptimizerKind::lm;
  throw InputError("unknown optimizer '" + s + "' (sgd, adam, lbfgs or lm)");
}

std::string OptimizerSettings::validation_error() const {
  if (!(learning_rate > 0.0) || !std::isfinite(learning_rate)) return "learning_rate must be positive and finite";
  if (!(momentum >= 0.0 && momentum < 1.0)) return "momentum must be in [0, 1)";
  if (!(beta1 >= 0.0 && beta1 < 1.0)) return "beta1 must be in [0, 1)";
  if (!(beta2 >= 0.0 && beta2 < 1.0)) return "beta2 must be in [0, 1)";
  if (!(epsilon > 0.0)) return "epsilon must be positive";
  if (!(decay >= 0.0) || !std::isfinite(decay)) return "decay must be non-negative and finite";
  if (!(clip_norm > 0.0)) return "clip_norm must be positive";
  if (memory < 1) return "memory must be ≥ 1";
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
  pair_size_ = 0;
}

void Optimizer::restore(const OptimizerState& state) {
  if (state.m.size() != state.s.size()) throw InputError("optimizer state: moments of different sizes");
  if (settings_.kind == OptimizerKind::lbfgs && state.m.size() > 0 && state.steps <= 0)
    throw InputError("optimizer state: lbfgs pairs without a step");
  if (state.steps < 0) throw InputError("optimizer state: negative step count");
  if (!state.m.allFinite() || !state.s.allFinite()) throw InputError("optimizer state: a moment is not finite");
  if (settings_.kind == OptimizerKind::lm && state.m.size() != 0 &&
      (state.m.size() != 2 || !(state.m(0) > 0.0) || !(state.m(1) >= 2.0)))
    throw InputError("optimizer state: lm damping must be (λ > 0, ν ≥ 2)");
  m_ = state.m;
  s_ = state.s;
  steps_ = state.steps;
  pair_size_ = 0;  // lbfgs: known again from the next gradient
}

double Optimizer::learning_rate() const {
  return settings_.learning_rate / (1.0 + settings_.decay * static_cast<double>(steps_));
}

void Optimizer::step(Vector& xi, const Vector& gradient) {
  if (gradient.size() != xi.size()) throw InputError("optimizer: gradient and parameters differ in size");
  if (!gradient.allFinite()) throw std::runtime_error("optimizer: the gradient is not finite");
  if (settings_.kind == OptimizerKind::lbfgs)
    throw std::logic_error("optimizer: lbfgs steps need a line search (train() runs it)");
  if (settings_.kind == OptimizerKind::lm)
    throw std::logic_error("optimizer: lm steps need residuals and trial evaluations (train() runs them)");
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

bool Optimizer::lm_damping(double& lambda, double& nu) const {
  if (m_.size() != 2) return false;
  lambda = m_(0);
  nu = m_(1);
  return true;
}

void Optimizer::lm_set_damping(double lambda, double nu, bool accepted) {
  if (!(lambda > 0.0) || !std::isfinite(lambda) || !(nu >= 2.0) || !std::isfinite(nu))
    throw std::logic_error("optimizer: lm damping must be (λ > 0, ν ≥ 2) and finite");
  m_ = Vector(2);
  m_ << lambda, nu;
  s_ = Vector::Zero(2);
  if (accepted) ++steps_;
}

int Optimizer::lbfgs_pairs() const {
  return m_.size() == 0 || pair_size_ == 0 ? 0 : static_cast<int>(m_.size() / pair_size_);
}

void Optimizer::lbfgs_forget() {
  m_.resize(0);
  s_.resize(0);
  pair_size_ = 0;
}

// Nocedal & Wright (2006), Algorithm 7.4: q = g; for i newest→oldest: aᵢ = ρᵢ sᵢᵀq,
// q −= aᵢ yᵢ; r = H₀ q; for i oldest→newest: b = ρᵢ yᵢᵀr, r += sᵢ (aᵢ − b); d = −r.
Vector Optimizer::lbfgs_direction(const Vector& gradient) const {
  if (!gradient.allFinite()) throw std::runtime_error("optimizer: the gradient is not finite");
  Vector q = gradient;
  if (m_.size() == 0) return -q;
  if (pair_size_ == 0) pair_size_ = gradient.size();  // after restore()
  if (pair_size_ != gradient.size() || gradient.size() == 0 || m_.size() % pair_size_ != 0)
    throw InputError("optimizer: gradient and stored lbfgs pairs differ in size");
  const int k = lbfgs_pairs();
  const Index n = pair_size_;
  Vector a(k), rho(k);
  for (int i = k - 1; i >= 0; --i) {
    const auto si = m_.segment(i * n, n), yi = s_.segment(i * n, n);
    rho(i) = 1.0 / yi.dot(si);
    a(i) = rho(i) * si.dot(q);
    q -= a(i) * yi;
  }
  const auto sn = m_.segment((k - 1) * n, n), yn = s_.segment((k - 1) * n, n);
  q *= sn.dot(yn) / yn.squaredNorm();
  for (int i = 0; i < k; ++i) {
    const auto si = m_.segment(i * n, n), yi = s_.segment(i * n, n);
    const double b = rho(i) * yi.dot(q);
    q += (a(i) - b) * si;
  }
  return -q;
}

bool Optimizer::lbfgs_accept(const Vector& s, const Vector& y) {
  if (s.size() != y.size()) throw InputError("optimizer: lbfgs pair of different sizes");
  ++steps_;
  const double sy = s.dot(y);
  if (!(sy > 1e-10 * s.norm() * y.norm()) || !s.allFinite() || !y.allFinite()) return false;
  if (m_.size() > 0 && pair_size_ != 0 && pair_size_ != s.size()) lbfgs_forget();
  if (m_.size() > 0 && m_.size() % s.size() != 0) lbfgs_forget();
  pair_size_ = s.size();
  const Index n = pair_size_;
  int k = lbfgs_pairs();
  if (k == settings_.memory) {  // drop the oldest pair
    m_ = Vector(m_.segment(n, (k - 1) * n));
    s_ = Vector(s_.segment(n, (k - 1) * n));
    --k;
  }
  m_.conservativeResize((k + 1) * n);
  s_.conservativeResize((k + 1) * n);
  m_.segment(k * n, n) = s;
  s_.segment(k * n, n) = y;
  return true;
}

}  // namespace lcprelax::learn
