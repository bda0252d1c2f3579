#pragma once
// Internal, equilibrated form of a QpProblem used by the interior point (not installed).
//
//   minimize ½ x̃ᵀ P̃ x̃ + q̃ᵀ x̃   s.t.  Ẽ x̃ = b̃,   g̃l ≤ G̃ x̃ ≤ g̃u,   x̃l ≤ x̃ ≤ x̃u
//
// - Ẽ stacks the rows of A, the rows of G with l = u, and one identity row per fixed
//   variable (xl = xu); G̃ keeps the remaining rows of G with at least one finite side.
// - Scaling (Ruiz equilibration of [P Eᵀ Gᵀ; E 0 0; G 0 0] and a cost scale c):
//   x = Dx∘x̃,  P̃ = c·Dx P Dx,  q̃ = c·Dx∘q,  Ẽ = diag(Ee) E diag(Dx),  b̃ = Ee∘b,
//   G̃ = diag(Eg) G diag(Dx),  g̃l = Eg∘l,  x̃l = xl/Dx, and the multipliers map back as
//   y = Ee∘ỹ/c,  z = Eg∘z̃/c,  z_bounds = z̃_b/(c·Dx).
#include <lcprelax/kkt/qp_problem.hpp>

#include <vector>

namespace lcprelax::detail {

/// Where an internal equality row comes from.
enum class EqSource { a_row, g_row, fixed_variable };

struct StandardForm {
  Index n = 0;   ///< variables
  Index me = 0;  ///< internal equality rows
  Index mg = 0;  ///< internal inequality rows (kept rows of G)

  SparseMatrix P;   ///< P̃, upper triangle
  Vector q;         ///< q̃
  SparseMatrix E;   ///< Ẽ (me×n)
  SparseMatrix Et;  ///< Ẽᵀ
  Vector be;        ///< b̃
  SparseMatrix G;   ///< G̃ (mg×n)
  SparseMatrix Gt;  ///< G̃ᵀ
  Vector gl, gu;    ///< g̃l, g̃u (±∞ where a side is absent)
  Vector xl, xu;    ///< x̃l, x̃u (±∞ where absent; fixed variables are free here)

  std::vector<EqSource> eq_source;  ///< per internal equality row
  std::vector<Index> eq_index;      ///< its row of A, row of G, or variable
  std::vector<Index> g_index;       ///< per kept G row: its row in the user's G
  std::vector<Index> g_eq_row;      ///< per user G row: internal equality row, or −1
  std::vector<Index> fixed_eq_row;  ///< per variable: internal equality row, or −1

  Vector Dx, Ee, Eg;  ///< scaling factors (see header comment)
  double c = 1.0;     ///< cost scaling

  /// Classification signature: which rows are equalities, which sides are finite.
  /// Two problems with the same data pattern and the same signature share a KKT pattern.
  std::vector<char> signature;
};

/// Builds the scaled internal form (ruiz_iterations = 0: no scaling, c = 1).
StandardForm build_standard_form(const QpProblem& problem, int ruiz_iterations);

}  // namespace lcprelax::detail
