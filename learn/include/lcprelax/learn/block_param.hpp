#pragma once
// Parameterizations of the 1-D frictional block's step (models/block1d.hpp) beyond the
// physical one: each maps θ and one transition (v, u) to the step's LCP data (M, q) and
// its linear readout v̂⁺ = P z + p, with the tangents ∂(M, q, P, p)/∂θₖ, so that any loss
// that returns ∂ℓ/∂(M, q, P, p) — Lemke's backward (hard) or the relaxed LCP's envelope
// gradient (learn/relaxed_lcp.hpp) — learns θ (learn/block_param_objective.hpp).
// Issue 20's question: how much structure does a learned contact model need?
//
// Conventions: z = (λ⁺, λ⁻, γ) as in models/block1d.hpp; m and mg are the dataset's known
// values (kg, N·s); w = 1/m; v* = v + u·w (m/s). M is stored with all 9 entries (explicit
// zeros included) so that every entry has a gradient slot. The physical model is
//     M = [[w, −w, 1], [−w, w, 1], [−1, −1, 0]],  q = (v*, −v*, μ·mg),
//     P = (w, −w, 0),  p = v*,
// and every parameterization below contains it (at the "truth" values listed), so a model
// of each family can fit noise-free data exactly.
//   physical    θ = {mu}                                    (log; truth μ)
//   pair        θ = {mu_pos, mu_neg (log), compliance (≥ 0), offset (m/s)}:
//               per-direction friction (the block's two tangent directions are its two
//               "material pairs"), a tangential compliance c and a velocity offset b:
//                 M₀₀ = M₁₁ = w + c,  q = (v* + b, −v* − b, μ̄·mg),  μ̄ = (μ₊ + μ₋)/2,
//                 (M₀₂, M₁₂) = (a₊, a₋),  (M₂₀, M₂₁) = (−a₊, −a₋),  a± = μ̄/μ±,
//               so that the bound row μ̄mg − a₊λ⁺ − a₋λ⁻ ≥ 0 caps λ⁺ at μ₊mg and λ⁻ at μ₋mg
//               (structured: the γ column stays the negative transpose of the bound row,
//               the friction rows' antisymmetry is imposed, and c ≥ 0 keeps sym(M) ⪰ 0;
//               truth μ₊ = μ₋ = μ, c = 0, b = 0). Readout physical.
//   residual    θ = {mu, residual.v, residual.u, residual.1}: a linear residual on the
//               free velocity in features of the state, v* ← v* + r_v·v + r_u·u + r_1 (in q
//               and in p alike; r_v dimensionless, r_u in 1/kg, r_1 in m/s); truth r = 0.
//   elementwise θ = {M.ij (9 free entries), q.i.v, q.i.u, q.i.1 (i = 0..2)}: M free and q
//               affine in the state features, q = A·(v, u, 1) with A free (q cannot be
//               "free" per transition and still be learned); readout physical (known m).
//               Truth: M physical, A = [[1, w, 0], [−1, −w, 0], [0, 0, μ·mg]].
// Stick/slip mode of a prediction: "stick" iff the sliding speed γ = z₂ ≤ 1e-10·(1 + ‖z‖∞)
// (the LCP's own mode, which is what a wrong q element flips; docs/structure.md).
#include <lcprelax/learn/parameters.hpp>
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/sparse/types.hpp>

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace lcprelax {
class LemkeSolver;
}

namespace lcprelax::learn {

enum class BlockParam { physical, pair, elementwise, residual };
const char* to_string(BlockParam p);
/// "physical", "pair", "elementwise" or "residual"; throws InputError naming the choices.
BlockParam parse_block_param(const std::string& s);

/// The parameter set of `param`, initialized at the physical model with friction `mu`
/// (the non-physical extras at their neutral values), for a block of mass `mass`, weight
/// impulse `mg`. Friction coefficients are log-transformed in [1e-8, 1e8]; compliance is
/// identity with lower bound 0; the rest identity, unbounded.
ParameterSet block_param_parameters(BlockParam param, double mu, double mass, double mg);

/// The parameter group of a parameter name (for reports): "friction", "compliance",
/// "offset", "residual", "M" or "q".
std::string block_param_group(const std::string& name);

/// The step's data at θ for one transition, with tangents per parameter (θ order).
struct BlockStepData {
  Eigen::Matrix3d M;
  Eigen::Vector3d q;
  Eigen::Vector3d P;  ///< the readout row
  double p = 0.0;
  struct Tangent {
    Eigen::Matrix3d dM = Eigen::Matrix3d::Zero();
    Eigen::Vector3d dq = Eigen::Vector3d::Zero();
    Eigen::Vector3d dP = Eigen::Vector3d::Zero();
    double dp = 0.0;
  };
  std::vector<Tangent> tangents;  ///< one per parameter of θ
};

/// Throws InputError when θ lacks a parameter of `param` (naming it) or mass, mg ≤ 0.
BlockStepData block_step_data(BlockParam param, const ParameterSet& theta, double mass, double mg, double v, double u);

/// M and q as the sparse/dense types of the solvers (all 9 entries of M stored).
SparseMatrix block_step_M(const BlockStepData& d);

/// ∂ℓ/∂θ from ∂ℓ/∂(M, q, P, p) (dM dense 3×3).
Vector block_step_chain(const BlockStepData& d, const Eigen::Matrix3d& dM, const Eigen::Vector3d& dq,
                        const Eigen::Vector3d& dP, double dp);

struct BlockPrediction {
  bool ok = false;         ///< Lemke found a solution
  std::string message;     ///< why not
  double v_next = 0.0;     ///< v̂⁺ = P z + p, m/s
  bool stick = false;      ///< γ = z₂ ≈ 0 (header comment)
};

/// The model's prediction by Lemke (one solver reused by the caller; cold start).
BlockPrediction block_param_predict(BlockParam param, const ParameterSet& theta, double mass, double mg, double v,
                                    double u, LemkeSolver& solver);

}  // namespace lcprelax::learn
