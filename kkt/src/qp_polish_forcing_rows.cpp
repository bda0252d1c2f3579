// Step 3b of polishing (qp_polish.hpp): the smallest sign-consistent multipliers of forcing
// rows. Conventions (qp_problem.hpp): Px + q + Aᵀy + Gᵀz + z_bounds = 0, z ≤ 0 at an active
// lower side and z ≥ 0 at an active upper one.
#include "qp_polish.hpp"

#include <algorithm>
#include <limits>
#include <vector>

namespace lcprelax::detail {

int shrink_forcing_row_multipliers(const StandardForm& f, const QpProblem& p, const std::vector<signed char>& rows,
                                   const std::vector<signed char>& bounds, QpResult& cand, Vector& target) {
  int shifted = 0;
  const Index n = f.n;
  // Per variable: +1 / −1 at an active upper / lower bound, 2 fixed (free sign), 0 free.
  std::vector<signed char> state(static_cast<size_t>(n), 0);
  for (Index j = 0; j < n; ++j) state[j] = f.fixed_eq_row[j] >= 0 ? 2 : bounds[j];
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Ar = p.A, Gr = p.G;
  constexpr double inf = std::numeric_limits<double>::infinity();
  // sign: +1 ω ≥ 0, −1 ω ≤ 0, 0 free.
  auto shrink = [&](const Eigen::SparseMatrix<double, Eigen::RowMajor>& M, Index row, double& omega, int sign) {
    double lo = -inf, hi = inf;
    bool any = false;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator e(M, row); e; ++e) {
      const Index j = e.col();
      const double g = e.value();
      if (g == 0.0) continue;
      if (state[j] == 0) return;  // a free variable: not a forcing row
      any = true;
      if (state[j] == 2) continue;
      // z_b,j = t_j − gΔ must not get a wrong sign or a worse one than now: at a lower bound
      // t_j − gΔ ≤ c = max(t_j, 0), i.e. gΔ ≥ t_j − c; at an upper one t_j − gΔ ≥ c =
      // min(t_j, 0), i.e. gΔ ≤ t_j − c. Δ = 0 always qualifies.
      const double t = target(j);
      const double c = state[j] < 0 ? std::max(t, 0.0) : std::min(t, 0.0);
      const double bound = (t - c) / g;
      const bool at_least = (state[j] < 0) == (g > 0);
      if (at_least) lo = std::max(lo, bound);
      else hi = std::min(hi, bound);
    }
    if (!any) return;
    if (sign > 0) lo = std::max(lo, -omega);  // ω + Δ ≥ 0
    if (sign < 0) hi = std::min(hi, -omega);  // ω + Δ ≤ 0
    if (!(lo <= 0.0 && 0.0 <= hi)) return;    // roundoff: leave the row as it is
    const double delta = std::clamp(-omega, lo, hi);
    if (delta == 0.0) return;
    omega += delta;
    ++shifted;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator e(M, row); e; ++e) target(e.col()) -= e.value() * delta;
  };
  int total = 0;
  for (int pass = 0; pass < kForcingRowPasses; ++pass) {
    shifted = 0;
    for (Index k = 0; k < f.me; ++k) {
      if (f.eq_source[k] == EqSource::a_row) shrink(Ar, f.eq_index[k], cand.y(f.eq_index[k]), 0);
      if (f.eq_source[k] == EqSource::g_row) shrink(Gr, f.eq_index[k], cand.z(f.eq_index[k]), 0);
    }
    for (Index k = 0; k < f.mg; ++k)
      if (rows[k] != 0) shrink(Gr, f.g_index[k], cand.z(f.g_index[k]), rows[k] < 0 ? -1 : 1);
    total += shifted;
    if (shifted == 0) break;
  }
  return total;
}

}  // namespace lcprelax::detail
