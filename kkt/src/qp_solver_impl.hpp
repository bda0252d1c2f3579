#pragma once
// QpSolver's private state, shared by the solver's translation units (internal).
#include "ipm_iterate.hpp"
#include "kkt_system.hpp"
#include "standard_form.hpp"

#include <lcprelax/kkt/qp_solver.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace lcprelax {

namespace detail {

/// Unscaled residuals of a candidate solution (see QpSettings for the definitions).
struct Residuals {
  double primal = 0, dual = 0, gap = 0;
  double scale_p = 0, scale_d = 0, scale_g = 0;
};

/// Whether all three residuals are within factor·(eps_abs + eps_rel·scale).
inline bool within(const Residuals& r, const QpSettings& s, double factor) {
  return r.primal <= factor * (s.eps_abs + s.eps_rel * r.scale_p) &&
         r.dual <= factor * (s.eps_abs + s.eps_rel * r.scale_d) &&
         r.gap <= factor * (s.eps_abs + s.eps_rel * r.scale_g);
}

/// Worst ratio of residual to tolerance (∞ when a residual is not finite).
inline double merit_of(const Residuals& r, const QpSettings& s) {
  if (!std::isfinite(r.primal) || !std::isfinite(r.dual) || !std::isfinite(r.gap))
    return std::numeric_limits<double>::infinity();
  return std::max({r.primal / (s.eps_abs + s.eps_rel * r.scale_p), r.dual / (s.eps_abs + s.eps_rel * r.scale_d),
                   r.gap / (s.eps_abs + s.eps_rel * r.scale_g)});
}

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
  Vector saved_dx, saved_dy, saved_dz;  ///< centrality correctors: the step being improved
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
/// The same with caller-owned product vectors P x, A x, G x, Aᵀy, Gᵀz (assigned here; no
/// allocation once sized): DenseQpSolver's termination test.
Residuals compute_residuals(const QpProblem& p, const QpResult& r, Vector& Px, Vector& Ax, Vector& Gx, Vector& Aty,
                            Vector& Gtz);
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
  /// Time limit bookkeeping: QpSettings::time_limit counts from the start of solve() and
  /// covers both runs, polishing and the infeasibility LPs. A numeric factorization cannot
  /// be interrupted, so none is started when the predicted time (the last measured one, or
  /// before any the analysis' flop count at kAssumedFlopRate) would pass the limit.
  std::chrono::steady_clock::time_point solve_start{};
  double last_factor_seconds = 0;  ///< wall time of the last numeric KKT factorization
  static constexpr double kAssumedFlopRate = 1e9;  ///< flops/s before the first measurement
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - solve_start).count();
  }
  double predicted_factor_seconds() const {
    return last_factor_seconds > 0 ? last_factor_seconds : kkt.factor_flops() / kAssumedFlopRate;
  }
  /// Whether `upcoming` more seconds would pass time_limit.
  bool out_of_time(double upcoming) const { return elapsed() + upcoming > settings.time_limit; }

  /// Copies p (compressed) and builds the standard form and the workspace.
  void build(const QpProblem& p);
  /// Copies the values of p (same pattern) into `problem` and refreshes the standard form
  /// in place; false (nothing changed) when p classifies its rows differently.
  bool refresh(const QpProblem& p);
  /// settings.kkt_backend with automatic resolved on the current form (dense_max_kkt).
  /// Throws for a failed KktSystem::setup: InputError when the user chose the dense backend
  /// for a system above its size limit, else std::runtime_error.
  [[noreturn]] void kkt_setup_failed(const char* where, const std::string& message) const;
  KktBackend kkt_backend() const {
    return detail::KktSystem::resolve_backend(settings.kkt_backend, form, settings.dense_max_kkt);
  }
  bool may_drop_row_regularization = true;  ///< false once a factorization with δ_g = 0 failed
  bool primal_reg_dropped = false;          ///< ρ lowered to QpSettings::primal_reg_drop in this run
  /// Second attempt after a stalled Mehrotra run (qp_ipm_loop.cpp): centring σ ≥
  /// kConservativeSigma and no second-order term in the corrector.
  bool conservative = false;
  /// Factor by which the cold start's multipliers are multiplied (1 except in the
  /// multiplier-scaled third run, qp_solve.cpp; QpSettings::multiplier_restart_growth).
  double start_multiplier_scale = 1.0;
  /// Largest multiplier of the cold start (after the scale), set by initial_point().
  double start_zmax = 0.0;
  /// How many times the largest multiplier of `final` exceeds start_zmax of the run that
  /// produced it (qp_solve.cpp's first run).
  double multiplier_growth(const detail::Iterate& final) const;
  bool factorize(QpInfo& info);
  /// Newton step for work.rd, work.rp and the sides' rc into work.dx, dy, dz and the
  /// sides' ds, dz; returns refinement steps.
  int newton_step();
  /// Gondzio's multiple centrality correctors (qp_ipm_loop.cpp) on the step in work.dx,
  /// dy, dz and the sides' ds, dz, whose rc holds its complementarity right-hand side;
  /// `amax` is that step's largest feasible length, `mu_target` = σμ. Returns the largest
  /// feasible length of the step kept; counts the accepted correctors in info.
  double centrality_correctors(double amax, double mu_target, QpInfo& info);
  bool initial_point(QpInfo& info);  ///< false if the factorization failed
  /// it.x, it.y and work.zg, work.zb from an unscaled point (x, y, z, z_bounds) of the
  /// problem (warm starts, polishing), then the side residuals (vg = G̃x̃).
  void load_unscaled_point(const Vector& x, const Vector& y, const Vector& z, const Vector& z_bounds);
  void run(QpInfo& info);
  /// Solution polishing after a run that ended solved_inaccurate, numerical_error or
  /// max_iterations (QpSettings::polish; qp_polish.hpp): replaces result and the status
  /// when the polished point is accepted, records the attempt in info.
  void polish(QpInfo& info);
  /// After an accepted polish: the scaled iterate becomes the polished point (slacks and
  /// multipliers at complementarity kPolishMu, qp_polish.hpp) and the KKT matrix is
  /// factorized there for backward(); false if that factorization failed.
  bool adopt_polished_point(QpInfo& info);
};

}  // namespace lcprelax
