#pragma once
// Semi-implicit, velocity-level time stepping of a 2-D world (docs/formulations.md).
//
// One step of length Δt:
//   1. contacts with gap φ ≤ margin + 2·Δt·max(|v| + |ω| r) over the bodies and over their
//      current and free velocities v, v* = v + Δt·M⁻¹f (a speculative margin, so that no
//      pair can close more than its gap in one step unseen);
//   2. islands of touching dynamic bodies, each solved as its own contact problem by the
//      scene's model (contact_step.hpp), in parallel over islands with OpenMP; bodies
//      without contacts fly freely (v⁺ = v + Δt·g);
//   3. positions q⁺ = q + Δt·v⁺ (symplectic Euler);
//   4. post-stabilization (Cline & Pai 2003): where the linearized gap φ + Δt·Jn v⁺ falls
//      below −slop, positions are projected by  min ½ΔqᵀMΔq  s.t.  Jn Δq + φ⁺ + slop ≥ 0,
//      an LCP in Wnn solved by Lemke (where Lemke fails on a singular Wnn, the primal QP by
//      the interior point); velocities are untouched, so penetration is removed without
//      adding kinetic energy. Up to post_stabilization_passes − 1 further passes re-detect
//      contacts at the projected positions and project on their true gaps φ where −φ still
//      exceeds the slop. Overlaps beyond the slop by at most 1e-6·slop (the roundoff of
//      contacts a projection left at −slop) are not projected, so a pile at rest is not.
// Warm starts: each contact is keyed by (body a, body b, static shape, ordinal within the
// pair); the final Lemke basis of its unknowns is reused next step, and with
// ConvexSolver::active_set_newton the convex solve's final active states (λn > 0, λt at
// ±μλn) start the next step's active-set solve (convex_model_newton.cpp).
//
// Energy (J): kinetic ½ Σ (m|v|² + Iω²) plus potential −Σ m g·x (zero at the origin).
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/convex_solver_cache.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/contact_warm_table.hpp>
#include <lcprelax/world/world.hpp>

#include <map>
#include <memory>
#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace lcprelax {

/// The contact model a world is stepped with: `lcp` (Stewart–Trinkle/Anitescu velocity-level
/// LCP, solved by Lemke) or `convex` (the two-phase convex model, solved by the interior-point
/// QP); contact_step.hpp states both.
enum class ContactModel { lcp, convex };

/// "lcp" or "convex".
constexpr const char* to_string(ContactModel m) {
  switch (m) {
    case ContactModel::lcp: return "lcp";
    case ContactModel::convex: return "convex";
  }
  return "unknown";
}

/// Inverse of to_string; throws InputError "unknown contact model 'x' (expected lcp or
/// convex)" for any other text (case-sensitive).
ContactModel parse_contact_model(std::string_view text);

