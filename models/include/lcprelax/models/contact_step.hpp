#pragma once
// One island's contact impulses for a velocity-level time step, by either contact model
// (docs/formulations.md). Δt in s, impulses in N·s, velocities in m/s and rad/s.
//
// Both models use the gap term max(φ, 0)/Δt: a contact inside the margin may close its
// gap during the step but never gets a push-out velocity from a penetration (that would
// add kinetic energy); penetration is removed at position level by the simulator's
// post-stabilization (simulator.hpp). Exception: a material pair with normal softness
// (compliance c, erp e; world.hpp FrictionTable) gives the lcp model's normal row
// Jn v⁺ + (max(φ,0) + e·min(φ,0))/Δt + c·λn (an implicit spring–damper); the convex model
// adds c and the push-out −e·min(φ,0)/Δt to its normal softening (normal_softening.hpp).
//
// lcp (Stewart & Trinkle 1996; Anitescu & Potra 1997), unknowns z = [λn, β⁺, β⁻, γ]
// (β± per friction row, λt = β⁺ − β⁻, γ the sliding speed):
//     0 ≤ λn ⊥ Jn v⁺ + max(φ,0)/Δt ≥ 0
//     0 ≤ β⁺ ⊥  Jt v⁺ + γ ≥ 0,   0 ≤ β⁻ ⊥ −Jt v⁺ + γ ≥ 0
//     0 ≤ γ  ⊥ μ λn − β⁺ − β⁻ ≥ 0,            v⁺ = v* + M⁻¹(Jnᵀλn + Jtᵀλt),
// an LCP in z with M assembled sparse from W = J M⁻¹ Jᵀ, solved by Lemke.
//   Resting stacks and pyramids make this LCP highly degenerate (q = 0 on every friction
//   row and on the normal rows between bodies that fall together; W singular where there
//   are more contact rows than degrees of freedom), and from a cold start Lemke then can
//   end on a secondary ray or a singular basis by roundoff. solve_lcp_model therefore
//   tries, cheapest first, with Lemke's own retries only in the last attempt:
//   1. the warm basis (if given and some z is basic in it: the all-w basis is step 2's cold
//      start) where its basic solution on q is feasible (no pivots), factorized and checked
//      in M's lifted form alone: M (and W) are formed only when step 1 fails
//      (StewartTrinkleLcpSource, lcp_model_attempts.hpp);
//   1b. a crash path (LemkeSettings::crash_start) from the warm basis on the perturbed q of
//      step 2 (first pattern), at most kLcpWarmCrashPivotsPerUnknown pivots per unknown,
//      then the polish of step 2; when the path ends on a ray within its first pivots, the
//      contacts it touched are taken back in the warm basis and it runs again
//      (kLcpWarmRayRestarts); if the crash path fails, step 2 runs as without a warm
//      basis; if only the polish fails, the crash path's solution is kept as the inexact
//      fallback and step 2 is skipped (its first pattern is the same perturbed LCP: the cold
//      path would end at the same basis and fail the same polish; on a 500-body pile this
//      halved the pivots per step, bench/README.md);
//   1c. when the warm basis is that of a regularized answer (step 4 below) or of a failed
//      step (solve_lcp_model's warm_from_regularized; the simulator marks such contacts'
//      warm-start entries, ContactWarmRecord::regularized), before step 1b (which then runs
//      only if 1c found nothing): step 1b's crash path, with its ray restarts, on
//      M + εI (step 4's regularization) from the warm basis, then step 4's polish on (M, q)
//      (skipped with accept_perturbed, as 1b's is: on a settled 1,000-body pile it failed on
//      every resting step and took two thirds of its solve time); failing that, its
//      solution is kept as the regularized fallback (step 4's residual bound), and step 2
//      is skipped (as after 1b's perturbed answer); it is taken when step 3 fails, or at
//      once with accept_perturbed. With accept_perturbed step 1 is skipped before it (the
//      warm basis is one of M + εI; on the settled 1,000-body pile it never solved M), and
//      1c's first path factorizes in step 1's warm_factorization, whose symbolic analysis
//      is then reused while the island rests (0.112 → 0.095 s per step there). A settled
//      pile loads more contacts than its bodies have degrees of freedom: a regularized
//      answer's basis is then singular in M, step 1b cannot start from it, and the cold
//      paths on 12,000–16,000 unknowns run to their caps, while on M + εI the same basis
//      solves the next step in 0–200 pivots, where step 1b on M from it once ran to its cap
//      (61,101 pivots, a refactorization every 3: 240 s). After an exact or perturbed answer 1c runs
//      last instead (step 6): its paths on M + εI refactorize about three times as often as
//      on M (the bases of M + εI are near-singular where M's are singular), and on 500-body
//      drops step 2 usually solves exactly where 1c would give an inexact answer;
//   2. Lemke from the all-w basis on the perturbed q + δu, δ = kLcpPerturbation·‖q‖∞,
//      u_i ∈ [½, 1) pseudo-random per row (deterministic, lcp_perturbation_pattern): distinct
//      positive offsets break the ties of the degenerate pivots (the perturbation that the
//      lexicographic rule only simulates, made real: in floating point the rule's tie
//      tolerance lets large degenerate piles cycle or end on a ray). u is a hash of the
//      row's contact identity (ContactSystem::ids), so that a
//      contact keeps its offsets from step to step, and the degenerate ties are broken the
//      same way as in the previous step, whose basis is step 1b's warm start. Each attempt
//      is capped at kLcpExactPivotsPerUnknown pivots per unknown. Its solution's basis then starts a crash
//      path on q of at most n/10 pivots ("polish"; no cold start after it), with the
//      covering vector B·1 and, where that path fails, along u (the homotopy from q + θu,
//      θ ≤ δ, back to q; LemkeSettings::crash_covering_from_basis = false): exact, so resting
//      bodies stay exactly at rest and the next step is warm-started. On 200- and 500-body
//      piles the first polish fails on about half of the steps (a ray or a singular basis
//      after 100–900 pivots) and the second rescues about a third of those. Up to
//      kLcpPerturbationSeeds patterns, δ ten times larger for each next one, until one
//      runs to its cap (a larger δ breaks ties and turns rays; it does not shorten a long
//      path: on a 1,000-body drop the three seeds ran to the same cap, 38–66 s each);
//   3. when no polish succeeded: Lemke on q from the all-w basis (skipped when the caller
//      accepts an inexact answer and step 1b or 1c gave one: accept_perturbed), at most
//      kLcpExactPivotsPerUnknown pivots per unknown. On an exact retry of an island whose
//      answers are regularized (step 1c gave one: lcp_retry_exact's steps), Lemke's
//      covering-vector retries follow a failed path (settings.covering_retries, each capped
//      alike): on a settled 1,000-body pile the path with the all-ones covering vector ends
//      on a singular basis after 1,000–2,400 pivots on every retry, while the second
//      covering vector reaches the exact solution (63,643 pivots, 24 s, once); from then
//      on the steps are exact and their Lemke solves take ~3 ms instead of the 15–70 ms of a
//      regularized one (bench/results/lemke_exact_retry_covering.txt). Not on other steps:
//      on a 500-body drop they cost 1.6× the time for the same 6 inexact answers.
//      Failing that, a perturbed solution is kept (status solved_inaccurate): each contact
//      may approach or slip at up to δ (m/s) unresisted, and no energy is added
//      (λnᵀ Jn v⁺ = −δuᵀλn ≤ 0, friction still opposes slip);
//   4. when neither gave a solution: Lemke on M + εI, ε = kLcpRegularization·max(1, ‖M‖∞),
//      from the all-w basis, at most kLcpRegularizedPivotsPerUnknown pivots per unknown,
//      then step 2's first polish (covering B·1) on (M, q) from its basis; failing that, the regularized
//      solution is kept (status solved_inaccurate) if its residual on the LCP (ε·‖z‖∞ at
//      most: ε is a compliance in m/s per N·s, ODE's constraint force mixing) is at most
//      kLcpRegularizedResidual·‖q‖∞: where the LCP has no solution (a learned q bias that
//      pulls wedged contacts together) z grows like 1/ε and the step fails. Why: in a jammed
//      pile, forces that cancel (Jᵀz = 0, z ≥ 0, on contacts with φ ≤ 0) make the LCP
//      feasible only on the boundary (qᵀz = 0 exactly), and roundoff can make it
//      infeasible: the cold paths on q and q + δu then end on rays (a 500-body pile, seed 2:
//      every attempt above). M + εI is strictly copositive, so its LCP has a solution for
//      every q, and Lemke's path ends at one (Cottle, Pang & Stone, "The Linear
//      Complementarity Problem", 1992, §3.8 and §4.4);
//   5. Lemke with the caller's settings (covering-vector and M + εI retries; costly on
//      large islands), each solve capped at kLcpExactPivotsPerUnknown pivots per unknown
//      unless settings.max_pivots is set;
//   6. when nothing solved and step 1c has not run: step 1c, whose regularized answer then
//      replaces the failure. So every attempt is bounded: at most about 45 pivots per
//      unknown per island and step in all.
//   ContactSolution::warm_started is set only when step 1 solved it (zero pivots).
//   ContactSolution::residual is always that of the unperturbed LCP (≤ δ after step 2,
//   ≤ kLcpRegularizedResidual·‖q‖∞ after step 4).
//
// convex (two phases), by the interior-point QP:
//   1. min_{λn ≥ 0} ½ λnᵀ Wnn λn + λnᵀ (Jn v* + max(φ,0)/Δt)             (no friction)
//   2. κ = eᵀλn;  min ½ λᵀ W λ + λᵀ J v* + ρ λnᵀ diag(exp(φ)) diag(Wnn) λn
//      s.t. Jn v⁺ + max(φ,0)/Δt ≥ 0, λn ≥ 0, eᵀλn ≤ κ, |λt| ≤ μ λn.
//   The softening term is a setting (NormalSofteningSettings, normal_softening.hpp):
//   exp_phi is the term above (the default); linear_penalty and mujoco_impedance replace
//   it by ½ λnᵀ diag(g(φ)) diag(Wnn) λn − λnᵀ v_ref with their own g and target velocity,
//   and subtract v_ref from phase 1's λn term too.
//   Phase 1's solution with λt = 0 is feasible for phase 2, so phase 2 always has one.
//   The softening term is scaled by diag(Wnn) with a dimensionless weight ρ (default 1e-3,
//   SimulatorSettings::convex_rho) so that it is unit-consistent (λ in N·s, W in 1/kg);
//   unscaled, a pile of heavy polygons can gain energy. The term makes λn unique with
//   redundant contacts but also makes contact slightly soft (a block that Coulomb friction
//   holds creeps, tests/dynamics_incline_test.cpp); ρ → 0 recovers maximum dissipation.
//   κ is loosened by 1e-6 relative so that the interior point has an interior, and where
//   phase 2 still fails by 1e-4, then 1e-2 (resting pyramids; convex_model.cpp); where no
//   contact approaches (b ≥ 0) the answer λ = 0 is returned directly.
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/normal_softening.hpp>

