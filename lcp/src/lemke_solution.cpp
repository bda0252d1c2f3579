// The solution from the final basis (a fresh factorization, z clipped or not, the residual
// check that decides `solved`) and backward() with that basis (lemke.hpp).
#include "lemke_impl.hpp"

#include <lcprelax/core/errors.hpp>

#include <stdexcept>
#include <string>

namespace lcprelax {

// Fills z, w, z_basic from a fresh factorization of the current basis (kept for
// backward()); checks the residual.
void LemkeSolver::Impl::extract_solution(bool xb_is_current) {
  // (res_tol = 0 when q = 0: then z = 0 is exact and the residual is 0.)
  take(result.z, z_spare);
  result.z.setZero();
  if (!xb_is_current && !refactor(xB)) return finish(LcpStatus::numerical_error, "final basis is singular");
  result.z_basic.assign(static_cast<std::size_t>(n), false);
  for (Index k = 0; k < n; ++k)
    if (basic[k] >= n && basic[k] < 2 * n) {
      result.z(basic[k] - n) = xB(k) * q_norm;
      result.z_basic[basic[k] - n] = true;
    }
  take(result.w, w_spare);
  // z = x_B as computed, and z clipped at 0: a basis that is feasible only to roundoff
  // (x_B,i ~ −1e-11 of a basic z_i; the lexicographic ratio test admits ties within its
  // tolerance) gives w = Mz + q exact in the first, while clipping moves w by ‖M‖·|x_B,i|
  // in other rows (granular fc2d, 2,020 contacts: 2.2e-9 against 4.8e-11). The one with
  // the smaller complementarity residual is returned (the clipped one on a tie).
  apply_matrix(result.z, refine);
  result.w = refine + q_user;
  const double unclipped = n ? result.z.cwiseMin(result.w).cwiseAbs().maxCoeff() : 0.0;
  if (n && result.z.minCoeff() < 0.0) {
    z_clip = result.z.cwiseMax(0.0);
    apply_matrix(z_clip, w_clip);
    w_clip += q_user;
    const double clipped = z_clip.cwiseMin(w_clip).cwiseAbs().maxCoeff();
    if (clipped <= unclipped) {
      result.z = z_clip;
      result.w = w_clip;
    }
    result.info.complementarity = std::min(clipped, unclipped);
  } else {
    result.info.complementarity = unclipped;
  }
  // Overflow (data near 1e308: z = x_B·‖q‖∞ or w = Mz + q beyond the double range) leaves
  // min(z, w) finite or 0 where w = ∞: never `solved` with a non-finite z or w.
  if (!result.z.allFinite() || !result.w.allFinite())
    finish(LcpStatus::numerical_error, "z or w has a non-finite entry (overflow: data too large for doubles)");
  else if (result.info.complementarity <= res_tol) finish(LcpStatus::solved, "solved");
  else finish(LcpStatus::numerical_error, "complementarity residual above tolerance after refactorization");
}

LcpGradient LemkeSolver::backward(const Vector& dl_dz) const {
  const Impl& m = *impl_;
  if (!has_solution(m.result.info.status))
    throw std::logic_error(std::string("LemkeSolver::backward needs status solved, status is ") +
                           to_string(m.result.info.status));
  if (dl_dz.size() != m.n || !dl_dz.allFinite()) throw InputError("LCP backward: dl_dz must be finite, size n");
  LcpGradient g;
  g.dq = Vector::Zero(m.n);
  m.ensure_matrix();  // dM has M's pattern
  g.dM = m.M;
  if (m.n > 0) {
    Vector gb = Vector::Zero(m.n);
    for (Index k = 0; k < m.n; ++k)
      if (m.basic[k] >= m.n && m.basic[k] < 2 * m.n) gb(k) = dl_dz(m.basic[k] - m.n);
    m.basis->solve_transposed(gb);  // λ = B⁻ᵀ g, with the final factorization
    g.dq = gb;
  }
  for (Index j = 0; j < g.dM.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(g.dM, j); it; ++it) it.valueRef() = g.dq(it.row()) * m.result.z(j);
  return g;
}

}  // namespace lcprelax
