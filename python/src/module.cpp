// Entry point of the compiled module lcprelax._lcprelax (imported by lcprelax/__init__.py).
// Each concept is bound in its own file: errors.cpp (exception mapping), qp.cpp (QpSolver),
// lcp.cpp (LemkeSolver), io.cpp (QPS and Siconos readers), qp_batch.cpp,
// lcp_batch.cpp, relaxed_lcp.cpp (batched solves in parallel, the engines of lcprelax.torch);
// simulator.cpp, scenes.cpp (Simulator, scene generators), objective.cpp, learning.cpp,
// scene_learning.cpp (learning losses with gradients);
// convert.cpp and batch.cpp hold the NumPy / scipy.sparse conversions they share. Conventions: docs/python.md.
#include "bindings.hpp"

PYBIND11_MODULE(_lcprelax, m) {
  m.doc() = "lcprelax: sparse interior-point QP with adjoint backward pass, Lemke LCP, readers";
  // NumPy and scipy.sparse are needed by every conversion: fail at import, not at first use.
  pybind11::module_::import("numpy");
  pybind11::module_::import("scipy.sparse");
  lcprelax::python::bind_errors(m);
  lcprelax::python::bind_qp(m);
  lcprelax::python::bind_lcp(m);
  lcprelax::python::bind_io(m);
  lcprelax::python::bind_qp_batch(m);
  lcprelax::python::bind_lcp_batch(m);
  lcprelax::python::bind_relaxed_lcp(m);
  lcprelax::python::bind_simulator(m);
  lcprelax::python::bind_scenes(m);
  lcprelax::python::bind_learning(m);
  lcprelax::python::bind_scene_learning(m);
  lcprelax::python::bind_polygon_learning(m);
}
