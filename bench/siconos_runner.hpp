#pragma once
// Siconos numerics (https://github.com/siconos/siconos, Apache-2.0; Debian package
// libsiconos-numerics-dev 4.4) as a peer of lcprelax's Lemke solver, called through its C
// API from siconos_runner.cpp. This header exposes lcprelax types only, so callers do not
// see Siconos headers. Built only when CMake finds Siconos (bench/CMakeLists.txt).
//
// Problems are handed to Siconos with dense storage (NM_DENSE, column-major): its
// lexicographic Lemke works on a dense tableau in any case, and its fc2d driver sends
// dense matrices to its dense NSGS.
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/sparse/types.hpp>

#include <limits>
#include <string>

namespace lcprelax::bench {

struct SiconosResult {
  int info = -1;            ///< the Siconos driver's return value (0: Siconos reports success)
  long iterations = 0;      ///< iparam[SICONOS_IPARAM_ITER_DONE]: Lemke pivots or NSGS sweeps
  long max_iterations = 0;  ///< iparam[SICONOS_IPARAM_MAX_ITER] passed in
  double residual = std::numeric_limits<double>::quiet_NaN();  ///< dparam[SICONOS_DPARAM_RESIDU]
  double seconds = 0.0;     ///< wall time of the driver call (problem conversion excluded)
  Vector x;                 ///< LCP: z;   fc2d: reaction r
  Vector y;                 ///< LCP: w;   fc2d: velocity u
  /// "iteration_limit" (iterations reached the limit), else "solved" (info 0) or
  /// "failed (info k)". Siconos 4.4's fc2d Lemke returns info 0 whatever its error: judge
  /// it by the error recomputed from x.
  std::string status() const;
};

/// Siconos' lexicographic Lemke (lcp_lexicolemke) through linearComplementarity_driver
/// with SICONOS_LCP_LEMKE. Siconos counts the pivots after the one that brings z₀ in.
SiconosResult siconos_lcp_lemke(const SparseMatrix& M, const Vector& q, long max_pivots);

enum class SiconosFc2dSolver {
  lemke,  ///< SICONOS_FRICTION_2D_LEMKE: fc2d_lexicolemke, an LCP of 3nc unknowns
  nsgs    ///< SICONOS_FRICTION_2D_NSGS: projected Gauss–Seidel over the contacts
};

/// fc2d_driver with the chosen solver; tolerance and max_iterations go to
/// dparam[SICONOS_DPARAM_TOL] and iparam[SICONOS_IPARAM_MAX_ITER].
SiconosResult siconos_fc2d(const io::Fc2dData& problem, SiconosFc2dSolver solver, double tolerance,
                           long max_iterations);

}  // namespace lcprelax::bench
