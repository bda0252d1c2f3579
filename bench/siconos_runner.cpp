// Calls into Siconos numerics' C API (siconos_runner.hpp). Names used, from its installed
// headers: LinearComplementarityProblem / FrictionContactProblem (problem structs),
// NM_create / NM_free (NumericsMatrix, NM_DENSE = column-major matrix0),
// solver_options_create / solver_options_delete (SolverOptions, iparam/dparam indices
// SICONOS_IPARAM_MAX_ITER, SICONOS_IPARAM_ITER_DONE, SICONOS_DPARAM_TOL,
// SICONOS_DPARAM_RESIDU), linearComplementarity_driver and fc2d_driver (NonSmoothDrivers.h).
#include "siconos_runner.hpp"

#include <FrictionContactProblem.h>
#include <Friction_cst.h>
#include <LinearComplementarityProblem.h>
#include <NonSmoothDrivers.h>
#include <NumericsMatrix.h>
#include <SolverOptions.h>
#include <lcp_cst.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>

namespace lcprelax::bench {
namespace {

struct MatrixDeleter {
  void operator()(NumericsMatrix* m) const { NM_free(m); }
};
struct OptionsDeleter {
  void operator()(SolverOptions* o) const { solver_options_delete(o); }
};
using MatrixPtr = std::unique_ptr<NumericsMatrix, MatrixDeleter>;
using OptionsPtr = std::unique_ptr<SolverOptions, OptionsDeleter>;

// A dense Siconos copy of a sparse matrix (NM_DENSE: column-major, size0 rows).
MatrixPtr dense_numerics_matrix(const SparseMatrix& A) {
  MatrixPtr m(NM_create(NM_DENSE, static_cast<int>(A.rows()), static_cast<int>(A.cols())));
  if (!m || !m->matrix0) throw std::runtime_error("Siconos: NM_create failed");
  double* data = m->matrix0;
  std::fill(data, data + A.rows() * A.cols(), 0.0);
  for (Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      data[static_cast<std::size_t>(j) * A.rows() + it.row()] += it.value();
  return m;
}

OptionsPtr make_options(int solver_id, long max_iterations, double tolerance) {
  OptionsPtr o(solver_options_create(solver_id));
  if (!o) throw std::runtime_error("Siconos: solver_options_create failed for id " + std::to_string(solver_id));
  o->iparam[SICONOS_IPARAM_MAX_ITER] = static_cast<int>(max_iterations);
  o->dparam[SICONOS_DPARAM_TOL] = tolerance;
  return o;
}

void read_options(const SolverOptions& o, SiconosResult& r) {
  r.iterations = o.iparam[SICONOS_IPARAM_ITER_DONE];
  r.max_iterations = o.iparam[SICONOS_IPARAM_MAX_ITER];
  r.residual = o.dparam[SICONOS_DPARAM_RESIDU];
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::string SiconosResult::status() const {
  // The limit first: Siconos 4.4's fc2d Lemke returns info 0 even when it stopped there.
  if (max_iterations > 0 && iterations >= max_iterations) return "iteration_limit";
  if (info == 0) return "solved";
  return "failed (info " + std::to_string(info) + ")";
}

SiconosResult siconos_lcp_lemke(const SparseMatrix& M, const Vector& q, long max_pivots) {
  MatrixPtr Md = dense_numerics_matrix(M);
  Vector q_copy = q;  // Siconos takes non-const pointers
  LinearComplementarityProblem problem{};
  problem.size = static_cast<int>(q.size());
  problem.M = Md.get();
  problem.q = q_copy.data();
  // The tolerance only decides the driver's final error check (filterOn): info = 0 iff
  // Siconos' own LCP error ≤ 1e-10, the target accuracy.
  OptionsPtr options = make_options(SICONOS_LCP_LEMKE, max_pivots, 1e-10);
  SiconosResult r;
  r.x = Vector::Zero(q.size());
  r.y = Vector::Zero(q.size());
  const auto t0 = std::chrono::steady_clock::now();
  r.info = linearComplementarity_driver(&problem, r.x.data(), r.y.data(), options.get());
  r.seconds = seconds_since(t0);
  read_options(*options, r);
  return r;
}

SiconosResult siconos_fc2d(const io::Fc2dData& d, SiconosFc2dSolver solver, double tolerance, long max_iterations) {
  MatrixPtr Wd = dense_numerics_matrix(d.W);
  Vector q_copy = d.q, mu_copy = d.mu;
  FrictionContactProblem problem{};
  problem.dimension = 2;
  problem.numberOfContacts = static_cast<int>(d.contacts);
  problem.M = Wd.get();
  problem.q = q_copy.data();
  problem.mu = mu_copy.data();
  const int id = solver == SiconosFc2dSolver::lemke ? SICONOS_FRICTION_2D_LEMKE : SICONOS_FRICTION_2D_NSGS;
  OptionsPtr options = make_options(id, max_iterations, tolerance);
  SiconosResult r;
  r.x = Vector::Zero(d.q.size());
  r.y = Vector::Zero(d.q.size());
  const auto t0 = std::chrono::steady_clock::now();
  r.info = fc2d_driver(&problem, r.x.data(), r.y.data(), options.get());
  r.seconds = seconds_since(t0);
  read_options(*options, r);
  return r;
}

}  // namespace lcprelax::bench
