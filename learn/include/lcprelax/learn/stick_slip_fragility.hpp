#pragma once
// Stick/slip fragility of the Stewart–Trinkle LCP (issue 20, experiment 1): how large a
// perturbation ε of ONE element of q, or of one of M's friction coefficients that the
// physics makes antisymmetric, turns a sticking contact into a sliding one. The derivation
// is in docs/structure.md; this file computes the derived thresholds in closed form and
// measures them with Lemke (lcp/lemke.hpp), for bench/run_fragility.cpp and
// tests/structure_fragility_test.cpp.
//
// A case is one sticking contact in the Stewart–Trinkle layout of models/block1d.hpp (the
// 1-D block: z = (β⁺, β⁻, γ), no normal row, friction capacity μmg = q_γ) or
// learn/polygon_lcp.hpp with one contact (z = (λn, β⁺, β⁻, γ), capacity μλn). Its stick
// solution (γ = 0, v_t⁺ = 0) solves K u = −b, u = (λn, λt) or (λt), K the contact's block
// of W = J M⁻¹ Jᵀ, b = (q_n, q_t⁺); the friction-cone slack is s = μλn − |λt| (block:
// μmg − |λt|) and the contact sticks while s > 0. "Sliding" means γ > 0 (the LCP's sliding
// speed), measured as γ > 1e-9·max(1, ‖q‖∞).
//
// Perturbations (the "active" friction row is the one whose β carries λt, β⁺ when λt > 0):
//   q_pair           q_t⁺ += ε, q_t⁻ −= ε  (the free tangential velocity moves by ε: physical)
//   q_active         q of the active friction row += ε (one element)
//   q_inactive       q of the other friction row += ε (one element)
//   q_cone           q_γ += ε (the block's μmg; 0 for the polygon)
//   q_normal         q_n += ε (polygon only)
//   M_pair_inactive  M[inactive row, c] += ε, c = λn's column (polygon) or the active β's
//                    (block): breaks the antisymmetry M[β⁻, c] = −M[β⁺, c]
//   M_cone_active    M[γ, active β] += ε  (the cone row's −1 against the +1 of M[β, γ])
//   M_gamma_active   M[active row, γ] += ε (the other half of that skew pair)
// Derived thresholds (docs/structure.md): the sum of the two friction rows is
// w⁺ + w⁻ = 2γ + σ with σ = δq⁺ + δq⁻ + Σ_c (δM⁺_c + δM⁻_c) z_c, which is 0 for every
// physical M, q; σ < 0 forces γ ≥ −σ/2 > 0. Hence q_active, q_inactive and M_pair_inactive
// slide for EVERY ε < 0 (threshold 0, γ = −σ/2 exactly while both β stay positive); the
// other thresholds are the first root of s(ε) along the stick solution's linear path (a
// q_normal root where λn reaches 0 as well is a lift-off without sliding: none).
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/learn/polygon_lcp.hpp>
#include <lcprelax/models/block1d.hpp>
#include <lcprelax/sparse/types.hpp>

#include <string>
#include <vector>

