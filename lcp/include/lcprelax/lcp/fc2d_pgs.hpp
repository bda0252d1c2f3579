#pragma once
// Approximate 2-D frictional contact solutions by projected Gauss–Seidel, and the Lemke
// basis they suggest (the crash start of lemke.hpp).
//
// Problem (fc2d_lcp.hpp): u = W r + q per contact (normal, tangent), Coulomb's law with
// friction μ_c. One sweep visits the contacts in order and solves each one's 2×2 problem
// exactly with the others' reactions fixed (a nonsmooth Gauss–Seidel: Jean 1999, "The
// non-smooth contact dynamics method", CMAME 177; Siconos' fc2d NSGS): with the local
// velocity ũ = u − W_cc r_c the local problem u_c = W_cc r_c + ũ has its solution in one of
// four cases, tried in order:
//   separation  r = 0 where ũ_n ≥ 0;
//   sticking    r = −W_cc⁻¹ũ where r_n ≥ 0 and |r_t| ≤ μ r_n;
//   sliding     r_t = −sμ r_n, r_n = −ũ_n/(W_nn − sμW_nt) ≥ 0, s = ±1, where the sliding
//               velocity u_t has the sign s;
//   otherwise   the previous r_c is kept (no case holds: a non-positive-definite block).
// u is kept as W r + q by column updates after each contact (W in CSC; W's 2×2 diagonal
// blocks must be positive definite for the cases to be exhaustive).
// Stops after `max_sweeps` or when a sweep changes no reaction by more than tolerance·‖r‖∞
// (relative: resting-contact problems have ‖q‖ ~ 1e-19). Units: those of W (velocity per impulse), q (velocity), r (impulse).
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/sparse/types.hpp>

#include <vector>

namespace lcprelax {

struct Fc2dPgsResult {
  Vector r;         ///< 2nc reactions (normal, tangent per contact)
  Vector u;         ///< W r + q
  int sweeps = 0;
  double change = 0.0;  ///< largest reaction change of the last sweep
};

/// Throws InputError on inconsistent sizes or negative μ.
Fc2dPgsResult fc2d_pgs(const SparseMatrix& W, const Vector& q, const Vector& mu, int max_sweeps, double tolerance);

/// The LCP point of reactions r (with u = W r + q): z = (r_n, r_t⁺, r_t⁻, λ) per contact
/// with r_n clipped at 0, λ = |u_t| where the contact slides (|r_t| ≥ μ r_n·(1 − 1e-9),
/// r_n > 0) and 0 elsewhere (size 4nc; LemkeSolver::warm_start_point takes it).
Vector fc2d_lcp_point(const Vector& r, const Vector& u, const Vector& mu);

/// The complementary basis of the LCP of fc2d_lcp.hpp suggested by reactions r (with u =
/// W r + q): the LCP point z = (r_n, r_t⁺, r_t⁻, λ) with λ = |u_t| where the contact slides
/// (|r_t| ≥ μ r_n·(1 − 1e-9), r_n > 0) and 0 elsewhere, w = Mz + q_lcp, and z_i basic where
/// z_i > w_i (true entries of the result; size 4nc, as LemkeSolver::warm_start takes).
std::vector<bool> fc2d_basis_guess(const Vector& r, const Vector& u, const Vector& mu, const SparseMatrix& M_lcp,
                                   const Vector& q_lcp);

/// How the PGS answer starts Lemke: `basis` = the basis it suggests (fc2d_basis_guess),
/// `purified` = its LCP point purified into a vertex basis first (fc2d_lcp_point,
/// LemkeSolver::warm_start_point).
enum class Fc2dCrash { basis, purified };

/// Lemke (lemke.hpp, `settings` with crash_start on) on `lcp` = fc2d_to_lcp(W, q, μ),
/// started from `sweeps` PGS sweeps (tolerance 1e-12) as `start` says: the solution's basis
/// when PGS found it (zero pivots), else a crash start, else the cold start. The PGS sweeps
/// run are written to *sweeps_done when given.
LcpResult solve_fc2d_lemke_crash(const SparseMatrix& W, const Vector& q, const Vector& mu, const Fc2dLcp& lcp,
                                 int sweeps, LemkeSettings settings = {}, int* sweeps_done = nullptr,
                                 Fc2dCrash start = Fc2dCrash::basis);

}  // namespace lcprelax
