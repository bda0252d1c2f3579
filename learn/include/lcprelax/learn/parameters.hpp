#pragma once
// Learnable physical parameters θ and their free (unconstrained) coordinates ξ.
//
// Each parameter has a name (e.g. "mu", "mass", "vertex3.x"), a value in SI units, a
// transform and optional bounds:
//   identity:  θ = s ξ                  (ground height, vertex coordinates, angles; s = scale)
//   log:       θ = exp(ξ), ξ = log θ    (μ, mass, inertia: positivity by construction)
// The optimizer works on ξ; losses return ∂ℓ/∂θ and chain_gradient() maps it to
// ∂ℓ/∂ξ = ∂ℓ/∂θ · dθ/dξ (dθ/dξ = s or θ). The scale s (> 0, default 1, same unit as θ)
// makes an identity parameter's ξ dimensionless, e.g. a vertex coordinate in units of its
// shape's radius, so that one learning rate means the same relative step for every kind. Bounds [lower, upper] apply to θ and are
// enforced by projection after each optimizer step (clamp()); a log parameter must have
// lower > 0 or no lower bound. A parameter with learn = false keeps its value: its gradient
// entry is zeroed by chain_gradient().
#include <lcprelax/sparse/types.hpp>

#include <limits>
#include <string>
#include <vector>

namespace lcprelax::learn {

enum class Transform { identity, log };

struct Parameter {
  std::string name;
  double value = 0.0;  ///< θ, SI units
  Transform transform = Transform::identity;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool learn = true;
  double scale = 1.0;  ///< s of the identity transform (θ = s ξ); ignored by log
};

class ParameterSet {
 public:
  ParameterSet() = default;
  explicit ParameterSet(std::vector<Parameter> parameters);

  /// Appends a parameter; throws InputError on a duplicate name, a non-finite value, a
  /// value outside its bounds, or a log parameter with value ≤ 0.
  void add(const Parameter& p);

  Index size() const { return static_cast<Index>(params_.size()); }
  const Parameter& operator[](Index i) const { return params_[static_cast<std::size_t>(i)]; }
  /// Index of a parameter by name; throws InputError if absent.
  Index index(const std::string& name) const;
  double value(const std::string& name) const { return (*this)[index(name)].value; }
  void set_value(const std::string& name, double v);
  void set_learn(const std::string& name, bool learn);

  /// θ as a vector (parameter order).
  Vector values() const;
  /// Sets θ from a vector (clamped to the bounds).
  void set_values(const Vector& theta);
  /// ξ for the current θ.
  Vector free() const;
  /// Sets θ from ξ, then clamps θ to the bounds.
  void set_free(const Vector& xi);
  /// ∂ℓ/∂ξ from ∂ℓ/∂θ (zero for parameters with learn = false).
  Vector chain_gradient(const Vector& dl_dtheta) const;

 private:
  void check(const Parameter& p) const;
  std::vector<Parameter> params_;
};

}  // namespace lcprelax::learn
