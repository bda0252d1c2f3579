#pragma once
// The Python view of a learn::Objective (learn/trainer.hpp): a loss over the samples of a
// dataset and its gradient with respect to the LEARNED parameters θ, evaluated in parallel
// with learn::evaluate_batch (fixed-order sums: the same bits for every thread count).
//
// Conventions (docs/python.md "Learning"):
// - θ is a 1-D array of the learned parameters' values in SI units, in the order of
//   `parameter_names` (the objective's full ParameterSet may hold more, held at their values);
// - evaluate(theta, samples=None, reduction='mean') returns (loss, gradient): the mean (or
//   sum) over the samples of ℓᵢ(θ) and of ∂ℓᵢ/∂θ (∂ with respect to θ itself, not to the
//   optimizer's free coordinates); `samples` selects a mini-batch by index;
// - a θ outside a parameter's bounds or not finite is an InputError naming the parameter; a
//   sample whose solve fails makes evaluate() raise RuntimeError with the first failure's
//   message (no sample is silently dropped from the loss).
// The GIL is released while the samples are evaluated; one objective serves one call at a
// time (a second concurrent call raises UsageError).
#include "bindings.hpp"

#include <lcprelax/learn/parameters.hpp>
#include <lcprelax/learn/relaxed_lcp.hpp>
#include <lcprelax/learn/scene_params.hpp>
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace lcprelax::python {

class PyObjective {
 public:
  virtual ~PyObjective() = default;

  /// (loss, gradient) at θ (see above).
  py::tuple evaluate(const py::object& theta, const py::object& samples, const std::string& reduction);
  std::vector<std::string> parameter_names() const;
  /// Lower and upper bounds of the learned parameters (SI units).
  py::array_t<double> lower_bounds() const;
  py::array_t<double> upper_bounds() const;
  Index num_samples() const { return objective_->num_samples(); }
  int threads() const { return threads_; }
  const std::string& method() const { return method_; }

 protected:
  /// `base` is the full parameter set (its values fill the held parameters); `learned`
  /// lists the indices of base that θ sets, in θ's order. `owned` keeps alive what the
  /// objective refers to (destroyed after the objective).
  void init(std::string method, learn::ParameterSet base, std::vector<Index> learned, int threads,
            std::shared_ptr<void> owned, std::unique_ptr<learn::Objective> objective);
  const learn::ParameterSet& base() const { return base_; }
  const std::vector<Index>& learned() const { return learned_; }
  /// The learned parameters' values of `set` (same layout as base()), in θ's order.
  py::array_t<double> learned_values(const learn::ParameterSet& set) const;
  learn::Objective& objective() { return *objective_; }

 public:
  /// Held (Busy) by every call that uses the objective.
  std::mutex& mutex() { return mutex_; }

 private:
  learn::ParameterSet with_values(const Vector& theta) const;

  std::string method_;
  learn::ParameterSet base_;
  std::vector<Index> learned_;
  int threads_ = 0;
  std::shared_ptr<void> owned_;                   // declared before objective_: outlives it
  std::unique_ptr<learn::Objective> objective_;
  std::mutex mutex_;
};

/// The `learn` keyword (a comma-separated str or a list of str) as the scene path's flags;
/// TypeError on another type, InputError "learn: ..." naming an unknown kind.
learn::SceneLearnFlags parse_learn_kinds(const py::object& learn);
/// The indices of the parameters of `set` marked learned; InputError when there are none.
std::vector<Index> learned_indices(const learn::ParameterSet& set);
/// InputError unless 0 ≤ fraction < 1 and seed ≥ 0 (perturbed_values' arguments).
void check_perturbation(double fraction, long long seed);
/// Applies the `qp` keyword (a dict of QpSettings, or None) to the relaxed and convex losses.
void apply_loss_qp_settings(learn::SceneLossSettings& settings, const py::object& qp);
/// Registers lcprelax.Objective (the base class of BlockObjective, SceneObjective).
void bind_objective_base(py::module_& m);
/// The keyword table of learn::RelaxedLcpSettings (a1..a5, soft flags, max_dissipation, ...).
const std::vector<SettingField<learn::RelaxedLcpSettings>>& relaxed_loss_fields();
/// Applies a dict of settings (None: nothing) through a keyword table.
template <class S>
void apply_settings_dict(S& settings, const std::vector<SettingField<S>>& fields, const py::object& dict,
                         const std::string& owner) {
  if (dict.is_none()) return;
  if (!py::isinstance<py::dict>(dict)) throw py::type_error(owner + " must be a dict of settings");
  py::kwargs kw;
  for (auto item : py::reinterpret_borrow<py::dict>(dict)) kw[item.first] = item.second;
  apply_settings(settings, fields, kw, owner);
}

}  // namespace lcprelax::python
