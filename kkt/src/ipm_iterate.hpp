#pragma once
// Interior-point iterate and its Newton step on a StandardForm (internal).
//
// Every finite side of a row of G̃ or of a variable bound is a one-sided constraint on a
// quantity v (v = G̃x̃ for rows, v = x̃ for bounds) with slack s > 0 and multiplier z > 0:
//     lower:  v − s = l          upper:  v + s = u
// The signed multiplier of a quantity is ζ = z_upper − z_lower (positive where the upper
// side is active, the convention of QpProblem's multipliers).
// Residuals: r = v − s − l (lower), r = v + s − u (upper), r_c = s∘z − σμ (+ corrector).
// Eliminating ds and dz from the Newton equations gives dζ = D dv + ξ with
//     D = Σ z/s,   ξ = Σ_upper (−r_c + z r)/s + Σ_lower (r_c + z r)/s,
// and then  ds = dv + r (lower), ds = −dv − r (upper), dz = (−r_c − z∘ds)/s.
#include "standard_form.hpp"

#include <array>
#include <vector>

namespace lcprelax::detail {

struct Side {
  std::vector<Index> idx;  ///< quantity index of each constraint
  Vector bound;            ///< l or u of each constraint
  bool upper = false;
  Vector s, z;             ///< slack and multiplier (> 0)
  Vector r, rc;            ///< primal residual and complementarity right-hand side
  Vector ds, dz;           ///< step
  Vector ds_saved, dz_saved, rc_saved;  ///< a step and its rc kept while a corrector is tried
  Index size() const { return static_cast<Index>(idx.size()); }
};

struct Iterate {
  Vector x, y;
  Side g_lower, g_upper, b_lower, b_upper;
  Vector vg;  ///< G̃x̃
  std::vector<Index> g_lower_pos, g_upper_pos;  ///< per row: position in g_lower/g_upper or −1
  std::vector<Index> b_lower_pos, b_upper_pos;  ///< per variable: position in b_lower/b_upper or −1

  /// Builds the four sides from the finite bounds of f (slacks and multipliers unset).
  void init_sides(const StandardForm& f);
  Index num_constraints() const;
  /// Σ s∘z / N (0 without inequality constraints).
  double mu() const;
  /// r for all sides from the current x (updates vg).
  void compute_side_residuals(const StandardForm& f);
  /// Barrier terms D for rows (Dg, size mg) and bounds (Db, size n). The outputs are
  /// resized only when their size differs (the solver passes presized work vectors).
  void barrier_terms(Index mg, Index n, Vector& Dg, Vector& Db) const;
  /// ξ for rows and bounds from the current r and rc (outputs as in barrier_terms).
  void xi_terms(Index mg, Index n, Vector& xig, Vector& xib) const;
  /// Recovers ds, dz of every side from dx, dvg = G̃ dx and the solved row step dζ. The
  /// row sides are then corrected so that dz_u − dz_l equals dζ exactly: rebuilding dζ
  /// as D·dv + ξ loses all accuracy at active rows, where D = z/s → ∞ amplifies the
  /// roundoff of dv; the correction goes to the side with the larger z/s, whose ds is
  /// then taken from its complementarity equation s·dz + z·ds = −r_c.
  /// The bound sides get the same treatment when dzeta_b (size n) is non-empty: it is the
  /// signed bound-multiplier step that makes the first block of the Newton equations hold
  /// exactly, dζ_b = −r_d − (P̃dx + Ẽᵀdy + G̃ᵀdζ_g), so that the dual residual of the next
  /// iterate is (1 − α)·r_d up to the roundoff of two products, whatever the accuracy of the
  /// linear solve; rebuilding dζ_b as Db·dx + ξ_b instead multiplies the error of dx by
  /// z/s ~ 1e20 at active bounds (QPCBOEI1: the dual residual rose from 4e-8 to 1.6e-3
  /// while μ fell to 1e-45). Variables without a finite bound are left as they are.
  void recover_side_steps(const Vector& dx, const Vector& dvg, const Vector& dzeta, const Vector& dzeta_b);
  /// Largest α ≤ 1 keeping s + α ds ≥ 0 and z + α dz ≥ 0.
  double max_step() const;
  /// Signed multipliers ζ of rows (mg) and bounds (n) (outputs as in barrier_terms).
  void signed_multipliers(Index mg, Index n, Vector& zg, Vector& zb) const;
  /// The same for the one-sided values max(z, 0), or max(dz, 0) with use_steps (the
  /// candidate of a primal infeasibility certificate).
  void signed_positive_parts(Index mg, Index n, bool use_steps, Vector& zg, Vector& zb) const;
  /// The four sides, without allocating (called several times per iteration).
  std::array<Side*, 4> sides() { return {&g_lower, &g_upper, &b_lower, &b_upper}; }
  std::array<const Side*, 4> sides() const { return {&g_lower, &g_upper, &b_lower, &b_upper}; }
};

}  // namespace lcprelax::detail
