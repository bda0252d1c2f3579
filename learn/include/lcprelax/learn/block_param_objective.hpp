#pragma once
// The block's hard and relaxed losses (learn/block_losses.hpp) for any parameterization of
// learn/block_param.hpp: per transition i = (v, u, v̄) the step data (M, q, P, p)(θ), then
//   hard:    ℓ = (P z + p − v̄)², z from Lemke; ∂ℓ/∂(M, q) by LemkeSolver::backward with
//            ∂ℓ/∂z = 2(P z + p − v̄)Pᵀ, plus the explicit ∂ℓ/∂P = 2r zᵀ, ∂ℓ/∂p = 2r;
//   relaxed: ℓ = c of learn/relaxed_lcp.hpp with (M, q, P, p, x̄ = v̄) and, for maximum
//            dissipation, E = (1, 1, 0), e = q₂ (the friction bound row's constant);
//            ∂ℓ/∂(M, q, P, p, e) by the envelope theorem.
// Then ∂ℓ/∂θ = Σ ⟨∂ℓ/∂(M, q, P, p), ∂(M, q, P, p)/∂θₖ⟩ (block_step_chain). The convex loss
// has no LCP data to parameterize: InputError. Nonconvex relaxed QPs (an elementwise M
// whose symmetric part is indefinite) follow settings.relaxed.nonconvex (the learning-curve
// bench uses NonconvexPolicy::shift). One solver per thread, cold starts (no per-sample
// state), so 1 and N threads give identical results.
#include <lcprelax/learn/block_losses.hpp>
#include <lcprelax/learn/block_param.hpp>

#include <memory>

namespace lcprelax::learn {

/// Throws InputError for BlockMethod::convex or invalid settings.
std::unique_ptr<Objective> make_block_param_objective(BlockParam param, BlockMethod method, const BlockDataset& data,
                                                      const BlockLossSettings& settings = {});

}  // namespace lcprelax::learn
