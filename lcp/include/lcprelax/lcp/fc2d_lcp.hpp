#pragma once
// 2-D frictional contact u = W r + q (per contact: normal, tangent) with Coulomb's law
//     0 ≤ r_n ⊥ u_n ≥ 0,   |r_t| ≤ μ r_n,   u_t = 0 if |r_t| < μ r_n, else r_t = −μ r_n sign(u_t)
// as an LCP with a polyhedral (exact in 2-D) friction cone: per contact the unknowns
// z = (r_n, β⁺, β⁻, λ) with r_t = β⁺ − β⁻ and the slack λ (= |u_t| when sliding), and
//     w_n = u_n                ⊥ r_n
//     w⁺  = u_t + λ            ⊥ β⁺
//     w⁻  = −u_t + λ           ⊥ β⁻
//     w_λ = μ r_n − β⁺ − β⁻    ⊥ λ
// (Stewart & Trinkle 1996, "An implicit time-stepping scheme for rigid body dynamics with
// inelastic collisions and Coulomb friction", IJNME 39; 2-D form as in Siconos' fc2d Lemke).
// M is assembled sparse from W's 2×2 blocks: nnz(M) ≤ 4·nnz(W) + 6·nc.
#include <lcprelax/sparse/types.hpp>

namespace lcprelax {

struct Fc2dLcp {
  SparseMatrix M;  ///< 4nc × 4nc
  Vector q;        ///< 4nc
};

/// W (2nc×2nc), q (2nc), μ (nc ≥ 0). Throws InputError on inconsistent sizes.
Fc2dLcp fc2d_to_lcp(const SparseMatrix& W, const Vector& q, const Vector& mu);

/// Maps an LCP solution z back to reactions r (2nc) and velocities u = W r + q.
void fc2d_from_lcp(const Vector& z, const SparseMatrix& W, const Vector& q, Vector& r, Vector& u);

}  // namespace lcprelax
