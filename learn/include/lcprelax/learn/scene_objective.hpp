#pragma once
// Learning on a multi-body scene as a learn::Objective (trainer.hpp): one sample per
// transition of a SceneDataset, ℓᵢ(θ) and ∂ℓᵢ/∂θ by one of the three step losses.
//
// evaluate(i, θ, thread):
//   1. the thread's World carries θ (SceneParameterMap::apply, done in prepare()); the
//      transition's poses and velocities are set;
//   2. the step's contacts and islands exactly as the Simulator poses them
//      (find_step_contacts: speculative margin, collision, islands; models/simulator.hpp) and
//      each island's ContactSystem (assemble_contact_system, the Simulator's own assembly);
//   3. per island the method's loss against the island bodies' observed next velocities
//      (step_loss_hard.hpp, step_loss_relaxed.hpp, step_loss_convex.hpp), pulled back to the
//      world's primitives (accumulate_world_gradient, models/contact_system_gradient.hpp),
//      then to θ (SceneParameterMap::gradient): sparse throughout, O(contacts + bodies);
//   4. dynamic bodies in no island fly freely, v⁺ = v* = v + Δt(g + u_xy/m, u_τ/I) + W f
//      (W f the velocity residual, RigidBody::velocity_residual); they add ‖v* − v̄‖² ((m/s)²,
//      weight 1 for every method), whose gradient reaches mass and inertia through the
//      applied forces (a pushed body in flight identifies its mass), and W through f.
// ℓᵢ is the sum over islands and free bodies. A transition in which any island's solve has
// no solution (ContactStatus failed) fails as a whole (SampleResult::ok = false, message
// naming the island): a failed island is never averaged in. Counts of islands and failures
// are kept (stats()).
// Relaxed method: each transition keeps its islands' last solution (λ̃n, γ) as the next
// evaluation's proximal centre (step_loss_relaxed.hpp), matched contact by contact (body
// pair and narrow-phase feature), so that over the epochs of training the convexity shift's
// bias vanishes at the cost of one solve per evaluation; a contact not seen before is
// centred at 0 (counted in stats().cold_contacts), and its island gets
// relaxed_cold_iterations proximal iterations (the biased centre 0 would otherwise enter
// that epoch's gradient). relaxed_warm_center = false: every evaluation starts centred at 0
// with the relaxed settings' proximal_iterations. The stored centres are saved in training
// checkpoints (save_state, checkpoint.hpp); stats() count this object's evaluations only.
// Hard method: each transition keeps its islands' final Lemke basis, matched contact by
// contact in the same way (which of λn, β⁺, β⁻, γ is basic), and the next evaluation starts
// Lemke from it (step_loss_hard.hpp: the warm basis, then a crash path from it). Over the
// epochs θ changes little, so the stored basis is often still feasible (zero pivots). The
// loss is the LCP's solution either way; only at a degenerate solution (z_i = w_i = 0) can
// the basis, and so the one-sided gradient, differ from a cold start's. hard_warm_basis =
// false: every evaluation starts cold. The bases are saved in checkpoints as the centres are.
// A transition whose last evaluation ended solved_inaccurate (a jammed pile's perturbed
// answer: its exact cold attempt failed) is re-solved without that attempt (step 3 of
// models/contact_step.hpp; the perturbed answer is kept, still solved_inaccurate), except on
// every kExactRetryEvery-th such evaluation in a row, which tries it again in case θ has
// moved the LCP to one that it solves. On a 300-body pile this cut an evaluation from
// 11,650 to 655 pivots (bench/results/learn_scene_hard_stored_bases.txt). The basis of an
// island whose answer was regularized (solved on M + εI) is stored marked, and the next
// evaluation starts from it on M + εI (step 1c), as the simulator does with its marked
// warm-start entries.
// Contacts are found at the CURRENT θ (a learned vertex or ground moves them), then held
// fixed while differentiating (a contact appearing or disappearing is a kink).
#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/learn/scene_params.hpp>
#include <lcprelax/learn/step_loss.hpp>
#include <lcprelax/learn/step_loss_convex.hpp>
#include <lcprelax/learn/step_loss_hard.hpp>
#include <lcprelax/learn/step_loss_relaxed.hpp>
#include <lcprelax/learn/trainer.hpp>
#include <lcprelax/models/simulator.hpp>

