#pragma once
// Solution errors computed exactly as Siconos numerics defines them, so that lcprelax's
// results compare with that library's.
//
// LCP (Siconos lcp_compute_error / lcp_compute_error_only, numerics/src/LCP):
//     w = M z + q,   e = ‖z − max(0, z − w)‖₂   (componentwise max: the natural map)
//     error = e / ‖q‖₂  if ‖q‖₂ > DBL_EPSILON,  else error = e  (no normalization).
//
// fc2d (Siconos fc2d_compute_error, numerics/src/FrictionContact/fc2d_compute_error.c,
// with fc2d_unitary_compute_and_add_error; current Siconos, ρ = 1): per contact i with
// r = (r_N, r_T), u = (u_N, u_T), friction coefficient μ and cone K = {(a, b): |b| ≤ μ a}:
//     v = (r_N − u_N − μ |u_T|,  r_T − u_T)            (De Saxcé's modified velocity)
//     P_K(v) = 0                                          if μ |v_T| ≤ −v_N   (polar cone)
//            = (a, μ a sgn(v_T)), a = (μ |v_T| + v_N)/(1 + μ²)   if |v_T| > μ v_N
//            = v                                          otherwise (v ∈ K)
//     e_i = r − P_K(v)
//     error = sqrt(Σ_i ‖e_i‖²) / s,  s = max(‖r‖₂, ‖u‖₂, ‖q‖₂), divided only if s > DBL_EPSILON.
// Siconos passes `norm` = ‖q‖₂ from its fc2d solvers; older Siconos versions divided by ‖q‖₂
// alone, the current one by the max above, which is what is implemented here. It is zero
// exactly when, for every contact, r ∈ K and the De Saxcé complementarity
// K ∋ r ⊥ u + (μ|u_T|, 0) ∈ K* holds (sticking, sliding with r_T = −μ r_N sgn(u_T), or
// separation).
//
// Inconsistent vector/matrix sizes throw lcprelax::InputError.
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/sparse/types.hpp>

namespace lcprelax::io {

/// Siconos LCP error of z for 0 ≤ z ⊥ M z + q ≥ 0 (formula above).
double lcp_error(const SparseMatrix& M, const Vector& q, const Vector& z);

/// Siconos fc2d error of the reaction r with the velocity u as given (the caller passes
/// u = W r + q; Siconos itself recomputes u that way before evaluating the same formula).
double fc2d_error(const Fc2dData& problem, const Vector& r, const Vector& u);

/// As above with u = W r + q computed here, exactly as Siconos does.
double fc2d_error(const Fc2dData& problem, const Vector& r);

}  // namespace lcprelax::io
