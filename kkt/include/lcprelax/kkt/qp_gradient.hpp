#pragma once
// Gradients of a scalar loss ℓ(x*, y*, z*) with respect to every QP datum, as returned by
// QpSolver::backward(). Matrix gradients live on the input's sparsity pattern:
// - dP has P's (upper-triangular) pattern; an off-diagonal entry is ∂ℓ/∂p for the stored
//   value p, which enters P twice (at (i,j) and (j,i)), so dP(i,j) = dx_i x_j + x_i dx_j.
// - dA, dG have A's and G's patterns.
// - dl, du, dxl, dxu are zero where the bound is infinite or inactive. For an equality row
//   (l_i = u_i) the whole derivative with respect to the common value is reported on the
//   side the multiplier says is active (du_i if z_i ≥ 0, else dl_i), the one-sided
//   derivative in the direction that keeps that side active.
#include <lcprelax/sparse/types.hpp>

namespace lcprelax {

struct QpGradient {
  SparseMatrix dP;
  Vector dq;
  SparseMatrix dA;
  Vector db;
  SparseMatrix dG;
  Vector dl;
  Vector du;
  Vector dxl;
  Vector dxu;
  /// Relative residual ‖K₀d − r‖∞ / (1 + ‖r‖∞) of the adjoint KKT solve after iterative
  /// refinement against the unregularized KKT matrix K₀ (scaled problem). At roundoff level
  /// (≲ 1e-10) when K₀ is well conditioned at the final iterate. A large value (say > 1e-6)
  /// means K₀ is singular or nearly so there: typically the optimum is not unique (e.g. an LP
  /// face; QAFIRO: 0.5) or the active set is degenerate, ∂ℓ/∂(data) does not exist, and the
  /// numbers above are set by the regularization (they scale like 1/ρ). Check it before
  /// trusting a gradient; backward() does not throw on it.
  double adjoint_residual = 0.0;
};

}  // namespace lcprelax