#include <memory>
#include <string>
#include <vector>

namespace lcprelax::learn {
namespace detail {
class ProximalCenters;
}

struct SceneLossSettings {
  LossMethod method = LossMethod::relaxed;
  HardStepLossSettings hard;
  RelaxedStepLossSettings relaxed;
  ConvexStepLossSettings convex;
  bool relaxed_warm_center = true;  ///< carry each island's proximal centre across evaluations
  int relaxed_cold_iterations = 5;  ///< proximal iterations of an island with a new contact (≥ 1)
  bool hard_warm_basis = true;      ///< hard: start each island's Lemke from its last final basis
  std::string validation_error() const;  ///< empty if valid, else names the field
};

/// Totals over all evaluations since construction (or reset_stats()).
struct SceneObjectiveStats {
  long transitions = 0;
  long islands = 0;
  long contacts = 0;
  long inaccurate_islands = 0;  ///< ContactStatus::solved_inaccurate (kept, usable)
  long failed_islands = 0;      ///< no solution: their transition failed
  long cold_contacts = 0;       ///< contacts evaluated without a stored centre (relaxed) or basis (hard)
  long proximal_solves = 0;     ///< relaxed QP solves (proximal iterations included)
  long solver_work = 0;         ///< Lemke pivots (hard) or interior-point iterations, summed
  double seconds_collision = 0.0, seconds_loss = 0.0, seconds_pullback = 0.0;
};

class SceneObjective : public Objective {
 public:
  /// Hard method: a transition re-solved without the exact cold attempt (header comment)
  /// tries it again on every kExactRetryEvery-th inaccurate evaluation in a row.
  static constexpr int kExactRetryEvery = 8;
  /// Keeps references to `data` and `map` (both must outlive the objective). Throws
  /// InputError for invalid settings, an empty or invalid dataset, or a map of another scene.
  SceneObjective(const SceneDataset& data, const SceneParameterMap& map, SceneLossSettings settings);
  ~SceneObjective() override;

  Index num_samples() const override;
  void prepare(const ParameterSet& theta, int threads) override;
  SampleResult evaluate(Index sample, const ParameterSet& theta, int thread) override;
  void save_state(StateWriter& out) const override;
  void load_state(StateReader& in) override;
  /// Empty for the convex method; the hard and relaxed methods give no residual Jacobian.
  std::string residuals_unavailable() const override;
  /// Convex method: rᵢ = v⁺ − v̄ for every body's 3 dofs (3 rows per world body, in body
  /// order; static bodies' rows are 0; free-flying bodies' v⁺ = v*), so ‖rᵢ‖² = ℓᵢ of
  /// evaluate(), and ∂rᵢ/∂θ row by row (convex_step_jacobian, pulled back like the
  /// gradient). For Gauss–Newton training (OptimizerKind::lm, least_squares.hpp).
  ResidualResult evaluate_residuals(Index sample, const ParameterSet& theta, int thread) override;

  SceneObjectiveStats stats() const;
  void reset_stats();
  /// Forgets the stored proximal centres (relaxed: the next evaluations start at 0) or final
  /// bases (hard: the next evaluations start cold).
  void reset_centers();
  const SceneLossSettings& settings() const { return settings_; }

 private:
  struct Workspace;
  /// Sets the transition's state in the thread's world, finds its contacts and islands.
  StepContacts begin_transition(Workspace& ws, Index sample, const ParameterSet& theta);
  /// Island k's ContactSystem; sets ws.target to its bodies' next velocities and marks them.
  ContactSystem island_system(Workspace& ws, const StepContacts& found, std::size_t k, const SceneTransition& t,
                              std::vector<bool>& in_island) const;
  const SceneDataset& data_;
  const SceneParameterMap& map_;
  SceneLossSettings settings_;
  std::vector<std::unique_ptr<Workspace>> workspaces_;
  std::vector<detail::ProximalCenters> centers_;  // per transition: centres (relaxed) or bases (hard)
  /// Hard method with stored bases, per transition: how many evaluations in a row ended
  /// solved_inaccurate (1…64, then 1 again: the retry cadence is kept); saved with the centres.
  std::vector<unsigned char> perturbed_runs_;
  /// Whether evaluate() keeps per-contact values between evaluations (centres or bases).
  bool keeps_contact_values() const;
};

}  // namespace lcprelax::learn