#include <memory>
#include <string>
#include <vector>

namespace lcprelax {

/// Relative size δ/‖q‖∞ of the perturbation of the lcp model's second attempt (above); the
/// smallest power of ten that solves the resting pyramids of tests/dynamics_rest_test.cpp.
constexpr double kLcpPerturbation = 1e-7;
/// Perturbation patterns tried before Lemke's own (costly) retries; the last has
/// δ = 100·kLcpPerturbation·‖q‖∞.
constexpr int kLcpPerturbationSeeds = 3;
/// Pivot cap per LCP unknown of the crash path from the previous step's basis (step 1b
/// above). On a dropping 300-body pile (islands of 3,360–4,300 unknowns, steps 20–30) the
/// paths took 0.22–0.39 pivots per unknown (once 0.67) against 0.65–0.78 for the cold
/// path; at 1/10 they all stopped at the cap. On a 500-body pile (one island of
/// 6,800–8,300 unknowns) the successful paths take 0.41–0.51 per unknown while the cold
/// path takes 1.4–1.7, so a cap of 1/2 stopped half of them just short of their end and
/// paid for both (`run_pile_scaling --sizes 100,200,500 --models lcp --steps 6`: pivots per
/// step at 500 bodies 18,154 with 1/2, 12,322 with 1; 100 and 200 bodies unchanged). With
/// the basis factorized by true partial pivoting (LemkeSettings::lu_pivot_tolerance = 1)
/// longer crash paths end solved, e.g. one of 1.57 per unknown where the cap of 1 sent the
/// step to a cold path of 1.8 more: `run_pile_scaling --sizes 500 --models lcp --steps 8
/// --warmup 1 --seed S`, pivots per step for seeds 1, 2, 3 with a cap of 1: 9,909, 10,894,
/// 12,278; 2: 8,394, 8,334, 12,758; 3: 8,394, 8,334, 8,614; at 200 bodies (seed 1, 10 steps)
/// 7,580 with 1 and 2,372 with 2 and 3; 100 bodies unchanged. A path that fails at the cap
/// costs about two cold solves (1.4–1.7 pivots per unknown each) more. 5 rather than 3
/// (bench/results/lemke_dense_skip.txt): on seed 3's 500-body window a crash path that
/// solves at 3.08 per unknown is stopped by a cap of 3 and the step pays two cold paths
/// after it (26.8k pivots capped, 25.2k solved): pivots per step 20,165 with 3, 12,388 with
/// 5 or 10 (no crash path between 5 and 10 per unknown); seeds 1, 2, 4 the same with 3 and
/// 5 (no path reaches 3).
constexpr double kLcpWarmCrashPivotsPerUnknown = 5.0;
/// Step 1b's restarts after an early ray: when the crash path from the warm basis ends on
/// a ray within kLcpWarmRayPivotsPerUnknown pivots per unknown, the contacts that its pivots
/// touched (and the contact of the variable that found no ratio) are taken back in the
/// warm basis, the friction rows first and the whole contact when it is touched again
/// (reset_warm_contacts_on_ray), and the crash path runs again from it, at most
/// kLcpWarmRayRestarts times and while the rayed paths together took at most
/// kLcpWarmRayBudgetPerUnknown pivots per unknown (lcp_warm_ray_restart_allowed; each
/// restart from scratch: a factorization and the pivots up to the next ray). Such rays
/// come within 1–70 pivots on a dropping 500-body pile (islands of 7,700–9,600 unknowns)
/// on 3–6 of 20 steps and are no roundoff (every perturbation pattern ends on the same
/// ray), while the warm basis differs from the step's solution in only 440–810 of its
/// statuses: 2–32 contacts taken back let the path solve instead of
/// the cold start (1.4–1.7 pivots per unknown). On the same LCPs (every step of 20-step
/// windows of seeds 1, 2 and 3, 14 steps for 3, each LCP solved with and without the
/// restarts) the pivots went from 177,604 to 151,577, 247,794 to 244,357 and 618,652 to
/// 607,437, the time down by 1.15×, 1.00× and 1.02×; perturbed answers 4, 11 and 6 steps
/// against 4, 10 and 6 (bench/results/lemke_warm_ray_restarts.txt). A modest gain: most
/// of a moving pile's pivots are in crash paths that solve. A bound of 4 restarts is too
/// few at 1,000 bodies: with it, step 114 of `lcprelax pile --bodies 1000 --model lcp` (an
/// island of 19,496 unknowns) rays 5 times within 1–104 pivots and then pays for every later
/// attempt: three perturbed cold paths stop at their cap of 58,491 pivots (29 s each),
/// an exact one on a ray, and M + εI stops at its cap of 155,969 pivots (197 s), about
/// 520 s for the step. The 6th restart solves it in 15,400 pivots (7.7 s).
/// A restart costs one factorization and fewer than kLcpWarmRayPivotsPerUnknown·n pivots,
/// and the cold path it saves 1.4–3 pivots per unknown or more. So the restarts are bounded
/// by what they cost, not by a small count: at most kLcpWarmRayRestarts of them, and
/// kLcpWarmRayBudgetPerUnknown·n pivots on the rayed paths together, a sixth of a 3n cold
/// cap. Each contact goes up at most two levels, so the restarts also end when every
/// touched contact is new. On the 500-body windows (`run_pile_scaling --sizes 500 --models lcp
/// --steps 8 --warmup 1`), 64 restarts against 4: seed 5, 20,741.4 → 20,171.1 pivots per step;
/// seeds 3 and 6 unchanged (bench/results/lemke_warm_ray_restarts.txt).
constexpr double kLcpWarmRayPivotsPerUnknown = 0.1;
constexpr int kLcpWarmRayRestarts = 64;
constexpr double kLcpWarmRayBudgetPerUnknown = 0.5;

/// Whether step 1b runs its crash path once more after `restarts` restarts whose rayed
/// paths (the first path included) took `ray_pivots` pivots in all, on an LCP of n unknowns:
/// restarts < kLcpWarmRayRestarts and ray_pivots ≤ kLcpWarmRayBudgetPerUnknown·n.
inline bool lcp_warm_ray_restart_allowed(int restarts, long ray_pivots, Index n) {
  return restarts < kLcpWarmRayRestarts &&
         static_cast<double>(ray_pivots) <= kLcpWarmRayBudgetPerUnknown * static_cast<double>(n);
}
/// Pivot cap per LCP unknown of the cold attempts (steps 2, 3 and 4 above): on a
/// 200-body pile the solved cold paths take 0.9–1.3 pivots per unknown, failing ones end on
/// a ray within 1.2 or cycle to the pivot limit (50 per unknown).
constexpr long kLcpExactPivotsPerUnknown = 3;

/// A jammed island at rest can have no exact solution that Lemke reaches: every step ends
/// on the perturbed (or regularized) answer, after the polish (step 1b) and the exact cold start (step 3)
/// failed again (200-body pile at 1.9e-6 m/s: 180 ms per step, of which 110 ms in step 3,
/// against 3 ms for a step solved by its warm basis). After such a step the simulator
/// takes step 1b's perturbed answer as it is (solve_lcp_model's accept_perturbed), except
/// after 1, 2, 4, 8, 16 and then every kLcpExactRetrySteps consecutive perturbed steps
/// (an exponential backoff), where every attempt runs again, so that an island that has
/// an exact solution again returns to it.
constexpr int kLcpExactRetrySteps = 32;

/// Whether an island whose last `perturbed_steps` answers were perturbed runs every attempt
/// (true) or takes step 1b's perturbed answer (false); true for 0.
constexpr bool lcp_retry_exact(int perturbed_steps) {
  return perturbed_steps < kLcpExactRetrySteps ? (perturbed_steps & (perturbed_steps - 1)) == 0
                                               : perturbed_steps % kLcpExactRetrySteps == 0;
}

/// Relative regularization ε/max(1, ‖M‖∞) of step 4 above. On the 500-body pile of seed 2
/// (5,916 unknowns, exported with `lcprelax pile --export-fc2d`; bench/README.md) 1e-12
/// and 1e-10 ended on rays (after 5,832 and 46,622 pivots); 1e-8 solved in 32,787 pivots
/// (residual on the LCP 2.7e-6 with ‖q‖∞ = 1 m/s), 1e-7 in 28,591 (2.5e-5); 1e-6 cycled to
/// Lemke's pivot limit.
constexpr double kLcpRegularization = 1e-8;
/// Pivot cap per LCP unknown of step 4 (5.5 per unknown were needed above).
constexpr double kLcpRegularizedPivotsPerUnknown = 8.0;
/// Largest residual on the LCP, relative to ‖q‖∞, of a regularized solution that step 4
/// keeps (2.6e-6 on the pile above): ten times the largest perturbation of step 2.
constexpr double kLcpRegularizedResidual = 1e-4;

/// The outcome of one island's contact solve.
enum class ContactStatus {
  unsolved,           ///< not solved yet
  solved,             ///< the model's solve reached its tolerance (LCP residual, or QP eps)
  solved_inaccurate,  ///< usable, but outside the tolerance: the lcp model's solution on a
                      ///< perturbed q (residual ≤ δ, above) or on M + εI, or a QP phase solved_inaccurate
  failed              ///< no solution of the model; the fields hold a fallback (see below)
};

constexpr const char* to_string(ContactStatus s) {
  switch (s) {
    case ContactStatus::unsolved: return "unsolved";
    case ContactStatus::solved: return "solved";
    case ContactStatus::solved_inaccurate: return "solved_inaccurate";
    case ContactStatus::failed: return "failed";
  }
  return "unknown";
}

/// Whether the impulses and v⁺ are the model's solution (solved or solved_inaccurate).
constexpr bool has_solution(ContactStatus s) {
  return s == ContactStatus::solved || s == ContactStatus::solved_inaccurate;
}

struct ContactSolution {
  ContactStatus status = ContactStatus::unsolved;
  std::string message;      ///< why, when the status is not solved
  Vector lambda_n;          ///< normal impulse per contact
  Vector lambda_t;          ///< tangential impulse per friction row (along t)
  Vector v_next;            ///< v⁺ per island dof
  double residual = 0.0;    ///< LCP: max|min(z, w)|; QP: max(primal, dual residual) of phase 2
  long work = 0;            ///< Lemke pivots, or interior-point iterations of both phases
  std::vector<bool> z_basic;  ///< LCP final basis (warm start of the next step)
  bool warm_started = false;  ///< LCP: the warm basis solved it in zero pivots
  bool perturbed = false;     ///< LCP: the answer solves q + δu (status solved_inaccurate)
  bool regularized = false;   ///< LCP: the answer solves M + εI (status solved_inaccurate)
  /// Convex model with ConvexSolver::active_set_newton: a phase did not converge by the
  /// active-set method and the interior point's answer (all of it) was used.
  bool newton_fallback = false;
  /// Convex model with release_open_contacts: phase 2 had no solution with the release and
  /// was solved without it.
  bool open_contacts_held = false;
};

struct StewartTrinkleLcp {
  SparseMatrix M;  ///< (nc + 3nf)²
  Vector q;
};

/// The LCP of the lcp model for an island (W = delassus(s)), with the contacts' compliance on
/// the normal diagonal and their erp in q's gap term (normal_gap_rate), and s.lcp_block added
/// to every contact's own block when enabled (world.hpp ContactLcpBlock).
StewartTrinkleLcp stewart_trinkle_lcp(const ContactSystem& s, const SparseMatrix& W, double dt);

/// stewart_trinkle_lcp(s, W, dt).q alone (the same numbers, bit for bit), without forming M.
Vector stewart_trinkle_q(const ContactSystem& s, double dt);

/// The lifted form of stewart_trinkle_lcp(s, delassus(s), dt)'s M (lcp_types.hpp
/// LcpLiftedForm, for Lemke's sparse basis): M = J diag(minv) Jᵀ + H with J's rows
/// [Jn; Jt; −Jt; 0] in the LCP's row order and H the compliance, μ, ±1 and lcp_block
/// entries. Throws InputError when the Jacobians do not match s's sizes.
LcpLiftedForm stewart_trinkle_lifted_form(const ContactSystem& s, double dt);

/// Each contact's indices in the LCP's z = [λn (nc), β⁺, β⁻, γ (nf each)]: 4 per contact in the
/// order λn, β⁺, β⁻, γ, with −1 for the last three of a contact without a friction row.
std::vector<Index> stewart_trinkle_contact_indices(const ContactSystem& s);

/// The lcp model's perturbation pattern u (step 2 above) for pattern number `seed` ≥ 0, in
/// the LCP's row order z = [λn, β⁺, β⁻, γ]: u_i ∈ [½, 1), a hash of (the key of row i's
/// contact, the row's kind, seed). The key of contact c is s.ids[c] (its identity across
/// time steps) when s.ids has nc entries, c when it is empty; other sizes throw InputError.
Vector lcp_perturbation_pattern(const ContactSystem& s, int seed);

/// Solves the lcp model; `warm` (size nc + 3nf, or empty) is tried as the first basis.
/// `warm_factorization` (optional): the factorization step 1 factorizes the warm basis in
/// (LemkeSolver::share_factorization), kept by the caller from one step to the next so that
/// a repeating basis pattern (an island at rest) reuses its symbolic analysis and pivot
/// order; the answer is the same bit for bit where partial pivoting would pick the same
/// pivots, within roundoff otherwise (lemke.hpp). Not to be shared between islands solved
/// at the same time.
/// `accept_perturbed`: step 1b's answer on q + δu is taken without the polish and the later
/// attempts, and step 1c's on M + εI without the later attempts (run_lcp_model_attempts;
/// kLcpExactRetrySteps says when the simulator asks). `warm_from_regularized`: `warm` is the
/// basis of a regularized answer or of a failed step, and step 1c runs early.
ContactSolution solve_lcp_model(const ContactSystem& s, double dt, const LemkeSettings& settings,
                                const std::vector<bool>& warm = {},
                                const std::shared_ptr<LemkeSharedFactorization>& warm_factorization = {},
                                bool accept_perturbed = false, bool warm_from_regularized = false);

/// How the convex model's QPs are posed (models/convex_phase_qp.hpp): `dual` in
/// the impulses λ with the Delassus matrix W = J M⁻¹ Jᵀ; `lifted` in (Δv, λ) with the
/// equality M Δv = Jᵀ λ, whose KKT matrix holds only M and the Jacobians (less fill on
/// large islands); `automatic`: lifted from kLiftedMinContacts contacts on. Both give the
/// same v⁺ to the QP tolerance.
enum class ConvexFormulation { automatic, dual, lifted };

/// Smallest island (contacts) that ConvexFormulation::automatic solves lifted: the measured
/// crossover between the two formulations (bench/README.md).
constexpr Index kLiftedMinContacts = 24;

/// Solves the convex two-phase model. When phase 1 succeeds but phase 2 fails (e.g. a plank
/// 10⁶ times heavier than the boxes it rests on, tests/dynamics_mass_ratio_test.cpp),
/// the result has status failed and carries phase 1's frictionless answer (λn, λt = 0, v⁺).
/// `softening` chooses phase 2's normal softening (validated: InputError when invalid).
/// The convex model has no LCP: InputError when s.lcp_block is enabled (world.hpp). A
/// contact's normal compliance and erp enter through add_pair_softness (normal_softening.hpp).
ContactSolution solve_convex_model(const ContactSystem& s, double dt, const QpSettings& settings,
                                   double rho = 1e-3, ConvexFormulation formulation = ConvexFormulation::automatic,
                                   const NormalSofteningSettings& softening = {});

struct ConvexSolverCache;  // convex_solver_cache.hpp

/// As above, with the phase solvers kept in `cache` (may be null: fresh solvers): a phase
/// whose QP has the pattern of the cache's last one is updated in place (its symbolic
/// analysis reused), else set up afresh. The answer is that of the fresh solve to roundoff.
/// `release_open_contacts`: phase 2 puts no normal impulse on an open contact (φ > 0) that
/// phase 1's frictionless answer leaves open (detail::release_open_contacts,
/// convex_phase_qp.hpp; SimulatorSettings::convex_release_open_contacts). Where phase 2 has
/// no solution with the release, it is solved without it (ContactSolution::open_contacts_held).
ContactSolution solve_convex_model(const ContactSystem& s, double dt, const QpSettings& settings, double rho,
                                   ConvexFormulation formulation, const NormalSofteningSettings& softening,
                                   ConvexSolverCache* cache, bool release_open_contacts = false);

/// How the convex model's phase QPs are solved: by the interior point (QpSolver), or by the
/// warm-started primal–dual active-set (semismooth Newton) method of active_set_qp.hpp,
/// which falls back to the interior point for the whole island when a phase does not
/// converge to its tolerances (ContactSolution::newton_fallback).
enum class ConvexSolver { interior_point, active_set_newton };

/// The convex model by the active-set Newton method (ConvexSolver::active_set_newton), same
/// model and same QPs as solve_convex_model. `warm` is empty or holds nc + nf entries: per
/// contact 1 (its λn was positive last step), 0 (it was zero) or −1 (unknown: guessed from
/// bn < 0); per friction row +1 (λt = μλn last step), −1 (λt = −μλn) or 0 (inside the cone).
/// On return z_basic holds nc + 3nf flags in solve_lcp_model's layout: λn > 0, λt at +μλn,
/// λt at −μλn, and 0 (for the next step's `warm`; empty after a fallback). The tolerance is
/// settings.eps_abs on the phase KKT residuals (active_set_qp.hpp); `cache` is used by the
/// interior-point fallback only. `max_iterations`: factorizations per phase before the
/// fallback (kConvexNewtonMaxIterations by default).
ContactSolution solve_convex_model_newton(const ContactSystem& s, double dt, const QpSettings& settings, double rho,
                                          ConvexFormulation formulation, const NormalSofteningSettings& softening,
                                          ConvexSolverCache* cache, const std::vector<signed char>& warm = {},
                                          int max_iterations = -1, bool release_open_contacts = false);

/// Default cap of active-set iterations (KKT factorizations) per phase of
/// solve_convex_model_newton; beyond it the island falls back to the interior point.
constexpr int kConvexNewtonMaxIterations = 20;

}  // namespace lcprelax
