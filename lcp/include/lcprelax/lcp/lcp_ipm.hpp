#pragma once
// Monotone LCPs (M + Mᵀ positive semidefinite) by the interior-point QP:
//     minimize zᵀ(Mz + q) = ½ zᵀ(M + Mᵀ)z + qᵀz   s.t.  Mz + q ≥ 0,  z ≥ 0,
// a convex QP whose optimal value is 0 exactly when the LCP has a solution (Cottle, Pang &
// Stone 1992, §1.2). For M that is not monotone the QP is not convex: the interior point
// then fails or stops, and the status says so (a negative diagonal of M + Mᵀ throws
// InputError before solving); never a silent answer: the result is
// `solved` only if the complementarity residual max|min(z, w)| ≤ 1e-9·max(1, ‖q‖∞)).
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/lcp/lcp_types.hpp>

namespace lcprelax {

/// Solves the LCP through the QP above; info.pivots holds the interior-point iterations.
/// Throws InputError on inconsistent sizes, NaN/Inf data or a negative diagonal of M + Mᵀ.
LcpResult solve_lcp_ipm(const SparseMatrix& M, const Vector& q, const QpSettings& settings = {});

}  // namespace lcprelax
