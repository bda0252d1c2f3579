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
};

}  // namespace lcprelax
