#pragma once
// The Stewart–Trinkle velocity-level LCP of one polygon on a static shape, written densely,
// and the linear map from its unknowns to the predicted next velocity: the closed-form
// stick/slip analysis of learn/stick_slip_fragility.hpp works on it. (Learning on a polygon
// does not use it: learn polygon is the scene path on a one-body scene, polygon_objective.hpp.)
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
#include <lcprelax/sparse/types.hpp>

namespace lcprelax::learn {

/// Dense contact data of one body (3 dofs: vx, vy, ω) with nc contacts, one friction row
/// each. Units: Jn, Jt rows (1, 1, m); φ m; M⁻¹ (1/kg, 1/kg, 1/(kg·m²)); v* (m/s, m/s, rad/s).
struct PolygonContactData {
  DenseMatrix Jn;   ///< nc×3
  DenseMatrix Jt;   ///< nc×3
  Vector phi;       ///< nc
  Vector mu;        ///< nc
  Vector minv;      ///< 3
  Vector v_star;    ///< 3

  Index num_contacts() const { return static_cast<Index>(phi.size()); }
  /// Sets every entry to zero with the sizes of a problem of nc contacts.
  void set_zero(Index nc);
};

struct PolygonLcp {
  DenseMatrix M;  ///< n×n
  Vector q;       ///< n
  DenseMatrix P;  ///< 3×n
  Vector p;       ///< 3
};

/// The LCP and prediction map of the data (value).
void polygon_lcp(const PolygonContactData& d, double dt, PolygonLcp& out);

/// A sparse copy of a dense matrix that STORES EVERY ENTRY (zeros included), so that
/// gradients "on the input's sparsity pattern" (Lemke, QP, relaxed backward) cover all
/// entries.
SparseMatrix full_pattern(const DenseMatrix& A);

}  // namespace lcprelax::learn
