#pragma once
// QpSolver's private state, shared by the solver's translation units (internal).
#include "ipm_iterate.hpp"
#include "kkt_system.hpp"
#include "standard_form.hpp"

#include <lcprelax/kkt/qp_solver.hpp>

namespace lcprelax {

namespace detail {

/// Unscaled residuals of a candidate solution (see QpSettings for the definitions).
struct Residuals {
  double primal = 0, dual = 0, gap = 0;
  double scale_p = 0, scale_d = 0, scale_g = 0;
};

/// Maps the scaled iterate back to the user's variables and multipliers.
void unscale_solution(const StandardForm& f, const QpProblem& p, const Iterate& it, QpResult& r);
Residuals compute_residuals(const QpProblem& p, const QpResult& r);

/// Infeasibility certificates on a candidate direction (scaled space); on success the
/// certificate is written into r (unscaled, ∞-norm 1) and true is returned; otherwise r
/// is left untouched.
bool primal_infeasibility_certificate(const StandardForm& f, const QpProblem& p, const Vector& y, const Iterate& it,
                                      bool use_steps, double eps, QpResult& r);
bool dual_infeasibility_certificate(const StandardForm& f, const Vector& d, double eps, QpResult& r);

}  // namespace detail

struct QpSolver::Impl {
  QpSettings settings;
  QpProblem problem;  ///< the user's data (unscaled)
  detail::StandardForm form;
  detail::KktSystem kkt;
  detail::Iterate it;
  QpResult result;
  bool is_setup = false;
  bool has_warm_start = false;
  QpResult warm;                ///< warm-start point (unscaled)
  Vector Db, Dg;                ///< barrier terms of the last factorization
  double rho = 0, delta = 0;    ///< regularization of the last factorization
  double delta_rows = 0;        ///< its inequality-block part δ_g (δ, or 0 once dropped)
  double setup_seconds = 0;

  void build(const QpProblem& p);
  /// settings.kkt_backend with automatic resolved on the current form (dense_max_kkt).
  KktBackend kkt_backend() const {
    return detail::KktSystem::resolve_backend(settings.kkt_backend, form, settings.dense_max_kkt);
  }
  bool may_drop_row_regularization = true;  ///< false once a factorization with δ_g = 0 failed
  /// Second attempt after a stalled Mehrotra run (qp_ipm_loop.cpp): centring σ ≥
  /// kConservativeSigma and no second-order term in the corrector.
  bool conservative = false;
  bool factorize(QpInfo& info);
  /// Newton step for the current rd, rp and side rc; returns refinement steps.
  int newton_step(const Vector& rd, const Vector& rp, Vector& dx, Vector& dy, Vector& dz);
  bool initial_point(QpInfo& info);  ///< false if the factorization failed
  void run(QpInfo& info);
};

}  // namespace lcprelax
