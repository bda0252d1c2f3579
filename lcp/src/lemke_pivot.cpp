// Lemke's pivots: the cold start from the all-w basis, the pivot loop and the
// lexicographic minimum-ratio test (method in lemke.hpp, tie-break on rows of B⁻¹ in
// lemke_lexicographic.hpp).
#include "lemke_impl.hpp"

#include <algorithm>
#include <cmath>

namespace lcprelax {

// Lexicographic minimum ratio over the candidate rows `rows` (key: rows of [x_B, B⁻¹] /
// den_i). Ratios of a key column v tie with the minimum θ when v_i/den_i ≤ θ + t, with
// - for x_B: t = tol·(|θ| + 1/den_max), den_max = max den_i over the rows: relative to
//   θ, plus the roundoff of x_B seen through the largest pivot. q is normalized to
//   ‖q‖∞ = 1, so this is scale-free (resting contact has ‖q‖ ~ 1e-19). An absolute
//   ratio tolerance would make the ratios of size 1e-6 of stiff contact problems
//   (‖M‖ ~ 1e3) ties and break feasibility (granular fc2d problem);
// - for the B⁻¹ columns: t = tol·(1 + |θ|), absolute: on lcp_tobenna (bases with
//   pivots up to 4e6) anything tighter misses roundoff ties and cycles into a singular
//   basis.
// Rows of B⁻¹ are formed only for rows still tied after x_B, with their nonzeros only on
// the sparse basis (lemke_lexicographic.hpp). Returns −1 when a ratio is not finite (NaN
// or ∞ in x_B or B⁻¹: the basis has lost all accuracy).
Index LemkeSolver::Impl::lexicographic_row(const Vector& den, const Vector& x, bool prefer_z0) {
  double den_max = 0.0;
  for (Index i : rows) den_max = std::max(den_max, den(i));
  if (!detail::keep_minimal_ratio(rows, keep, ties.ratios, den, tol, 1.0 / den_max, [&](Index i) { return x(i); })) return -1;
  if (prefer_z0)
    for (Index i : rows)
      if (basic[i] == z0()) return i;
  if (rows.size() == 1) return rows.front();
  ++result.info.tie_breaks;
  return ties.reduce(rows, keep, den, tol, *basis) ? rows.front() : -1;
}

void LemkeSolver::Impl::run() {
  if (n == 0) {
    result.z.resize(0);
    result.w.resize(0);
    result.z_basic.clear();
    result.info.complementarity = 0.0;
    return finish(LcpStatus::solved, "empty problem");
  }
  long crash_pivots = 0;
  // Purification, the repair of a singular crash basis and the flips read M's columns.
  if (warm_point.size() == n || settings.crash_start) ensure_matrix();
  if (warm_point.size() == n) purify_warm_point();  // sets `warm` (lemke_purify.cpp)
  if (!warm.empty()) {
    bool factorized = load_warm_basis();
    if (!factorized && settings.crash_start && repair_warm_basis()) factorized = load_warm_basis();
    if (settings.crash_start && settings.crash_flip_rounds > 0) factorized = flip_infeasible(factorized);
    if (try_warm_start(factorized)) return;
    if (settings.crash_start && !settings.crash_cold_fallback && !factorized)
      return finish(LcpStatus::numerical_error, "crash basis is singular (no cold fallback)");
    if (factorized && settings.crash_start) {
      if (try_crash_start() || !settings.crash_cold_fallback) return;
      crash_pivots = result.info.pivots;  // a failed crash path: cold start, pivots add up
      factor_current = false;
    }
  }
  for (Index i = 0; i < n; ++i) basic[i] = i;
  if (q.minCoeff() >= 0) return extract_solution();  // z = 0 solves it
  if (!refactor(xB)) return finish(LcpStatus::numerical_error, "identity basis failed to factorize");
  pivot_from_current_basis();
  result.info.pivots += crash_pivots;
}

// a = B⁻¹ c_entering and the rows where a_i > tol (the ratio test's candidates); false if
// there are none. The rows are collected without a branch per row (rows has capacity n:
// every index is written, the count advances only where a_i > tol): on pile bases a
// large share of a solved column's entries are candidates, and a data-dependent branch
// mispredicts (with the x_B update below, 1.04-1.06x less time per step on a dropping
// 500-body pile, same pivots: bench/results/lemke_branch_free_loops.txt).
bool LemkeSolver::Impl::entering_candidates(Index entering) {
  if (!matrix_formed) ensure_matrix();  // a z column of M enters (setup(lifted, q): formed here)
  basis->solve_column(entering, a);
  rows.resize(static_cast<std::size_t>(n));
  Index count = 0;
  const double* av = a.data();
  Index* out = rows.data();
  for (Index i = 0; i < n; ++i) {
    out[count] = i;
    count += av[i] > tol;
  }
  rows.resize(static_cast<std::size_t>(count));
  return count > 0;
}

// Lemke's pivots from the factorized current basis (without z₀) and x_B = B⁻¹q: z₀
// enters at the most negative x_B,i/(B⁻¹d)_i (lexicographically on [x_B, B⁻¹]/(B⁻¹d)).
void LemkeSolver::Impl::pivot_from_current_basis(bool covered_rows_only) {
  result.info.pivots = 0;
  Index entering = z0();
  basis->solve_column(entering, a);  // = −d
  ratio_col = -a;
  rows.clear();
  if (!covered_rows_only) {
    // B⁻¹d = d > 0 from the all-w basis, = 1 for d = B·1: every row is a candidate.
    for (Index i = 0; i < n; ++i) rows.push_back(i);
  } else {
    // A crash basis with the settings' d: only rows where z₀ raises x_B (B⁻¹d > 0); a
    // negative x_B,i in any other row cannot be covered.
    for (Index i = 0; i < n; ++i) {
      if (ratio_col(i) > tol) rows.push_back(i);
      else if (xB(i) < -tol) return finish(LcpStatus::numerical_error, "the covering vector does not cover the start basis");
    }
    if (rows.empty()) return finish(LcpStatus::numerical_error, "the covering vector does not cover the start basis");
  }
  Index r = lexicographic_row(ratio_col, xB, false);
  for (long pivot = 0;; ++pivot) {
    if (r < 0) return finish(LcpStatus::numerical_error, "non-finite ratio in the minimum-ratio test (basis lost accuracy)");
    // Pivot on (r, entering): update the factorization and x_B.
    bool updated = basis->replace(r, a);
    factor_current = false;
    // x_B(r) ← x_B(r)/a_r, x_B(i) ← x_B(i) − a_i·x_B(r) elsewhere: one vectorized pass
    // over all rows (a_i = 0 leaves x_B(i) unchanged, bit for bit, as x_B(r) is finite).
    const double xr = xB(r) / a(r);
    xB.noalias() -= xr * a;
    xB(r) = xr;
    const Index leaving = basic[r];
    trace_pivot(entering, leaving);
    basic[r] = entering;
    result.info.pivots = pivot + 1;
    if (leaving == z0()) return extract_solution();
    if (result.info.pivots >= max_pivots) return finish(LcpStatus::pivot_limit, "pivot limit reached");
    if (updated && basis->update_needs_check()) {
      // An ill-conditioned update (lemke_basis.hpp): kept while the updated x_B still
      // solves B x_B = q to kUpdateResidual; a refactorization is due only past that.
      ++result.info.update_checks;
      residual_of_basic(xB, refine);
      const double scale = std::max(1.0, mnorm) * std::max(1.0, xB.lpNorm<Eigen::Infinity>());
      if (!(refine.lpNorm<Eigen::Infinity>() <= kUpdateResidual * scale)) {
        ++result.info.update_refactorizations;
        updated = false;
      }
    }
    if (!updated && !refactor(xB)) return finish(LcpStatus::numerical_error, "basis became singular");
    entering = complement(leaving, n);
    if (!entering_candidates(entering) && !factor_current) {
      // No positive entry in a column solved with an updated factorization: before calling
      // it a ray, refactorize the current basis and solve the column again (a ray can be
      // roundoff of the updates; simplex codes recheck unboundedness the same way).
      ++result.info.ray_rechecks;
      if (!refactor(xB)) return finish(LcpStatus::numerical_error, "basis became singular");
      entering_candidates(entering);
    }
    if (rows.empty()) {
      if (drop_vanished_z0(entering)) return;
      return finish(LcpStatus::ray_termination, "ray termination: no solution found by Lemke");
    }
    r = lexicographic_row(a, xB, true);
  }
}

// A ray met with z₀ already at zero (to roundoff): the almost-complementary basis then
// holds a solution of the LCP to within d·z₀ (w = Mz + q + d·z₀), and pivoting z₀ out of its
// row (a degenerate pivot: the point does not move) gives a complementary basis of it.
// `entering` (a = B⁻¹ of its column) or else the variable that just left takes z₀'s row when
// its entry there is above the pivot tolerance; the solution from a fresh factorization is
// accepted only through extract_solution's residual check. Cost: one factorization; false
// (basis changed, no solution left in the result) when it does not solve.
// Measured on a 300-body pile (run_pile_scaling --sizes 300 --models lcp --steps 13
// --warmup 0 --seed 3): 6 crash-path rays with |z₀| ≤ 1.2e-8, at pivots 110–217. In one,
// z₀ is pivoted out and the island is solved, which saves the step's cold fallback (~1.6
// pivots per unknown; bench/results/lemke_vanished_z0.txt). In the other five
// neither of the pair has an entry in z₀'s row (the column lies in the span of the other
// basic columns: every complementary basis at that point is singular); they stay rays.
bool LemkeSolver::Impl::drop_vanished_z0(Index entering) {
  Index k0 = -1;
  for (Index k = 0; k < n; ++k)
    if (basic[k] == z0()) k0 = k;
  if (k0 < 0 || std::abs(xB(k0)) * d.lpNorm<Eigen::Infinity>() > kVanishedZ0) return false;
  Index var = entering;
  if (std::abs(a(k0)) <= tol) {
    var = complement(entering, n);
    ensure_matrix();
    basis->solve_column(var, a);
    if (!a.allFinite() || std::abs(a(k0)) <= tol) return false;
  }
  basis->replace(k0, a);
  factor_current = false;
  trace_pivot(var, z0());
  basic[k0] = var;
  ++result.info.pivots;
  extract_solution();
  if (result.info.status != LcpStatus::solved) {
    discard_solution();  // the ray stands: the refused exit leaves no z, w or residual
    return false;
  }
  result.info.message = "solved (z0 vanished at a ray: the almost-complementary basis, z0 pivoted out)";
  return true;
}

}  // namespace lcprelax
