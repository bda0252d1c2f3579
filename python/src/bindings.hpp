#pragma once
// Shared declarations of the lcprelax Python module (_lcprelax): the per-concept binding
// functions and the conversions between NumPy / scipy.sparse and lcprelax's Eigen types.
//
// Conversion rules (docs/python.md):
// - matrices: any scipy.sparse matrix or array (converted to CSC, duplicates summed,
//   explicit zeros kept as part of the pattern); a dense numpy.ndarray is rejected with a
//   TypeError that says how to wrap it; real dtypes only (bool, int, float), copied as float64;
// - vectors: anything numpy.asarray turns into a 1-D real array, copied as float64;
// - a wrong shape is lcprelax.InputError (a ValueError) naming the dimension, a wrong type
//   is TypeError; NaN / Inf are reported by the C++ validation as InputError.
// Settings: keyword arguments map one to one onto the fields of a C++ ...Settings struct
// through a table of SettingField (unknown name or wrong Python type: TypeError naming it).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/sparse/types.hpp>

#include <pybind11/pybind11.h>
#include <pybind11/numpy.h>

#include <functional>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace lcprelax::python {

namespace py = pybind11;

void bind_errors(py::module_& m);
void bind_qp(py::module_& m);
void bind_lcp(py::module_& m);
void bind_io(py::module_& m);
void bind_qp_batch(py::module_& m);
void bind_lcp_batch(py::module_& m);
void bind_relaxed_lcp(py::module_& m);
void bind_simulator(py::module_& m);
void bind_scenes(py::module_& m);
void bind_learning(py::module_& m);
void bind_scene_learning(py::module_& m);
void bind_polygon_learning(py::module_& m);

/// Takes a solver for one call or fails: a solver busy in another thread is a UsageError
/// (std::logic_error "<solver> is in use by another thread").
struct Busy {
  std::unique_lock<std::mutex> lock;
  Busy(std::mutex& m, const char* solver) : lock(m, std::try_to_lock) {
    if (!lock.owns_lock()) throw std::logic_error(std::string(solver) + " is in use by another thread");
  }
};

/// scipy.sparse (any format) → CSC SparseMatrix; `name` is used in error messages.
SparseMatrix to_sparse(py::handle obj, const std::string& name);
/// 1-D real array_like → Vector; expected < 0 accepts any length, otherwise a different
/// length is an InputError "name has length k, expected <expected> (<what>)".
Vector to_vector(py::handle obj, const std::string& name, Index expected = -1, const std::string& what = "");
/// 1-D bool array_like → std::vector<bool>.
std::vector<bool> to_bool_vector(py::handle obj, const std::string& name);

/// Copies: a new float64 NumPy array and a new scipy.sparse.csc_matrix.
py::array_t<double> to_numpy(const Vector& v);
py::object to_scipy(const SparseMatrix& M);

/// A QpProblem as a dict of copies with the keyword names of QpSolver.setup (P upper
/// triangle, q, A, b, G, l, u, xl, xu, r).
py::dict problem_dict(const QpProblem& p);

/// Python scalar → C++ setting value, TypeError naming the field on a wrong type.
double setting_double(py::handle v, const std::string& field);
long long setting_int(py::handle v, const std::string& field);
bool setting_bool(py::handle v, const std::string& field);
std::string setting_string(py::handle v, const std::string& field);

/// One keyword argument of a settings struct S: how to set it from Python and read it back.
template <class S>
struct SettingField {
  std::string name;
  std::function<void(S&, py::handle)> set;
  std::function<py::object(const S&)> get;
};

/// Applies kwargs to `settings` through `fields`; an unknown keyword is a TypeError naming
/// it and listing the valid ones (`owner` names the callable, e.g. "QpSolver()").
template <class S>
void apply_settings(S& settings, const std::vector<SettingField<S>>& fields, const py::kwargs& kwargs,
                    const std::string& owner) {
  for (auto item : kwargs) {
    const std::string key = py::str(item.first);
    const SettingField<S>* found = nullptr;
    for (const auto& f : fields)
      if (f.name == key) found = &f;
    if (!found) {
      std::string valid;
      for (const auto& f : fields) valid += (valid.empty() ? "" : ", ") + f.name;
      throw py::type_error(owner + " got an unexpected keyword argument '" + key + "' (valid: " + valid + ")");
    }
    found->set(settings, item.second);
  }
}

/// The settings as a dict {field: value}.
template <class S>
py::dict settings_dict(const S& settings, const std::vector<SettingField<S>>& fields) {
  py::dict d;
  for (const auto& f : fields) d[py::str(f.name)] = f.get(settings);
  return d;
}

/// Field builders for the common member types.
template <class S>
SettingField<S> double_field(const char* name, double S::*member) {
  return {name, [=](S& s, py::handle v) { s.*member = setting_double(v, name); },
          [=](const S& s) { return py::object(py::float_(s.*member)); }};
}
template <class S, class Int>
SettingField<S> int_field(const char* name, Int S::*member) {
  return {name,
          [=](S& s, py::handle v) {
            const long long x = setting_int(v, name);
            if (x < static_cast<long long>(std::numeric_limits<Int>::min()) ||
                x > static_cast<long long>(std::numeric_limits<Int>::max()))
              throw InputError(std::string(name) + " = " + std::to_string(x) + " is out of range");
            s.*member = static_cast<Int>(x);
          },
          [=](const S& s) { return py::object(py::int_(static_cast<long long>(s.*member))); }};
}
template <class S>
SettingField<S> bool_field(const char* name, bool S::*member) {
  return {name, [=](S& s, py::handle v) { s.*member = setting_bool(v, name); },
          [=](const S& s) { return py::object(py::bool_(s.*member)); }};
}
/// An enum setting given by its to_string() name (e.g. kkt_backend="cholmod").
template <class S, class E>
SettingField<S> enum_field(const char* name, E S::*member, std::vector<E> values) {
  return {name,
          [=](S& s, py::handle v) {
            const std::string text = setting_string(v, name);
            std::string valid;
            for (E e : values) {
              if (text == to_string(e)) {
                s.*member = e;
                return;
              }
              valid += (valid.empty() ? "" : ", ") + std::string(to_string(e));
            }
            throw InputError(std::string(name) + " = '" + text + "' is not one of: " + valid);
          },
          [=](const S& s) { return py::object(py::str(to_string(s.*member))); }};
}

/// The keyword tables of QpSettings (qp.cpp) and LemkeSettings (lcp.cpp), shared by the
/// single-problem and the batched bindings.
const std::vector<SettingField<QpSettings>>& qp_fields();
const std::vector<SettingField<LemkeSettings>>& lemke_fields();

}  // namespace lcprelax::python
