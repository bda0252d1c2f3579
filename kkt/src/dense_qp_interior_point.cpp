// DenseQpSolver's interior point: Mehrotra's predictor-corrector on the dense normal
// equations K = P + Cᵀ diag(λ/s) C (+ρI) and, with equality rows, their Schur complement,
// both by dense Cholesky (method, conventions: dense_qp_solver.hpp).
#include "dense_qp_impl.hpp"

#include <algorithm>
#include <cmath>

namespace lcprelax {
namespace dense_qp_interior_point_detail {

constexpr int kDenseMaxIterations = 60;  // then QpSolver takes over
constexpr double kStepToBoundary = 0.99;
constexpr int kRegRaises = 8;

// Largest α ≤ 1 with v + α dv ≥ 0.
double max_step(const Vector& v, const Vector& dv) {
  double a = 1.0;
  for (Index k = 0; k < v.size(); ++k)
    if (dv(k) < 0) a = std::min(a, -v(k) / dv(k));
  return a;
}

}  // namespace dense_qp_interior_point_detail

using namespace dense_qp_interior_point_detail;

int DenseQpSolver::Impl::max_interior_point_iterations() const { return std::min(kDenseMaxIterations, settings.max_iter); }

bool DenseQpSolver::Impl::factorize(const Vector& dk) {
  double reg = reg_base;
  for (int attempt = 0; attempt <= kRegRaises; ++attempt, reg *= 10.0) {
    Drow.setZero();
    K = P;
    for (Index k = 0; k < mc; ++k) {
      const Side& sd = sides[static_cast<std::size_t>(k)];
      if (sd.on_g_row)
        Drow(sd.gi_row) += dk(k);
      else
        K(sd.index, sd.index) += dk(k);
    }
    for (Index r = 0; r < Gi.rows(); ++r)
      if (Drow(r) != 0.0) K.noalias() += (Drow(r) * Gi.row(r).transpose()) * Gi.row(r);
    K.diagonal().array() += reg;
    if (!llt_K.compute(K)) continue;
    if (me == 0) return true;
    W = Ae.transpose();
    llt_K.solve_lower_columns(W);
    S.noalias() = W.transpose().lazyProduct(W);
    S.diagonal().array() += reg;
    if (llt_S.compute(S)) return true;
  }
  return false;
}

void DenseQpSolver::Impl::solve_reduced(const Vector& rhs_x, const Vector& rhs_e, Vector& out_x, Vector& out_y) {
  f = rhs_x;
  if (me > 0) {
    // S y = rhs_e − Ae K⁻¹ f, then x = K⁻¹(f + Aeᵀ y)  (K x − Aeᵀ y = f, Ae x = rhs_e).
    tmp_n = f;
    llt_K.solve_in_place(tmp_n);
    tmp_me.noalias() = Ae * tmp_n;
    tmp_me = rhs_e - tmp_me;
    out_y = tmp_me;
    llt_S.solve_in_place(out_y);
    f.noalias() += Ae.transpose() * out_y;
  }
  out_x = f;
  llt_K.solve_in_place(out_x);
}

bool DenseQpSolver::Impl::run_dense() {
  QpInfo& info = result.info;
  info.iterations = 0, info.factorizations = 0;
  factorized_at_final = false;
  // Start: minimize ½xᵀPx + qᵀx + ½‖Cx − d‖² on Ae x = be, then s = max(Cx − d, 1), λ = 1.
  lam.setOnes();
  if (!factorize(lam)) return false;
  ++info.factorizations;
  apply_Ct(d, tmp_n);
  rd = tmp_n - problem.q;
  solve_reduced(rd, be, x, y);  // K x − Aeᵀ y = Cᵀd − q, Ae x = be
  apply_C(x, cx);
  s = (cx - d).cwiseMax(1.0);
  const int max_iter = max_interior_point_iterations();
  for (int it = 0;; ++it) {
    info.iterations = it;
    if (!x.allFinite() || !y.allFinite() || !s.allFinite() || !lam.allFinite()) return false;
    // Residuals of Px + q − Aeᵀy − Cᵀλ = 0, Ae x = be, Cx − s = d.
    rd.noalias() = P * x;
    rd += problem.q;
    if (me > 0) rd.noalias() -= Ae.transpose() * y;
    apply_Ct(lam, tmp_n);
    rd -= tmp_n;
    if (me > 0) {
      re.noalias() = Ae * x;
      re -= be;
    }
    apply_C(x, cx);
    rp = cx - s - d;
    const double mu = mc > 0 ? s.dot(lam) / static_cast<double>(mc) : 0.0;
    // The test on the user's residuals, once complementarity is near the tolerance (with a
    // relative tolerance, every iteration).
    const bool near = settings.eps_rel > 0 || static_cast<double>(mc) * mu <= 10.0 * settings.eps_abs;
    if (near && fill_result_and_check()) {
      // The adjoint system at the final iterate, for backward().
      if (!factorize_adjoint()) return false;
      ++info.factorizations;
      factorized_at_final = true;
      return true;
    }
    if (it >= max_iter) return false;
    w = lam.cwiseQuotient(s);
    if (!factorize(w)) return false;
    ++info.factorizations;
    // Direction for a complementarity target rc (λ∘s − target):
    //   K dx − Aeᵀdy = −rd − Cᵀ S⁻¹(rc + Λ rp),  Ae dx = −re,
    //   ds = C dx + rp,  dλ = −S⁻¹(rc + Λ ds).
    auto direction = [&] {
      dlam = (rc + lam.cwiseProduct(rp)).cwiseQuotient(s);
      apply_Ct(dlam, tmp_n);
      tmp_n = -rd - tmp_n;
      dx = tmp_n;
      solve_reduced(dx, -re, dx, dy);
      apply_C(dx, ds);
      ds += rp;
      dlam = -(rc + lam.cwiseProduct(ds)).cwiseQuotient(s);
    };
    rc = s.cwiseProduct(lam);
    direction();
    double alpha = std::min(max_step(s, ds), max_step(lam, dlam));
    if (mc > 0) {
      const double mu_aff = (s + alpha * ds).dot(lam + alpha * dlam) / static_cast<double>(mc);
      const double sigma = std::pow(mu_aff / mu, 3);
      rc = s.cwiseProduct(lam) + ds.cwiseProduct(dlam);
      rc.array() -= sigma * mu;
      direction();
      alpha = std::min(1.0, kStepToBoundary * std::min(max_step(s, ds), max_step(lam, dlam)));
    }
    x += alpha * dx, y += alpha * dy, s += alpha * ds, lam += alpha * dlam;
  }
}

}  // namespace lcprelax