struct SimulatorSettings {
  double dt = 1e-2;                        ///< time step (s), > 0 and finite
  ContactModel model = ContactModel::lcp;  ///< contact model
  double margin = 1e-2;  ///< contact margin (m), ≥ 0: contacts with gap φ above it (plus the speculative part) are not posed
  LemkeSettings lemke;       ///< for the lcp model and the position projection
  QpSettings qp;             ///< for the convex model (eps_abs 1e-8 by default here)
  double penetration_slop = 1e-4;  ///< m: allowed overlap before projection
  double convex_rho = 1e-3;  ///< weight ρ of the convex model's λnᵀdiag(exp(φ))diag(Wnn)λn term
  /// The convex model's normal softening (normal_softening.hpp): exp_phi (the term above,
  /// default), linear_penalty (uses convex_rho too) or mujoco_impedance.
  NormalSofteningSettings convex_softening;
  /// Convex model: how its phase QPs are posed (contact_step.hpp ConvexFormulation):
  /// automatic (lifted from kLiftedMinContacts contacts on), dual or lifted. Islands with a
  /// large mass ratio want lifted: W = J M⁻¹ Jᵀ then has eigenvalues spread by the ratio
  /// while lifted keeps M diagonal, which the QP's equilibration absorbs. Measured on a plank
  /// 10⁶× heavier than the two 1 kg boxes it rests on (tests/dynamics_mass_ratio_test.cpp,
  /// 200 steps, convex_rho 1e-6): dual fails in 197 islands, lifted in none (drift 7e-9 m);
  /// at 10⁵ and ρ = 1e-3 dual leaves 166 inaccurate islands, lifted none. Keep ρ·(mass
  /// ratio) ≲ 1 there: the softening weights λn by the light body's Wnn while the load is the
  /// heavy body's, and at ρ = 1e-3, ratio 10⁶ the (correctly solved) model lets the boxes
  /// slip out (31.8 m in 200 steps; 9e-7 m at 10⁵).
  ConvexFormulation convex_formulation = ConvexFormulation::automatic;
  bool post_stabilization = true;
  /// Post-stabilization passes (≥ 1). The first projects on the step's contacts with the
  /// linearized gap φ + Δt·Jn v⁺; each further pass re-detects contacts at the projected
  /// positions and projects again on their true gaps where an overlap still exceeds the
  /// slop (a nonlinear projection: rotating polygons overlap through features that the
  /// linearization did not see), stopping early once none does. Largest start-of-step
  /// overlap while a pile drops (300 steps, one run each): convex 200 bodies 11.0 mm with 1
  /// pass, 2.1 / 3.4 / 0.2 mm with 2 / 3 / 5; 500 bodies 12.3 → 1.4 mm with 5; LCP 100 bodies
  /// 8.5 → 0.1 mm with 5; CPU per step within ±10%; 1,000 bodies 400 steps 13.9 → 0.47 mm.
  /// Learning piles keep one pass (LearningPileOptions::post_stabilization_passes: more
  /// passes leave contacts at exactly −slop, on the gap term's kink).
  int post_stabilization_passes = 5;
  bool warm_start = true;
  int threads = 0;           ///< OpenMP threads over islands; 0 = OpenMP's default
  /// Convex model: keep each island's phase solvers between steps and update them in place
  /// while the island's QP pattern repeats (convex_solver_cache.hpp; same answers to
  /// roundoff); false: fresh solvers (a new symbolic analysis) every step.
  bool reuse_convex_solvers = true;
  /// Convex model: how its phase QPs are solved (contact_step.hpp ConvexSolver). With
  /// active_set_newton each contact's final active state is kept (keyed as the LCP warm
  /// start) and starts the next step's solve; failures fall back to the interior point.
  /// Default interior_point: on the piles of bench/results/pile_newton.csv (50–1,000 bodies,
  /// still moving at 0.3–0.6 m/s) every active-set solve hit its cap and fell back, costing
  /// 1.1–1.9× the interior point's CPU time; it converges on stacks (0 fallbacks).
  ConvexSolver convex_solver = ConvexSolver::interior_point;
  /// Convex model: phase 2 puts no normal impulse on an open contact (gap φ > 0) that phase
  /// 1's frictionless answer leaves open (convex_phase_qp.hpp release_open_contacts). Without
  /// it, phase 2 may spend phase 1's normal-impulse budget κ on contacts within the margin and
  /// hold bodies above their supports: a 200-body pile settled 300 steps (seed 1, margin 1 cm)
  /// had 14 bodies more than 1 mm from any contact, up to 12.5 mm, and none with it
  /// (docs/formulations.md). Off by default: the released set is a discrete decision that
  /// makes the convex learning loss (learn/step_loss_convex.hpp, which has the same option)
  /// rough in the parameters (a 30-body recovery from 25% off stalls at a relative error of
  /// 3.3 with it, reaches 0.67% without; docs/formulations.md).
  bool convex_release_open_contacts = false;
  SimulatorSettings();

  /// Empty when valid, else a message naming the first bad field ("dt: must be ...").
  std::string validation_error() const;
};

