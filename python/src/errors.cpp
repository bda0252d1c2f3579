// Exception mapping of the lcprelax Python module (docs/python.md, "Errors").
//
// lcprelax's C++ conventions (docs/conventions.md): bad input throws lcprelax::InputError,
// calls out of order throw std::logic_error, outcomes are statuses. In Python:
//   lcprelax::InputError                 → lcprelax.InputError (subclass of ValueError),
//                                          same message (it names the field, file, line)
//   std::logic_error (calls out of order,
//     e.g. solve() before setup(),       → lcprelax.UsageError (subclass of RuntimeError)
//     backward() without a solution)
//   std::invalid_argument, domain_error,
//     length_error, out_of_range         → pybind11's defaults (ValueError, IndexError)
//   std::bad_alloc                       → MemoryError (pybind11's default)
//   any other std::exception             → RuntimeError with the same message
// Type errors detected by the bindings themselves (a dense array where a sparse matrix is
// required, a str where a float setting is) are raised directly as TypeError.
#include "bindings.hpp"

#include <lcprelax/core/errors.hpp>

#include <exception>
#include <stdexcept>

namespace lcprelax::python {
namespace {

// The Python exception types, created once per process. The module attribute holds a
// reference; the pointers below are leaked on purpose so that no Python object is released
// by a C++ static destructor after the interpreter has shut down.
PyObject* g_input_error = nullptr;
PyObject* g_usage_error = nullptr;

void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const InputError& e) {
    PyErr_SetString(g_input_error, e.what());
  } catch (const std::invalid_argument&) {
    throw;  // pybind11's default: ValueError
  } catch (const std::domain_error&) {
    throw;  // ValueError
  } catch (const std::length_error&) {
    throw;  // ValueError
  } catch (const std::out_of_range&) {
    throw;  // IndexError
  } catch (const std::logic_error& e) {
    PyErr_SetString(g_usage_error, e.what());
  }
}

}  // namespace

void bind_errors(py::module_& m) {
  g_input_error = py::exception<InputError>(m, "InputError", PyExc_ValueError).release().ptr();
  g_usage_error = py::exception<std::logic_error>(m, "UsageError", PyExc_RuntimeError).release().ptr();
  m.attr("InputError").attr("__doc__") =
      "Invalid input: wrong shapes or sizes, NaN or infinite data, a malformed file, invalid "
      "settings. A ValueError; the message names the field (and file and line for readers).";
  m.attr("UsageError").attr("__doc__") =
      "A call out of order: solve() or update() before setup(), backward() without a solution, "
      "or a solver used from two threads at once. A RuntimeError.";
  py::register_exception_translator(&translate);
}

}  // namespace lcprelax::python
