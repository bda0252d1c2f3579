// Bound-multiplier cleanup of an unscaled candidate solution (see qp_solver_impl.hpp).
//
// At an interior-point iterate the bound multipliers come from the scaled iterate, so the
// unscaled dual residual r_d = Px + q + Aᵀy + Gᵀz + z_b of a variable at an active bound
// carries the roundoff of the scaled quantities times 1/(c·Dx): a floor of ~1e-8 on
// QPCBOEI1 whatever the iterate. For a variable at its bound the exact multiplier is
// available componentwise: z_b,j = −(Px + q + Aᵀy + Gᵀz)_j, projected on the sign its
// bound allows (≥ 0 at an upper bound, ≤ 0 at a lower one, any sign when xl = xu). A
// variable counts as at its bound when |x_j − bound|·|z_b,j| ≤ 1e-3·eps_abs, so that the
// complementarity term it adds to the duality gap stays below the tolerance. Multipliers
// of variables at no bound are left alone. The caller keeps the cleaned candidate only
// if its recomputed residuals are better (the status is always decided on the residuals
// recomputed from the user's data).
#include "qp_solver_impl.hpp"

#include <algorithm>
#include <cmath>

namespace lcprelax::detail {

int clean_bound_multipliers(const QpProblem& p, double eps_abs, QpResult& r, Workspace& w) {
  // w.Px, w.Aty, w.Gtz hold P x, Aᵀy, Gᵀz of this candidate (compute_residuals).
  int changed = 0;
  const double tol = 1e-3 * eps_abs;
  for (Index j = 0; j < r.x.size(); ++j) {
    const double target = -(w.Px(j) + p.q(j) + w.Aty(j) + w.Gtz(j));
    const double xj = r.x(j), lo = p.xl(j), hi = p.xu(j);
    const bool at_upper = std::isfinite(hi) && std::abs(xj - hi) * std::abs(target) <= tol;
    const bool at_lower = std::isfinite(lo) && std::abs(xj - lo) * std::abs(target) <= tol;
    double v = r.z_bounds(j);
    if (at_upper && at_lower) v = target;
    else if (at_upper) v = std::max(target, 0.0);
    else if (at_lower) v = std::min(target, 0.0);
    else continue;
    if (v != r.z_bounds(j)) {
      r.z_bounds(j) = v;
      ++changed;
    }
  }
  return changed;
}

}  // namespace lcprelax::detail
