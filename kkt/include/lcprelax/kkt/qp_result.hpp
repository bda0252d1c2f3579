#pragma once
// Status, per-solve information and solution of the interior-point QP solver.
// Info fields start at sentinel values (status unsolved, NaN residuals) so that reading
// a result before solve() is obvious.
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/sparse/types.hpp>

#include <cmath>
#include <limits>
#include <string>

namespace lcprelax {

/// The outcome of a solve. Misuse of the API (setup() not called, wrong sizes, NaN data,
/// invalid settings) is not a status: it throws InputError.
enum class QpStatus {
  unsolved,           ///< solve() was not called
  solved,             ///< residuals and gap within eps
  solved_inaccurate,  ///< the iteration stalled (no progress) with residuals and gap within 1e3·eps
  primal_infeasible,  ///< certificate in QpResult::y, z, z_bounds (see below)
  dual_infeasible,    ///< certificate (an unbounded direction) in QpResult::x
  max_iterations,     ///< QpSettings::max_iter reached before eps (x is the last iterate)
  time_limit,         ///< QpSettings::time_limit reached before eps (x is the last iterate)
  numerical_error     ///< stalled above 1e3·eps, or the KKT system could not be factorized
};

constexpr const char* to_string(QpStatus s) {
  switch (s) {
    case QpStatus::unsolved: return "unsolved";
    case QpStatus::solved: return "solved";
    case QpStatus::solved_inaccurate: return "solved_inaccurate";
    case QpStatus::primal_infeasible: return "primal_infeasible";
    case QpStatus::dual_infeasible: return "dual_infeasible";
    case QpStatus::max_iterations: return "max_iterations";
    case QpStatus::time_limit: return "time_limit";
    case QpStatus::numerical_error: return "numerical_error";
  }
  return "unknown";
}

/// Whether a result with this status carries a usable solution (solved, or solved to
/// 1e3·eps where the iteration stalled); the one test every caller uses.
constexpr bool has_solution(QpStatus s) { return s == QpStatus::solved || s == QpStatus::solved_inaccurate; }

struct QpInfo {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  QpStatus status = QpStatus::unsolved;
  std::string message = "solve() was not called";
  int iterations = 0;
  double objective = nan;        ///< ½xᵀPx + qᵀx + r
  double primal_residual = nan;  ///< see QpSettings (unscaled, ∞-norm)
  double dual_residual = nan;
  double duality_gap = nan;
  double reg_primal = nan;       ///< final static regularizations (scaled problem)
  double reg_dual = nan;
  int factorizations = 0;        ///< numeric KKT factorizations in this solve()
  int factor_retries = 0;        ///< factorizations repeated with raised regularization
  int refinement_steps = 0;      ///< total iterative-refinement steps
  int centrality_correctors = 0; ///< accepted Gondzio correctors (QpSettings::centrality_correctors)
  KktForm kkt_form = KktForm::automatic;  ///< the form actually used
  KktBackend kkt_backend = KktBackend::automatic;  ///< the backend actually used
  long kkt_factor_nnz = 0;       ///< nnz of the KKT factor
  double setup_seconds = 0.0;
  double solve_seconds = 0.0;
  double factor_seconds = 0.0;   ///< part of solve_seconds spent factorizing
  double backward_seconds = 0.0; ///< last backward()
  /// Solution polishing (QpSettings::polish): whether it ran (the interior point ended
  /// solved_inaccurate, numerical_error or max_iterations), how many reduced KKT systems it
  /// factorized, and whether its point replaced the interior point's (then message says so
  /// and the residuals above are the polished point's).
  bool polish_attempted = false;
  bool polish_accepted = false;
  int polish_rounds = 0;
  double polish_seconds = 0.0;   ///< part of solve_seconds spent polishing
};

/// Certificates: for primal_infeasible, (y, z, z_bounds) normalized to ∞-norm 1 satisfy
/// Aᵀy + Gᵀz + z_bounds ≈ 0 and bᵀy + Σ u_i z_i⁺ − l_i z_i⁻ + (same for bounds) < 0;
/// for dual_infeasible, x normalized to ∞-norm 1 satisfies Px ≈ 0, Ax ≈ 0, Gx within the
/// recession cone of [l,u], and qᵀx < 0.
struct QpResult {
  Vector x;         ///< n primal solution
  Vector y;         ///< me equality multipliers
  Vector z;         ///< mi row multipliers (> 0 upper active, < 0 lower active)
  Vector z_bounds;  ///< n bound multipliers (> 0 upper active, < 0 lower active)
  QpInfo info;
};

}  // namespace lcprelax
