#pragma once
// The Stewart–Trinkle velocity-level LCP of one polygon sample, the linear map from its
// unknowns to the predicted next velocity, and their derivatives with respect to θ
// (forward mode: the tangent for one parameter from the assembly's tangent).
//
// Stewart & Trinkle, "An implicit time-stepping scheme for rigid body dynamics with
// inelastic collisions and Coulomb friction", IJNME 39, 1996; Anitescu & Potra, "Formulating
// dynamic multi-rigid-body contact problems with friction as solvable linear
// complementarity problems", Nonlinear Dynamics 14, 1997. The same LCP as
// models/contact_step.hpp stewart_trinkle_lcp (checked in tests), written densely for one
// body with nc ≤ 2 contacts and one friction row per contact:
//     z = [λn (nc), β⁺ (nc), β⁻ (nc), γ (nc)],  n = 4nc,  W = J M⁻¹ Jᵀ,  J = [Jn; Jt],
//     M = [ Wnn  Wnt −Wnt  0 ]      q = [ Jn v* + max(φ,0)/Δt ]
//         [ Wtn  Wtt −Wtt  I ]          [ Jt v*               ]
//         [−Wtn −Wtt  Wtt  I ]          [−Jt v*               ]
//         [ diag(μ) −I −I  0 ]          [ 0                   ]
// Prediction: v⁺ = P z + p with P = M⁻¹ [Jnᵀ  Jtᵀ  −Jtᵀ  0] (3×n) and p = v*.
// Tangents: dW = dJ M⁻¹ Jᵀ + J dM⁻¹ Jᵀ + J M⁻¹ dJᵀ; the gap term's derivative is dφ/Δt where
// φ > 0 and 0 where φ < 0 (a kink at φ = 0; gradient checks stay away from it).
#include <lcprelax/learn/polygon_assembly.hpp>
#include <lcprelax/sparse/types.hpp>

namespace lcprelax::learn {

struct PolygonLcp {
  DenseMatrix M;  ///< n×n
  Vector q;       ///< n
  DenseMatrix P;  ///< 3×n
  Vector p;       ///< 3
};

/// The LCP and prediction map of the data (value).
void polygon_lcp(const PolygonContactData& d, double dt, PolygonLcp& out);

/// Their derivative along the tangent dd of the data (d the value at which it is taken).
void polygon_lcp_tangent(const PolygonContactData& d, const PolygonContactData& dd, double dt, PolygonLcp& out);

/// A sparse copy of a dense matrix that STORES EVERY ENTRY (zeros included), so that
/// gradients "on the input's sparsity pattern" (Lemke, QP, relaxed backward) cover all
/// entries.
SparseMatrix full_pattern(const DenseMatrix& A);

/// Σ over the stored entries (i, j) of G of G_ij · T_ij.
double pattern_inner(const SparseMatrix& G, const DenseMatrix& T);

}  // namespace lcprelax::learn
