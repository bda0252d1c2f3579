// Learnable parameters and their free coordinates (parameters.hpp).
#include <lcprelax/learn/parameters.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>

namespace lcprelax::learn {

ParameterSet::ParameterSet(std::vector<Parameter> parameters) {
  for (const Parameter& p : parameters) add(p);
}

void ParameterSet::check(const Parameter& p) const {
  const std::string where = "parameter '" + p.name + "': ";
  if (p.name.empty()) throw InputError("parameter with an empty name");
  if (!std::isfinite(p.value)) throw InputError(where + "value is not finite");
  if (std::isnan(p.lower) || std::isnan(p.upper) || p.lower > p.upper)
    throw InputError(where + "bounds are NaN or lower > upper");
  if (p.value < p.lower || p.value > p.upper) throw InputError(where + "value outside its bounds");
  if (p.transform == Transform::log && p.value <= 0.0)
    throw InputError(where + "a log-transformed parameter must be positive");
}

void ParameterSet::add(const Parameter& p) {
  check(p);
  for (const Parameter& q : params_)
    if (q.name == p.name) throw InputError("parameter '" + p.name + "' given twice");
  params_.push_back(p);
}

Index ParameterSet::index(const std::string& name) const {
  for (std::size_t i = 0; i < params_.size(); ++i)
    if (params_[i].name == name) return static_cast<Index>(i);
  throw InputError("no parameter named '" + name + "'");
}

void ParameterSet::set_value(const std::string& name, double v) {
  Parameter p = params_[static_cast<std::size_t>(index(name))];
  p.value = v;
  check(p);
  params_[static_cast<std::size_t>(index(name))] = p;
}

void ParameterSet::set_learn(const std::string& name, bool learn) {
  params_[static_cast<std::size_t>(index(name))].learn = learn;
}

Vector ParameterSet::values() const {
  Vector theta(size());
  for (Index i = 0; i < size(); ++i) theta(i) = (*this)[i].value;
  return theta;
}

void ParameterSet::set_values(const Vector& theta) {
  if (theta.size() != size()) throw InputError("parameter vector has the wrong length");
  for (Index i = 0; i < size(); ++i) {
    Parameter& p = params_[static_cast<std::size_t>(i)];
    if (!std::isfinite(theta(i))) throw InputError("parameter '" + p.name + "': value is not finite");
    double v = std::clamp(theta(i), p.lower, p.upper);
    if (p.transform == Transform::log) v = std::max(v, std::numeric_limits<double>::min());
    p.value = v;
  }
}

Vector ParameterSet::free() const {
  Vector xi(size());
  for (Index i = 0; i < size(); ++i) {
    const Parameter& p = (*this)[i];
    xi(i) = p.transform == Transform::log ? std::log(p.value) : p.value / p.scale;
  }
  return xi;
}

void ParameterSet::set_free(const Vector& xi) {
  if (xi.size() != size()) throw InputError("free parameter vector has the wrong length");
  Vector theta(size());
  for (Index i = 0; i < size(); ++i)
    theta(i) = (*this)[i].transform == Transform::log ? std::exp(xi(i)) : (*this)[i].scale * xi(i);
  set_values(theta);
}

Vector ParameterSet::chain_gradient(const Vector& dl_dtheta) const {
  if (dl_dtheta.size() != size()) throw InputError("gradient has the wrong length");
  Vector g(size());
  for (Index i = 0; i < size(); ++i) {
    const Parameter& p = (*this)[i];
    g(i) = !p.learn ? 0.0 : p.transform == Transform::log ? dl_dtheta(i) * p.value : dl_dtheta(i) * p.scale;
  }
  return g;
}

}  // namespace lcprelax::learn