struct StepStats {
  int contacts = 0;
  int islands = 0;             ///< = solved_islands + inaccurate_islands + failed_islands
  int solved_islands = 0;      ///< ContactStatus::solved
  int inaccurate_islands = 0;  ///< ContactStatus::solved_inaccurate (usable, outside tolerance)
  int largest_island_unknowns = 0;
  long work = 0;               ///< Lemke pivots + interior-point iterations
  int warm_started_islands = 0;
  double max_residual = 0.0;   ///< largest contact-solve residual (contact_step.hpp)
  double max_penetration = 0.0;  ///< largest −φ ≥ 0 at the start of the step (m)
  /// Islands whose solve failed. Fallbacks: an lcp island takes the convex model's
  /// answer; a convex island of at most 64 contacts takes the LCP model's (Lemke) answer
  /// if Lemke solves it, else (and on larger islands) its phase-1 (frictionless) answer;
  /// with neither, v⁺ = v* (no contact impulse). A fallback still counts as a failure.
  int failed_islands = 0;
  std::string first_failure;   ///< message of the first failed solve
  std::string first_inaccurate;  ///< message of the first inaccurate solve
  int projected_islands = 0;     ///< islands whose positions the post-stabilization moved
  int failed_projections = 0;    ///< islands whose projection failed (positions left as they were)
  double collision_seconds = 0.0, solve_seconds = 0.0;
  /// Convex model: phase solvers set up afresh (a symbolic analysis each) and phase solvers
  /// updated in place because the island's QP pattern repeated (convex_solver_cache.hpp).
  long solver_setups = 0, solver_updates = 0;
  /// Convex model with ConvexSolver::active_set_newton: islands whose active-set solve
  /// did not converge and took the interior point's answer (not failures).
  int newton_fallbacks = 0;
  /// Convex model with reuse_convex_solvers: wall time (s, summed over islands) of building
  /// the phase QPs, of QpSolver setup()/update(), of solve() and, within it, of the numeric
  /// KKT factorizations (ConvexSolverCache).
  double qp_assemble_seconds = 0.0, qp_prepare_seconds = 0.0, qp_solve_seconds = 0.0, qp_factor_seconds = 0.0;
};

/// The contacts a step poses, and their islands: what Simulator::step solves, shared with
/// learning (learn/scene_objective.hpp) so that a loss sees the simulator's own problems.
struct StepContacts {
  double margin = 0.0;            ///< settings.margin + the speculative part (m)
  std::vector<Contact> contacts;  ///< find_contacts at `margin` (collision.hpp order)
  std::vector<Island> islands;    ///< find_islands (contact_system.hpp)
};

/// The speculative contact margin of a step (m): settings.margin + 2Δt·max over the dynamic
/// bodies and over {v, v* = v + Δt M⁻¹f} of (|v_xy| + |ω|·r), r the body's largest vertex
/// radius, f gravity plus `applied` (one (fx, fy, τ) per body, or empty); v* includes the
/// velocity residual W f, and the margin grows by 2·max(0, −gap_offset) over the bodies.
double speculative_contact_margin(const World& world, const SimulatorSettings& settings,
                                  const std::vector<Vec3>& applied = {});

/// Contacts and islands of the step that Simulator::step would take from `world`. Throws
/// InputError when `applied` is neither empty nor one entry per body.
StepContacts find_step_contacts(const World& world, const SimulatorSettings& settings,
                                const std::vector<Vec3>& applied = {});

/// Largest |position| (m), |angle| (rad), |velocity| (m/s), |angular velocity| (rad/s) and
/// |gravity| (m/s²) a Simulator accepts: 1e15, far from where the step's derived quantities
/// (contact margins, positions after a step) overflow; beyond it the field is named.
constexpr double kMaxSceneMagnitude = 1e15;

class Simulator {
 public:
  /// Throws InputError on invalid settings (validation_error()) or bodies (non-positive
  /// mass or inertia of a dynamic body, non-finite pose or velocity, a value beyond
  /// kMaxSceneMagnitude, naming the body's field).
  explicit Simulator(World world, SimulatorSettings settings = {});

