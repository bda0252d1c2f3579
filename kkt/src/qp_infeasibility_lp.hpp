#pragma once
// Auxiliary LPs that decide infeasibility when the interior point fails (internal).
//
// Primal: min t  s.t.  |Ax − b| ≤ t,  l − t ≤ Gx ≤ u + t,  xl − t ≤ x ≤ xu + t,  t ≥ 0.
//   t* is the smallest ∞-norm violation any x can reach (the primal residual of
//   QpSettings). Its multipliers, summed per original row, are a Farkas certificate
//   (y, z, z_bounds): Aᵀy + Gᵀz + z_bounds = 0 and the support term equals −t* < 0.
// Dual: min qᵀd  s.t.  Pd = 0, Ad = 0, Gd and d in the recession cones of the row and
//   variable bounds, −1 ≤ d ≤ 1. A negative optimum gives an unbounded direction d.
// Both certificates are verified on the user's data before they are reported.
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/kkt/qp_result.hpp>
#include <lcprelax/kkt/qp_settings.hpp>

namespace lcprelax::detail {

/// True (and certificate in cert.y, cert.z, cert.z_bounds) if the constraints cannot be
/// met to a residual below max(1e-6, 1e3·eps_abs).
bool prove_primal_infeasible(const QpProblem& p, const QpSettings& s, QpResult& cert);
/// True (and direction in cert.x) if the objective decreases without bound.
bool prove_dual_infeasible(const QpProblem& p, const QpSettings& s, QpResult& cert);

}  // namespace lcprelax::detail
