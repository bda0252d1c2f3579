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
//   Ruiz, "A scaling algorithm to equilibrate both rows and columns norms in matrices",
//   RAL-TR-2001-034, 2001; the cost scale follows OSQP (Stellato et al. 2020, §5.1).
//
// Two steps: build_standard_form() classifies the rows, builds the patterns of P̃, Ẽ, Ẽᵀ,
// G̃, G̃ᵀ with a source map per stored value, and then calls refresh_standard_form(),
// which writes the values of a problem with the same pattern and classification into
// that structure and equilibrates them in place (no allocation).
#include <lcprelax/kkt/qp_problem.hpp>

#include <vector>

namespace lcprelax::detail {

/// Where an internal equality row comes from.
enum class EqSource { a_row, g_row, fixed_variable };

struct StandardForm {
  Index n = 0;   ///< variables
  Index me = 0;  ///< internal equality rows
  Index mg = 0;  ///< internal inequality rows (kept rows of G)

  SparseMatrix P;   ///< P̃, upper triangle (the pattern of the problem's P)
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

  /// Classification signature: per row of G and per variable, 'e' (equality), 'b' (two
  /// finite sides), 'l', 'u' (one side) or 'f' (free). Two problems with the same data
  /// pattern and the same signature share this structure and the KKT pattern.
  std::vector<char> signature;

  // Value maps of the compressed matrices (slots of the problem's compressed value arrays).
  std::vector<Index> e_src;    ///< per value of Ẽ: slot in A or G (see e_from_g), −1: fixed variable (1)
  std::vector<char> e_from_g;  ///< per value of Ẽ: 1 if e_src is a slot of G
  std::vector<Index> g_src;    ///< per value of G̃: slot in G
  std::vector<Index> et_src;   ///< per value of Ẽᵀ: slot in Ẽ
  std::vector<Index> gt_src;   ///< per value of G̃ᵀ: slot in G̃
  Vector ruiz_col, ruiz_e, ruiz_g;  ///< Ruiz workspace (norms, then factors of one pass)
};

/// Builds the scaled internal form (ruiz_iterations = 0: no scaling, c = 1). P, A and G
/// of `problem` must be compressed; the value maps refer to their value arrays.
StandardForm build_standard_form(const QpProblem& problem, int ruiz_iterations);

/// Whether `problem` classifies its rows and variables as f.signature says.
bool same_signature(const StandardForm& f, const QpProblem& problem);

/// Writes the values of `problem` (compressed P, A, G with the pattern f was built from,
/// same signature) into f and equilibrates in place. Allocation-free; gives the values
/// build_standard_form() gives for that problem.
void refresh_standard_form(StandardForm& f, const QpProblem& problem, int ruiz_iterations);

}  // namespace lcprelax::detail