  /// Advances one step; applied (fx, fy, torque) per body (N, N·m) may be empty.
  StepStats step(const std::vector<Vec3>& applied = {});

  const World& world() const { return world_; }
  const SimulatorSettings& settings() const { return settings_; }
  double time() const { return time_; }
  long steps_taken() const { return steps_; }
  /// Each contact's part of the last step's Lemke basis (lcp model) or active set (the
  /// convex model's active_set_newton), by contact identity (ContactKey: body a, body b,
  /// static kind, static index, ordinal among the pair's contacts) in the codes of
  /// lcp_basis_codes.hpp: what the next step warm-starts from. Empty before the first step.
  /// A contact of a failed island (StepStats::failed_islands) keeps the entry that its
  /// step started from, if it had one: the next step starts from the last basis that solved.
  /// The lcp model marks the entries of a regularized or failed island `regularized`: a
  /// basis of M + εI (or the last that solved), from which the next step tries M + εI first.
  std::vector<ContactWarmRecord> warm_start_state() const { return warm_.records(); }
  /// Replaces that state, e.g. by one saved with a scene file (scene_json.hpp
  /// "warm_start"): the next step starts from it as from the step that produced it. Throws
  /// InputError naming the record for a body index outside [0, bodies) (a; b: [−1,
  /// bodies)), a static kind outside 0..2, a static index < −1, an ordinal < 0, a normal
  /// code other than 0 or 1, or a friction code that is not an integer in 0..7. A record
  /// that matches no contact is harmless: no contact reads it.
  void set_warm_start_state(const std::vector<ContactWarmRecord>& records);
  /// Contacts found at the start of the last step.
  const std::vector<Contact>& contacts() const { return contacts_; }
  double kinetic_energy() const;
  double potential_energy() const;
  double total_energy() const { return kinetic_energy() + potential_energy(); }

 private:
  void check_extreme_values() const;  // the kMaxSceneMagnitude checks of the constructor
  using ContactKey = lcprelax::ContactKey;
  std::vector<ContactKey> contact_keys() const;
  void project_positions(const ContactSystem& s, const Vector& v_next, StepStats& stats);
  /// One further post-stabilization pass on the contacts at the current positions; false
  /// when no overlap exceeds the slop (nothing done).
  bool project_overlaps(StepStats& stats);

  World world_;
  SimulatorSettings settings_;
  double time_ = 0.0;
  long steps_ = 0;
  std::vector<Contact> contacts_;
  /// Each contact's part of the last basis or active set (contact_warm_table.hpp), and the
  /// table the step fills for the next one (swapped with it: both keep their capacity).
  ContactWarmTable warm_, next_warm_;
  std::vector<double> warm_normal_, warm_friction_;  // step(): the step's codes per contact (NaN: none)
  std::vector<char> warm_regularized_;  // step(): per contact, ContactWarmRecord::regularized
  std::vector<const ContactWarmTable::Entry*> previous_;  // step(): warm_'s entry per contact (find_sorted)
  /// Convex model: each island's phase solvers, keyed by the island's smallest body index
  /// (an island keeps it while its bodies stay together); dropped when no island has it.
  std::map<int, ConvexSolverCache> convex_caches_;
  /// LCP model, per island (matched by its smallest body like convex_caches_): the
  /// factorization of its warm basis (LemkeSharedFactorization), and how many consecutive
  /// steps ended on a perturbed or regularized answer or failed (contact_step.hpp
  /// kLcpExactRetrySteps). Whether its basis came from a regularized answer or a failed step
  /// is in the warm-start entries (ContactWarmRecord::regularized), so that a scene file
  /// carries it.
  struct LcpIslandMemory {
    std::shared_ptr<LemkeSharedFactorization> factorization = make_lemke_shared_factorization();
    int perturbed_steps = 0;
  };
  std::map<int, LcpIslandMemory> lcp_islands_;
};

}  // namespace lcprelax
