// Conversions between Python objects and lcprelax's types (bindings.hpp): scipy.sparse →
// SparseMatrix (CSC, 32-bit indices, duplicates summed, explicit zeros kept), array_like →
// Vector (1-D, real, copied as float64), and back (copies), plus the type checks of
// settings values. Shape errors are lcprelax::InputError (→ lcprelax.InputError, a
// ValueError) naming the dimension; type errors are TypeError. Needs the GIL.
#include "bindings.hpp"

#include <lcprelax/core/errors.hpp>

#include <cstdint>
#include <limits>

namespace lcprelax::python {
namespace {

std::string type_name(py::handle obj) { return py::str(py::type::handle_of(obj).attr("__qualname__")); }

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

bool is_text(py::handle obj) { return PyUnicode_Check(obj.ptr()) || PyBytes_Check(obj.ptr()); }

bool is_scipy_sparse(py::handle obj) {
  return py::module_::import("scipy.sparse").attr("issparse")(obj).cast<bool>();
}

/// numpy.asarray(obj) with a real dtype (allowed kinds), else TypeError naming `name`.
py::array real_array(py::handle obj, const std::string& name, const std::string& kinds) {
  if (obj.is_none() || is_text(obj) || is_scipy_sparse(obj))
    throw py::type_error(name + " must be a 1-D NumPy array (or array_like) of numbers, got " + type_name(obj));
  py::array a;
  try {
    a = py::module_::import("numpy").attr("asarray")(obj);
  } catch (py::error_already_set& e) {
    throw py::type_error(name + " cannot be converted to a NumPy array: " + std::string(e.what()));
  }
  const char kind = a.dtype().kind();
  if (kinds.find(kind) == std::string::npos)
    throw py::type_error(name + " must hold real numbers, got dtype " + std::string(py::str(a.dtype())));
  return a;
}

Index checked_index(long long v, const std::string& what) {
  if (v < 0 || v > std::numeric_limits<Index>::max())
    throw InputError(what + " = " + std::to_string(v) + " is outside [0, 2^31 - 1]");
  return static_cast<Index>(v);
}

}  // namespace

SparseMatrix to_sparse(py::handle obj, const std::string& name) {
  if (!is_scipy_sparse(obj)) {
    std::string hint = py::isinstance<py::array>(obj) ? " (wrap a dense array with scipy.sparse.csc_matrix(...))" : "";
    throw py::type_error(name + " must be a scipy.sparse matrix or array, got " + type_name(obj) + hint);
  }
  py::object m = obj.attr("tocsc")();
  if (!m.attr("has_canonical_format").cast<bool>()) {
    m = m.attr("copy")();
    m.attr("sum_duplicates")();  // also sorts the row indices of each column
  }
  const char kind = py::dtype::from_args(m.attr("dtype")).kind();
  if (std::string("biuf").find(kind) == std::string::npos)
    throw py::type_error(name + " must hold real numbers, got dtype " + std::string(py::str(m.attr("dtype"))));
  const py::tuple shape = m.attr("shape");
  const Index rows = checked_index(shape[0].cast<long long>(), name + " rows");
  const Index cols = checked_index(shape[1].cast<long long>(), name + " columns");
  using Ints = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
  using Reals = py::array_t<double, py::array::c_style | py::array::forcecast>;
  const Ints indptr = Ints::ensure(m.attr("indptr"));
  const Ints indices = Ints::ensure(m.attr("indices"));
  const Reals data = Reals::ensure(m.attr("data"));
  if (!indptr || !indices || !data) throw py::type_error(name + ": cannot read its CSC arrays");
  if (indptr.size() != static_cast<py::ssize_t>(cols) + 1)
    throw InputError(name + ": CSC indptr has length " + std::to_string(indptr.size()) + ", expected " +
                     std::to_string(cols + 1));
  const std::int64_t* p = indptr.data();
  const std::int64_t nnz = p[cols];
  if (p[0] != 0 || nnz > indices.size() || nnz > data.size() || nnz > std::numeric_limits<Index>::max())
    throw InputError(name + ": inconsistent CSC arrays (indptr, indices, data)");
  SparseMatrix M(rows, cols);
  M.resizeNonZeros(static_cast<Index>(nnz));
  for (Index j = 0; j <= cols; ++j) {
    if (j > 0 && p[j] < p[j - 1]) throw InputError(name + ": CSC indptr is not nondecreasing");
    M.outerIndexPtr()[j] = static_cast<Index>(p[j]);
  }
  const std::int64_t* idx = indices.data();
  const double* val = data.data();
  for (std::int64_t k = 0; k < nnz; ++k) {
    if (idx[k] < 0 || idx[k] >= rows)
      throw InputError(name + ": row index " + std::to_string(idx[k]) + " outside [0, " + std::to_string(rows) + ")");
    M.innerIndexPtr()[k] = static_cast<Index>(idx[k]);
    M.valuePtr()[k] = val[k];
  }
  return M;
}

Vector to_vector(py::handle obj, const std::string& name, Index expected, const std::string& what) {
  py::array a = real_array(obj, name, "iuf");
  if (a.ndim() != 1) throw InputError(name + " must be 1-D, got shape " + shape_text(a));
  if (expected >= 0 && a.shape(0) != expected)
    throw InputError(name + " has length " + std::to_string(a.shape(0)) + ", expected " + std::to_string(expected) +
                     (what.empty() ? "" : " (" + what + ")"));
  checked_index(a.shape(0), name + " length");
  using Reals = py::array_t<double, py::array::c_style | py::array::forcecast>;
  const Reals r = Reals::ensure(a);
  Vector v(static_cast<Index>(r.size()));
  for (Index i = 0; i < v.size(); ++i) v(i) = r.data()[i];
  return v;
}

std::vector<bool> to_bool_vector(py::handle obj, const std::string& name) {
  py::array a = real_array(obj, name, "b");
  if (a.ndim() != 1) throw InputError(name + " must be 1-D, got shape " + shape_text(a));
  using Bools = py::array_t<bool, py::array::c_style | py::array::forcecast>;
  const Bools r = Bools::ensure(a);
  return std::vector<bool>(r.data(), r.data() + r.size());
}

py::array_t<double> to_numpy(const Vector& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  double* out = a.mutable_data();
  for (Index i = 0; i < v.size(); ++i) out[i] = v(i);
  return a;
}

py::object to_scipy(const SparseMatrix& M) {
  SparseMatrix c = M;
  c.makeCompressed();
  const Index nnz = static_cast<Index>(c.nonZeros());
  py::array_t<double> data(nnz);
  py::array_t<std::int32_t> indices(nnz), indptr(static_cast<py::ssize_t>(c.cols()) + 1);
  for (Index k = 0; k < nnz; ++k) {
    data.mutable_data()[k] = c.valuePtr()[k];
    indices.mutable_data()[k] = c.innerIndexPtr()[k];
  }
  for (Index j = 0; j <= c.cols(); ++j) indptr.mutable_data()[j] = c.outerIndexPtr()[j];
  return py::module_::import("scipy.sparse")
      .attr("csc_matrix")(py::make_tuple(data, indices, indptr), py::arg("shape") = py::make_tuple(c.rows(), c.cols()));
}

double setting_double(py::handle v, const std::string& field) {
  const bool number = (PyFloat_Check(v.ptr()) || PyLong_Check(v.ptr()) || PyIndex_Check(v.ptr()) ||
                       py::isinstance(v, py::module_::import("numpy").attr("floating"))) &&
                      !PyBool_Check(v.ptr());
  if (!number) throw py::type_error(field + " must be a float, got " + type_name(v));
  return py::float_(py::reinterpret_borrow<py::object>(v)).cast<double>();
}

long long setting_int(py::handle v, const std::string& field) {
  if (PyBool_Check(v.ptr()) || !PyIndex_Check(v.ptr()))
    throw py::type_error(field + " must be an int, got " + type_name(v));
  PyObject* index = PyNumber_Index(v.ptr());
  if (!index) throw py::error_already_set();
  const py::int_ i = py::reinterpret_steal<py::int_>(index);
  int overflow = 0;
  const long long x = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
  if (overflow) throw InputError(field + " is out of range");
  return x;
}

bool setting_bool(py::handle v, const std::string& field) {
  if (PyBool_Check(v.ptr())) return v.ptr() == Py_True;
  if (py::isinstance(v, py::module_::import("numpy").attr("bool_"))) return py::bool_(v.attr("item")()).cast<bool>();
  throw py::type_error(field + " must be a bool, got " + type_name(v));
}

std::string setting_string(py::handle v, const std::string& field) {
  if (!PyUnicode_Check(v.ptr())) throw py::type_error(field + " must be a str, got " + type_name(v));
  return v.cast<std::string>();
}

}  // namespace lcprelax::python
