#pragma once
// Convexity of a QP: is the Hessian P (given by its upper triangle, qp_problem.hpp)
// positive semidefinite? The interior point needs it: with an indefinite P the barrier
// terms can still make every Newton system quasi-definite, and the iteration then ends at
// a KKT point that is not a minimum (P = [1 3; 3 1] on the box [−1, 1]²: the saddle x = 0,
// objective 0, while the minimum is −2). QpSolver::setup() refuses such a P with
// InputError (QpSettings::check_convexity).
//
// Test (psd_error). With the roundoff shift τ = kPsdRoundoff·max_i P_ii (1e-12 relative:
// a matrix formed in floating point, such as M + Mᵀ of a monotone M = BᵀB + S − Sᵀ, has
// entries of that size where exact arithmetic gives 0), P + τI on the support J (columns
// with a nonzero entry) is scaled to unit diagonal, S = D (P + τI)_JJ D with
// D = diag(P_ii + τ)^(-1/2) (a congruence: same inertia), and S + δI with δ =
// kPsdTolerance = 1e-9 is factorized by Cholesky (dense LLᵀ up to kDensePsdMax columns, else
// CHOLMOD supernodal LLᵀ with AMD): P is accepted exactly when that factorization succeeds.
// So a PSD P (also singular: LPs with P = 0, rank-deficient Hessians) passes with roundoff
// to spare (pivot errors ~ column count · 1e-16 ≪ δ), and a P whose scaled smallest
// eigenvalue is below −δ is refused; between −δ and 0 is roundoff and passes. An
// off-diagonal P_ij beyond roundoff where P_ii = 0 is refused by the 2×2 test below (a PSD
// matrix has a zero row wherever its diagonal is zero), and a diagonal P is accepted without
// factorizing (validate() has checked its signs). Cost: one sparse Cholesky of P's
// pattern, small next to the interior point's KKT factorizations (measured on the
// Maros–Meszaros set in tests/qp_convexity_test.cpp).
//
// Cheap test (psd_minor_error): the 2×2 principal minors of P + τI, |S_ij| ≤ 1 + δ for
// every stored entry; O(nnz(P)), no allocation: what QpSolver::update() checks (its values change
// without a new factorization allowed; a P whose every 2×2 minor is fine can still be
// indefinite, which only setup() detects).
#include <lcprelax/sparse/types.hpp>

#include <string>

namespace lcprelax {

/// δ of the header comment: the unit-diagonal scaled P must satisfy S + δI ≻ 0.
constexpr double kPsdTolerance = 1e-9;
/// τ/max_i P_ii of the header comment: the roundoff shift of P.
constexpr double kPsdRoundoff = 1e-12;
/// Largest support factorized densely (Eigen LLᵀ); above it CHOLMOD.
constexpr Index kDensePsdMax = 128;

/// Empty when the symmetric matrix with upper triangle `P_upper` is positive semidefinite
/// within kPsdTolerance, else a message that names it as `name` and says why (the smallest
/// eigenvalue for supports up to kDensePsdMax, else the column where Cholesky failed).
std::string psd_error(const SparseMatrix& P_upper, const std::string& name = "P");

/// The 2×2-minor test of the header comment (necessary, not sufficient); allocation-free.
std::string psd_minor_error(const SparseMatrix& P_upper, const std::string& name = "P");

}  // namespace lcprelax
