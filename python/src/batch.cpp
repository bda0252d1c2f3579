// Batched arguments, output arrays and the OpenMP loop over samples (batch.hpp).
#include "batch.hpp"

#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <limits>
#include <stdexcept>

#ifdef LCPRELAX_HAS_OPENMP
#include <omp.h>
#endif

namespace lcprelax::python {
namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

}  // namespace

BatchRows BatchArgs::add(const py::object& obj, const std::string& name, Index cols) {
  if (obj.is_none()) return {};
  if (PyUnicode_Check(obj.ptr()) || PyBytes_Check(obj.ptr()))
    throw py::type_error(name + " must be a float array, got str");
  py::array a;
  try {
    a = py::module_::import("numpy").attr("asarray")(obj);
  } catch (py::error_already_set& e) {
    throw py::type_error(name + " cannot be converted to a NumPy array: " + std::string(e.what()));
  }
  if (std::string("iuf").find(a.dtype().kind()) == std::string::npos)
    throw py::type_error(name + " must hold real numbers, got dtype " + std::string(py::str(a.dtype())));
  const std::string expected = "(" + std::to_string(cols) + ",) or (B, " + std::to_string(cols) + ")";
  if (a.ndim() < 1 || a.ndim() > 2 || a.shape(a.ndim() - 1) != cols)
    throw InputError(name + " has shape " + shape_text(a) + ", expected " + expected);
  BatchRows rows;
  rows.cols = cols;
  if (a.ndim() == 2 && a.shape(0) != 1) {
    const Index b = static_cast<Index>(a.shape(0));
    if (b == 0) throw InputError(name + " has an empty batch dimension (shape " + shape_text(a) + ")");
    if (batch_ > 0 && b != batch_)
      throw InputError(name + " has batch size " + std::to_string(b) + " but " + batch_name_ + " has " +
                       std::to_string(batch_));
    batch_ = b, batch_name_ = name;
    rows.batched = true;
  }
  keep_.push_back(py::array_t<double, py::array::c_style>::ensure(a));
  if (!keep_.back()) throw py::type_error(name + ": cannot be read as a float64 array");
  rows.data = keep_.back().data();
  return rows;
}

py::array_t<double> batch_array(Index rows, Index cols) {
  py::array_t<double> a({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
  std::fill(a.mutable_data(), a.mutable_data() + a.size(), 0.0);
  return a;
}

void copy_row(const double* src, Index n, double* dst) {
  if (n > 0) std::copy(src, src + n, dst);
}

void copy_or_nan(const Vector& v, Index n, double* dst) {
  if (v.size() == n)
    copy_row(v.data(), n, dst);
  else
    std::fill(dst, dst + n, std::numeric_limits<double>::quiet_NaN());
}

void for_each_sample(Index count, int threads, const std::function<void(Index)>& body) {
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(count));
  auto guarded = [&](Index k) {
    try {
      body(k);
    } catch (...) {
      errors[static_cast<std::size_t>(k)] = std::current_exception();
    }
  };
#ifdef LCPRELAX_HAS_OPENMP
  // No more threads than samples (waking an idle thread costs more than a small sample).
  const int nt = static_cast<int>(std::min<Index>(threads > 0 ? threads : omp_get_max_threads(), std::max<Index>(count, 1)));
#pragma omp parallel for num_threads(nt) schedule(dynamic, 16)
  for (Index k = 0; k < count; ++k) guarded(k);
#else
  (void)threads;
  for (Index k = 0; k < count; ++k) guarded(k);
#endif
  for (Index k = 0; k < count; ++k) {
    if (!errors[static_cast<std::size_t>(k)]) continue;
    const std::string where = "sample " + std::to_string(k) + ": ";
    try {
      std::rethrow_exception(errors[static_cast<std::size_t>(k)]);
    } catch (const InputError& e) {
      throw InputError(where + e.what());
    } catch (const std::logic_error& e) {
      throw std::logic_error(where + e.what());
    } catch (const std::exception& e) {
      throw std::runtime_error(where + e.what());
    }
  }
}

}  // namespace lcprelax::python
