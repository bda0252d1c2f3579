#pragma once
// Monotone LCPs (M + Mᵀ positive semidefinite) by the interior-point QP:
//     minimize zᵀ(Mz + q) = ½ zᵀ(M + Mᵀ)z + qᵀz   s.t.  Mz + q ≥ 0,  z ≥ 0,
// a convex QP whose optimal value is 0 exactly when the LCP has a solution (Cottle, Pang &
// Stone 1992, §1.2). For M that is not monotone the QP is not convex: the interior point
// would end at a KKT point that is not a solution: M + Mᵀ is checked first (psd_error of
// kkt/qp_convexity.hpp, one Cholesky factorization) and a non-monotone M throws InputError
// in the LCP's terms ("M is not monotone"); never a silent answer: the result is `solved`
// only if z and w are finite and the complementarity residual max|min(z, w)| ≤
// 1e-9·max(1, ‖q‖∞).
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/lcp/lcp_types.hpp>

namespace lcprelax {

/// Solves the LCP through the QP above; info.pivots holds the interior-point iterations.
/// Throws InputError on inconsistent sizes, NaN/Inf data, or M + Mᵀ not positive semidefinite.
LcpResult solve_lcp_ipm(const SparseMatrix& M, const Vector& q, const QpSettings& settings = {});

}  // namespace lcprelax
