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

/// Work vectors of one QpSolver, sized by resize() whenever the form is (re)built, so
/// that solve() and update() run without heap allocation.
struct Workspace {
  // Scaled space: the iteration (qp_ipm_loop.cpp).
  Vector rd, rp;                 ///< dual (n) and equality (me) residuals
  Vector dx, dy, dz;             ///< Newton step (n, me, mg)
  Vector last_dx, last_dy;       ///< previous step (infeasibility certificates)
  Vector zg, zb;                 ///< signed multipliers of rows (mg) and bounds (n)
  Vector xig, xib, rx, ry, rz, dvg;  ///< newton_step: ξ terms, right-hand sides, G̃·dx
  Vector dzb;                    ///< newton_step: signed bound-multiplier step (n)
  Vector empty;                  ///< size 0 (recover_side_steps without the bound correction)
  Vector xc, gc, rhs_x;          ///< cold start: projections and right-hand side
  // Unscaling and certificates.
  Vector yi, uzg, uzb;           ///< unscale_solution (me, mg, n)
  Vector cert_zg, cert_zb;       ///< certificate candidate's signed multipliers (mg, n)
  Vector cert_n, cert_me, cert_mg;  ///< certificate residuals (n, me, mg)
  // Unscaled space: residuals of the user's problem.
  Vector Px, Ax, Gx, Aty, Gtz;   ///< P x (n), A x (ma), G x (mi), Aᵀy (n), Gᵀz (n)
  Vector zb_saved;               ///< z_bounds before clean_bound_multipliers (n)

  void resize(const StandardForm& f, const QpProblem& p);
};

/// Maps the scaled iterate back to the user's variables and multipliers.
void unscale_solution(const StandardForm& f, const QpProblem& p, const Iterate& it, QpResult& r, Workspace& w);
Residuals compute_residuals(const QpProblem& p, const QpResult& r, Workspace& w);
/// Replaces the bound multipliers of variables at a bound by the exact componentwise
/// value (qp_bound_multipliers.cpp); needs w.Px, w.Aty, w.Gtz of r (compute_residuals).
/// Returns how many changed.
int clean_bound_multipliers(const QpProblem& p, double eps_abs, QpResult& r, Workspace& w);

/// Infeasibility certificates on a candidate direction (scaled space); on success the
/// certificate is written into r (unscaled, ∞-norm 1) and true is returned; otherwise r
/// is left untouched. Allocation-free unless a certificate is found.
bool primal_infeasibility_certificate(const StandardForm& f, const QpProblem& p, const Vector& y, const Iterate& it,
                                      bool use_steps, double eps, QpResult& r, Workspace& w);
bool dual_infeasibility_certificate(const StandardForm& f, const Vector& d, double eps, QpResult& r, Workspace& w);

}  // namespace detail

struct QpSolver::Impl {
  QpSettings settings;
  QpProblem problem;  ///< the user's data (unscaled)
  detail::StandardForm form;
  detail::KktSystem kkt;
  detail::Iterate it;
  QpResult result;
  QpInfo info;                  ///< the running solve's info (its message keeps its capacity)
  QpInfo fresh_info;            ///< QpInfo{} (copied over info: no allocation, unlike QpInfo{})
  detail::Workspace work;
  bool is_setup = false;
  bool has_warm_start = false;
  QpResult warm;                ///< warm-start point (unscaled)
  Vector Db, Dg;                ///< barrier terms of the last factorization
  double rho = 0, delta = 0;    ///< regularization of the last factorization
  double delta_rows = 0;        ///< its inequality-block part δ_g (δ, or 0 once dropped)
  double setup_seconds = 0;

  /// Copies p (compressed) and builds the standard form and the workspace.
  void build(const QpProblem& p);
  /// Copies the values of p (same pattern) into `problem` and refreshes the standard form
  /// in place; false (nothing changed) when p classifies its rows differently.
  bool refresh(const QpProblem& p);
  /// settings.kkt_backend with automatic resolved on the current form (dense_max_kkt).
  KktBackend kkt_backend() const {
    return detail::KktSystem::resolve_backend(settings.kkt_backend, form, settings.dense_max_kkt);
  }
  bool may_drop_row_regularization = true;  ///< false once a factorization with δ_g = 0 failed
  /// Second attempt after a stalled Mehrotra run (qp_ipm_loop.cpp): centring σ ≥
  /// kConservativeSigma and no second-order term in the corrector.
  bool conservative = false;
  bool factorize(QpInfo& info);
  /// Newton step for work.rd, work.rp and the sides' rc into work.dx, dy, dz and the
  /// sides' ds, dz; returns refinement steps.
  int newton_step();
  bool initial_point(QpInfo& info);  ///< false if the factorization failed
  void run(QpInfo& info);
};

}  // namespace lcprelax
