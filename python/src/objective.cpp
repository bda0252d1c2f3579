// lcprelax.Objective: the shared Python view of the learning objectives (objective.hpp
// states the conventions), and the keyword table of the relaxed loss's settings.
#include "objective.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/batch.hpp>

#include <pybind11/stl.h>

#include <stdexcept>
#include <utility>

namespace lcprelax::python {

const std::vector<SettingField<learn::RelaxedLcpSettings>>& relaxed_loss_fields() {
  using S = learn::RelaxedLcpSettings;
  static const std::vector<SettingField<S>> fields = {
      double_field("a1", &S::a1), double_field("a2", &S::a2), double_field("a3", &S::a3),
      double_field("a4", &S::a4), double_field("a5", &S::a5),
      bool_field("soft_nonnegativity", &S::soft_nonnegativity), bool_field("soft_lambdas", &S::soft_lambdas),
      bool_field("l1_softness", &S::l1_softness), double_field("regularization", &S::regularization),
      SettingField<S>{"max_dissipation",
                      [](S& s, py::handle v) {
                        s.max_dissipation = learn::parse_max_dissipation(setting_string(v, "max_dissipation"));
                      },
                      [](const S& s) { return py::object(py::str(learn::to_string(s.max_dissipation))); }},
      SettingField<S>{"nonconvex",
                      [](S& s, py::handle v) {
                        const std::string t = setting_string(v, "nonconvex");
                        if (t != "report" && t != "shift")
                          throw InputError("nonconvex = '" + t + "' is not one of: report, shift");
                        s.nonconvex = t == "shift" ? learn::NonconvexPolicy::shift : learn::NonconvexPolicy::report;
                      },
                      [](const S& s) {
                        return py::object(py::str(s.nonconvex == learn::NonconvexPolicy::shift ? "shift" : "report"));
                      }}};
  return fields;
}

namespace {

std::string learn_kinds(const py::object& learn) {
  if (PyUnicode_Check(learn.ptr())) return learn.cast<std::string>();
  if (!py::isinstance<py::list>(learn) && !py::isinstance<py::tuple>(learn))
    throw py::type_error("learn must be a str ('mu,mass') or a list of str");
  std::string out;
  for (auto item : learn) {
    if (!PyUnicode_Check(item.ptr())) throw py::type_error("learn must be a list of str");
    out += (out.empty() ? "" : ",") + item.cast<std::string>();
  }
  return out;
}

}  // namespace

learn::SceneLearnFlags parse_learn_kinds(const py::object& learn) {
  try {
    return learn::parse_scene_learn_flags(learn_kinds(learn));
  } catch (const InputError& e) {
    std::string msg = e.what();
    if (msg.rfind("--learn: ", 0) == 0) msg = msg.substr(9);  // the CLI's option name
    throw InputError("learn: " + msg);
  }
}

std::vector<Index> learned_indices(const learn::ParameterSet& set) {
  std::vector<Index> learned;
  for (Index k = 0; k < set.size(); ++k)
    if (set[k].learn) learned.push_back(k);
  if (learned.empty()) throw InputError("learn: no parameter of the chosen kinds");
  return learned;
}

void check_perturbation(double fraction, long long seed) {
  if (!(fraction >= 0 && fraction < 1)) throw InputError("fraction: must be in [0, 1)");
  if (seed < 0) throw InputError("seed: must be >= 0");
}

void apply_loss_qp_settings(learn::SceneLossSettings& settings, const py::object& qp) {
  apply_settings_dict(settings.relaxed.qp, qp_fields(), qp, "qp");
  apply_settings_dict(settings.convex.qp, qp_fields(), qp, "qp");
}

py::array_t<double> PyObjective::learned_values(const learn::ParameterSet& set) const {
  Vector v(static_cast<Index>(learned_.size()));
  for (std::size_t i = 0; i < learned_.size(); ++i) v(static_cast<Index>(i)) = set[learned_[i]].value;
  return to_numpy(v);
}

void PyObjective::init(std::string method, learn::ParameterSet base, std::vector<Index> learned, int threads,
                       std::shared_ptr<void> owned, std::unique_ptr<learn::Objective> objective) {
  if (threads < 0) throw InputError("threads: must be >= 0 (0: all cores)");
  method_ = std::move(method);
  base_ = std::move(base);
  learned_ = std::move(learned);
  threads_ = threads;
  owned_ = std::move(owned);
  objective_ = std::move(objective);
}

std::vector<std::string> PyObjective::parameter_names() const {
  std::vector<std::string> names;
  for (Index k : learned_) names.push_back(base_[k].name);
  return names;
}

py::array_t<double> PyObjective::lower_bounds() const {
  Vector v(static_cast<Index>(learned_.size()));
  for (std::size_t i = 0; i < learned_.size(); ++i) v(static_cast<Index>(i)) = base_[learned_[i]].lower;
  return to_numpy(v);
}

py::array_t<double> PyObjective::upper_bounds() const {
  Vector v(static_cast<Index>(learned_.size()));
  for (std::size_t i = 0; i < learned_.size(); ++i) v(static_cast<Index>(i)) = base_[learned_[i]].upper;
  return to_numpy(v);
}

learn::ParameterSet PyObjective::with_values(const Vector& theta) const {
  std::vector<learn::Parameter> params;
  for (Index k = 0; k < base_.size(); ++k) params.push_back(base_[k]);
  for (std::size_t i = 0; i < learned_.size(); ++i) params[static_cast<std::size_t>(learned_[i])].value = theta(static_cast<Index>(i));
  learn::ParameterSet out;
  for (const learn::Parameter& p : params) out.add(p);  // InputError: not finite, outside the bounds
  return out;
}

py::tuple PyObjective::evaluate(const py::object& theta, const py::object& samples, const std::string& reduction) {
  if (reduction != "mean" && reduction != "sum")
    throw InputError("reduction = '" + reduction + "' is not one of: mean, sum");
  const Vector t = to_vector(theta, "theta", static_cast<Index>(learned_.size()), "number of learned parameters");
  const learn::ParameterSet set = with_values(t);
  const Index n = objective_->num_samples();
  std::vector<Index> batch;
  if (samples.is_none()) {
    for (Index i = 0; i < n; ++i) batch.push_back(i);
  } else {
    const Vector s = to_vector(samples, "samples");
    for (Index k = 0; k < s.size(); ++k) {
      if (!(s(k) >= 0 && s(k) < n) || s(k) != static_cast<double>(static_cast<Index>(s(k))))
        throw InputError("samples[" + std::to_string(k) + "] is not a sample index in [0, " + std::to_string(n) + ")");
      batch.push_back(static_cast<Index>(s(k)));
    }
    if (batch.empty()) throw InputError("samples is empty");
  }
  Busy busy(mutex_, "Objective");
  learn::BatchResult r;
  {
    py::gil_scoped_release nogil;
    const int threads = learn::resolve_threads(threads_);
    objective_->prepare(set, threads);
    r = learn::evaluate_batch(batch, set.size(), threads,
                              [&](Index i, int thread) { return objective_->evaluate(i, set, thread); });
  }
  if (r.failed > 0)
    throw std::runtime_error(std::to_string(r.failed) + " of " + std::to_string(batch.size()) +
                             " samples failed to evaluate; first: " + r.first_failure);
  const double scale = reduction == "mean" ? 1.0 / static_cast<double>(batch.size()) : 1.0;
  Vector g(static_cast<Index>(learned_.size()));
  for (std::size_t i = 0; i < learned_.size(); ++i) g(static_cast<Index>(i)) = scale * r.gradient(learned_[i]);
  return py::make_tuple(scale * r.loss, to_numpy(g));
}

void bind_objective_base(py::module_& m) {
  py::class_<PyObjective>(m, "Objective",
                          "A learning loss over a dataset and its gradient in the learned parameters\n"
                          "(learn/trainer.hpp; docs/python.md 'Learning'). Made by BlockObjective or SceneObjective.")
      .def("evaluate", &PyObjective::evaluate, py::arg("theta"), py::arg("samples") = py::none(),
           py::arg("reduction") = "mean",
           "(loss, gradient) at theta (1-D, the learned parameters in parameter_names order, SI units):\n"
           "the mean (reduction='sum': the sum) over the samples (all, or the given indices) of the\n"
           "per-sample loss and of its gradient d loss / d theta. RuntimeError if a sample fails.")
      .def_property_readonly("parameter_names", &PyObjective::parameter_names, "names of the learned parameters (theta's order)")
      .def_property_readonly("lower_bounds", &PyObjective::lower_bounds, "lower bounds of theta")
      .def_property_readonly("upper_bounds", &PyObjective::upper_bounds, "upper bounds of theta")
      .def_property_readonly("num_samples", &PyObjective::num_samples)
      .def_property_readonly("threads", &PyObjective::threads, "OpenMP threads (0: all cores)")
      .def_property_readonly("method", &PyObjective::method, "'hard', 'relaxed' or 'convex'")
      .def("__len__", &PyObjective::num_samples);
}

}  // namespace lcprelax::python