namespace lcprelax::learn {

enum class FragilityPerturbation {
  q_pair, q_active, q_inactive, q_cone, q_normal, M_pair_inactive, M_cone_active, M_gamma_active
};
const char* to_string(FragilityPerturbation p);
/// Every perturbation that applies to `c` (q_normal only with a normal row).
struct StickCase;
std::vector<FragilityPerturbation> fragility_perturbations(const StickCase& c);

/// One sticking contact's LCP and the indices of its rows.
struct StickCase {
  std::string name;
  DenseMatrix M;        ///< n×n, Stewart–Trinkle layout
  Vector q;             ///< n
  Index row_n = -1;     ///< λn (−1: the block, no normal row)
  Index row_tp = 0, row_tm = 1, row_gamma = 2;  ///< β⁺, β⁻, γ
  double scale = 1.0;   ///< ‖q‖∞ (units of the q perturbations)
  /// Throws InputError when the rows are out of range or the stick solution does not
  /// stick strictly (s ≤ 0, λt = 0 or λn ≤ 0).
  void validate() const;
};

/// The block's LCP (models/block1d.hpp) at free velocity v* (u = 0, v = v*).
StickCase block_stick_case(const Block1d& block, double v_star);
/// The polygon LCP (learn/polygon_lcp.hpp) of one contact (d.num_contacts() == 1).
StickCase polygon_stick_case(const PolygonContactData& d, double dt, const std::string& name);
/// A unit square (1 kg, side 1 m, I = 1/6 kg·m²) standing on its corner (−½, −½) at
/// rotation `tilt` (rad, in (0, π/2)) on the ground y = 0, with pre-step velocity v
/// (vx, vy, ω), gravity 9.81 m/s² and friction μ: its contact data (φ = 0).
PolygonContactData square_on_corner(double tilt, const Vector& v, double mu, double dt);
/// The same square lying flat on the ground: two contacts, vertices (∓½, −½), φ = 0. Its
/// W is singular (4 contact rows, 3 dofs), so the friction split between the contacts is
/// not unique; the structural result (γ ≥ −σ/2 at the perturbed contact) holds regardless.
PolygonContactData square_flat(const Vector& v, double mu, double dt);

/// Sliding speeds γ (one per contact) of Lemke's solution of a polygon's LCP with q(row)
/// += ε (rows in polygon_lcp.hpp's layout); NaN entries if Lemke fails.
Vector polygon_sliding_speeds(const PolygonContactData& d, double dt, Index row, double eps,
                              const LemkeSettings& settings = {});

/// The stick solution of the unperturbed case: u = (λn, λt) (polygon) or (λt) (block), and
/// the cone slack s = capacity − |λt|.
struct StickSolution {
  double lambda_n = 0.0;   ///< NaN for the block
  double lambda_t = 0.0;   ///< β⁺ − β⁻
  double slack = 0.0;      ///< μλn − |λt| (block: μmg − |λt|)
};
StickSolution stick_solution(const StickCase& c);

/// (M, q) with the perturbation `p` of size ε applied.
void perturb(const StickCase& c, FragilityPerturbation p, double eps, DenseMatrix& M, Vector& q);

/// Thresholds on each side: `negative` ≤ 0 is the largest ε < 0 at which the contact
/// slides (−0.0 means every ε < 0; −∞ none), `positive` ≥ 0 likewise (+∞ none). For the
/// zero thresholds `slope` is dγ/dε on that side just past 0 (−½ for q, −z_c/2 for M, z_c
/// the perturbed column's unknown once sliding: λn, or for the block the active β of the
/// split β± = (μmg ± |λt|)/2); NaN elsewhere.
struct FragilityThreshold {
  double negative = 0.0, positive = 0.0;
  double slope = 0.0;
};
FragilityThreshold derived_threshold(const StickCase& c, FragilityPerturbation p);

/// The sliding speed γ of Lemke's solution of the perturbed LCP (NaN if Lemke fails).
double measured_sliding_speed(const StickCase& c, FragilityPerturbation p, double eps,
                              const LemkeSettings& settings = {});

struct FragilityMeasurement {
  FragilityThreshold threshold;  ///< slope: measured γ/ε at ε = ∓1e-6·scale on a zero side
  /// Perturbed LCPs Lemke did not solve (ray: e.g. q_γ < 0 beyond what friction can make
  /// up): counted as "not sticking", since the stick solution does not exist there either.
  int lemke_failures = 0;
  int solves = 0;
};
/// Scans ε = ±scale·10^(k/4), k = −48 … 4 (scale: c.scale for q, max|M_ij| for M) for the
/// first sliding ε on each side, then bisects between it and the last sticking one (or 0)
/// to relative 1e-10. Independent of the derivation.
FragilityMeasurement measured_threshold(const StickCase& c, FragilityPerturbation p, const LemkeSettings& settings = {});

}  // namespace lcprelax::learn
