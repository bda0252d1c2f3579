#pragma once
// Shared machinery of the batched bindings (qp_batch.cpp, lcp_batch.cpp, relaxed_lcp.cpp):
// a view of one batched NumPy argument, output arrays, and an OpenMP loop over samples.
//
// Batched arguments: a float64 array of shape (B, k) holds one row per sample; shape (k,)
// or (1, k) is shared by every sample (broadcast). B is the largest leading dimension of
// the batched arguments of one call (1 when none is batched); two batched arguments with
// different B are an InputError naming both. Arrays are read in place when they already are
// C-contiguous float64 (else copied once); they must stay alive while the GIL is released,
// which BatchArgs guarantees by holding them.
//
// The loop: samples k = 0..B−1 are processed with `threads` OpenMP threads (≤ 0: OpenMP's
// default), static schedule; every sample writes only its own rows of the outputs, so the
// outputs do not depend on the thread count. An exception of sample k is kept and the one
// of the lowest k rethrown after the loop with the prefix "sample k: " (InputError stays
// InputError, std::logic_error stays logic_error, anything else becomes runtime_error).
#include "bindings.hpp"

#include <pybind11/stl.h>

#include <exception>
#include <string>
#include <vector>

namespace lcprelax::python {

/// One batched argument after conversion.
struct BatchRows {
  const double* data = nullptr;  ///< nullptr when the argument was None
  Index cols = 0;
  bool batched = false;          ///< one row per sample (else shared)
  bool given() const { return data != nullptr; }
  const double* row(Index k) const { return batched ? data + k * cols : data; }
};

/// Converts the batched arguments of one call and fixes the batch size.
class BatchArgs {
 public:
  /// `obj` is None (→ an empty BatchRows) or array_like of shape (cols,), (1, cols) or
  /// (B, cols); another shape, a non-real dtype or a second B is an InputError / TypeError
  /// naming `name`.
  BatchRows add(const py::object& obj, const std::string& name, Index cols);
  /// The batch size: the common B of the batched arguments, or 1.
  Index batch_size() const { return batch_ > 0 ? batch_ : 1; }

 private:
  std::vector<py::array_t<double, py::array::c_style>> keep_;
  Index batch_ = 0;
  std::string batch_name_;
};

/// A new zero-filled float64 array of shape (rows, cols).
py::array_t<double> batch_array(Index rows, Index cols);

/// Runs body(k) for k < count on `threads` threads (see the header comment). Call it with
/// the GIL released; body must not touch Python objects.
void for_each_sample(Index count, int threads, const std::function<void(Index)>& body);

/// Copies `n` values of a row into `dst` (n may be 0).
void copy_row(const double* src, Index n, double* dst);
/// Copies v into dst when it has n entries, else writes n NaN (a result vector that a
/// failed solve left empty or sized otherwise).
void copy_or_nan(const Vector& v, Index n, double* dst);

}  // namespace lcprelax::python
