// QpSolver::solve(): the attempts of one solve (see qp_solver.hpp): the Mehrotra run, the
// conservative second run after a stall, the multiplier-scaled third run, polishing and the
// infeasibility LPs.
#include "qp_infeasibility_lp.hpp"
#include "qp_solver_impl.hpp"

#include <algorithm>
#include <lcprelax/core/stopwatch.hpp>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lcprelax {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

const QpResult& QpSolver::solve() {
  Impl& m = *impl_;
  if (!m.is_setup) throw std::logic_error("QpSolver::solve before setup");
  const auto t0 = Clock::now();
  m.solve_start = t0;
  // The result's vectors keep their storage (run() overwrites them); info starts afresh.
  // Copying fresh_info reuses the message's capacity, where QpInfo{} would allocate.
  m.result.info = m.fresh_info;
  QpInfo& info = m.info;
  info = m.fresh_info;
  info.message.clear();
  info.kkt_form = m.kkt.form();
  info.kkt_backend = m.kkt.backend();
  m.run(info);
  // Polishing (qp_polish.hpp) while the time limit allows, of the run whose outcome is
  // reported: a numerical_error gets the conservative second run first (an interior-point
  // answer, whose multipliers are the central ones where they are not unique: what the
  // learning losses differentiate), and polishing only where that run ends without `solved`.
  const auto polish_in_time = [&](QpInfo& i) {
    if (!m.out_of_time(m.predicted_factor_seconds())) m.polish(i);
  };
  const bool rerun = info.status == QpStatus::numerical_error && !m.out_of_time(m.predicted_factor_seconds());
  if (!rerun) polish_in_time(info);
  if (rerun) {
    // Mehrotra's corrector can cycle on degenerate problems (relaxed-LCP QPs of the polygon
    // loss whose μ alternates between two values until "no progress"). One more run from
    // the start, with σ ≥ 0.1 and no second-order term (a plain primal–dual path-following
    // step), before the failure is reported; the first run's outcome is kept if it fails too.
    const QpResult first_result = m.result;
    const QpInfo first_info = info;
    const detail::Iterate first_iterate = m.it;  // polishing starts from the reported run's iterate
    const double growth = m.multiplier_growth(first_iterate);  // before the next run resets start_zmax
    QpInfo second;
    second.kkt_form = info.kkt_form;
    second.kkt_backend = info.kkt_backend;
    m.conservative = true;
    m.run(second);
    m.conservative = false;
    if (has_solution(second.status)) {
      polish_in_time(second);
      second.iterations += first_info.iterations;
      second.refinement_steps += first_info.refinement_steps;
      second.message = std::string(to_string(second.status)) + " by the conservative second run (first run: " +
                       first_info.message + ")";
      info = second;
    } else {
      QpInfo third;
      const bool scaled_run = m.settings.multiplier_restart_growth > 0 && growth >= m.settings.multiplier_restart_growth &&
                              !m.out_of_time(m.predicted_factor_seconds());
      if (scaled_run) {
        third.kkt_form = info.kkt_form;
        third.kkt_backend = info.kkt_backend;
        m.start_multiplier_scale = growth;
        m.run(third);
        m.start_multiplier_scale = 1.0;
      }
      if (scaled_run && has_solution(third.status)) {
        polish_in_time(third);
        third.iterations += first_info.iterations + second.iterations;
        third.refinement_steps += first_info.refinement_steps + second.refinement_steps;
        third.message = std::string(to_string(third.status)) + " by the multiplier-scaled third run (first run: " +
                        first_info.message + "; conservative second run: " + to_string(second.status) + ")";
        info = third;
      } else {
        m.result = first_result;
        m.it = first_iterate;
        info = first_info;
        info.iterations += second.iterations + third.iterations;
        info.message += std::string("; conservative second run: ") + to_string(second.status);
        if (scaled_run) info.message += std::string("; multiplier-scaled third run: ") + to_string(third.status);
        polish_in_time(info);
      }
    }
  }
  if (m.settings.infeasibility_lps && !m.out_of_time(0.0) &&
      (info.status == QpStatus::max_iterations || info.status == QpStatus::numerical_error)) {
    // The auxiliary LPs get what is left of the time limit (each its own solver).
    QpSettings lp_settings = m.settings;
    const auto remaining = [&] { return std::max(m.settings.time_limit - m.elapsed(), 1e-3); };
    lp_settings.time_limit = remaining();
    QpResult cert = m.result;
    if (detail::prove_primal_infeasible(m.problem, lp_settings, cert)) {
      m.result = cert;
      info.status = QpStatus::primal_infeasible;
      info.message = "primal infeasible (certificate from the auxiliary LP) after: " + info.message;
    } else if (!m.out_of_time(0.0) &&
               (lp_settings.time_limit = remaining(), detail::prove_dual_infeasible(m.problem, lp_settings, cert))) {
      m.result = cert;
      info.status = QpStatus::dual_infeasible;
      info.message = "dual infeasible (certificate from the auxiliary LP) after: " + info.message;
    }
  }
  info.kkt_factor_nnz = m.kkt.factor_nnz();
  info.reg_primal = m.rho;
  info.reg_dual = m.delta;
  if (m.result.x.size() == m.problem.num_variables() && info.status != QpStatus::dual_infeasible) {
    // ½xᵀPx + qᵀx + r (QpProblem::objective, on the work vector Px).
    const Vector& x = m.result.x;
    Vector& Px = m.work.Px;
    Px.noalias() = m.problem.P.selfadjointView<Eigen::Upper>() * x;
    info.objective = 0.5 * x.dot(Px) + m.problem.q.dot(x) + m.problem.r;
  }
  // Never `solved` with a non-finite number (data near the overflow threshold can give an
  // infinite objective or multiplier while the scaled residuals still look converged).
  if (has_solution(info.status) &&
      !(m.result.x.allFinite() && m.result.y.allFinite() && m.result.z.allFinite() && m.result.z_bounds.allFinite() &&
        std::isfinite(info.objective) && std::isfinite(info.primal_residual) && std::isfinite(info.dual_residual) &&
        std::isfinite(info.duality_gap))) {
    info.status = QpStatus::numerical_error;
    info.message = "the solution has a non-finite entry (overflow: data too large for doubles)";
  }
  info.setup_seconds = m.setup_seconds;
  info.solve_seconds = seconds_since(t0);
  if (info.message.empty()) info.message = to_string(info.status);
  m.result.info = info;
  m.has_warm_start = false;
  return m.result;
}

}  // namespace lcprelax
