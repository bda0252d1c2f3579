#pragma once
// Transitions of a multi-body scene for learning contact parameters: every body's state
// x_k = (q_k, v_k) and applied force u_k at step k, and x_{k+1}.
//
// Units and conventions (SI; world/world.hpp): pose q = (x, y, θ) in m, m, rad (centre of
// mass, counter-clockwise); velocity v = (vx, vy, ω) in m/s, m/s, rad/s; applied u =
// (fx, fy, τ) in N, N, N·m, the generalized force acting during the step in addition to
// gravity (the `applied` argument of Simulator::step). Static bodies are listed too: they
// never move and their u is zero.
//
// Generated data (generate_scene_dataset): the scene's Simulator (models/simulator.hpp, the
// scene's contact model, dt, margin and other settings) runs `steps` steps from the scene's
// world. Pushes make mass and inertia identifiable (without known forces only their ratios
// are): every `push_interval` steps, round(push_fraction · #dynamic bodies) distinct dynamic
// bodies are drawn, each gets a force of magnitude uniform in [push_force_min,
// push_force_max] (N) in a direction uniform in [0, 2π) and a torque uniform in
// ±push_torque_max (N·m), held for the interval; the other bodies get u = 0. The recorded
// next state is the simulator's state after the step: v_{k+1} is exactly the contact
// solve's v⁺, q_{k+1} the post-stabilized position (which may differ from q_k + Δt·v⁺ where
// the projection moved it). A transition has contact when the step found ≥ 1 contact
// (StepStats::contacts, which includes the speculative margin); with drop_without_contact
// the others are dropped. Noise: independent N(0, σ²) on every recorded component of q
// (σ = pose_noise, m and rad) and v (σ = velocity_noise, m/s and rad/s) of dynamic bodies,
// added once per recorded state (so transition k's next state and transition k+1's state
// carry the same noise), after the simulation. Random numbers come from std::mt19937_64
// mapped to [0, 1) by the top 53 bits (library-independent), pushes from `seed` and noise
// from a second stream of `seed`: the same settings give the same dataset bit for bit,
// whatever the thread count.
//
// Loaded data (load_scene_dataset): a scene JSON (scenes/scene_json.hpp) and a trajectory
// CSV (scenes/trajectory_csv.hpp, applied forces from its optional fx, fy, torque columns,
// zero without them). Every pair of consecutive frames gives one transition, so the CSV's
// steps must be consecutive (k, k+1, k+2, ...): a gap is an error, not skipped. Rules (each
// violation an InputError "TRAJ.csv:LINE: ..." naming the line, or "TRAJ.csv: ..."):
// - each frame has as many bodies as the scene ("frame has 3 bodies, the scene has 5");
// - at least two frames; steps consecutive and ≤ the scene's `steps`;
// - the time difference of consecutive frames equals the scene's dt within 1e-6·dt;
// - static bodies keep the scene's pose and velocity (within 1e-9·(1 + |value|)) and have
//   zero applied force;
// - NaN and Inf are rejected by the CSV reader with their line.
// With `drop_without_contact`, transitions whose pre-state has no contact by the simulator's
// rule (find_contacts within margin + 2·Δt·max over dynamic bodies of |v| + |ω|·r for the
// current and the free velocity; simulator.hpp step 1) are dropped.
#include <lcprelax/scenes/scene.hpp>
#include <lcprelax/scenes/trajectory_csv.hpp>
#include <lcprelax/world/world.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace lcprelax::learn {

/// One step of a scene: all bodies' state and applied force at step k and state at k + 1.
struct SceneTransition {
  int step = 0;                     ///< k (0 = the scene's initial world)
  std::vector<Vec3> pose;           ///< q_k per body (m, m, rad)
  std::vector<Vec3> velocity;       ///< v_k per body (m/s, m/s, rad/s)
  std::vector<Vec3> applied;        ///< u_k per body (N, N, N·m), zero for static bodies
  std::vector<Vec3> next_pose;      ///< q_{k+1} per body
  std::vector<Vec3> next_velocity;  ///< v_{k+1} per body
};

/// What generation did (zero for a loaded dataset).
struct SceneGenerationStats {
  int steps = 0;                    ///< simulated steps
  int dropped_without_contact = 0;  ///< transitions dropped because the step found no contact
  long contacts = 0;                ///< contacts over all recorded transitions
  int pushed_bodies = 0;            ///< bodies pushed per push interval
  int inaccurate_islands = 0;       ///< over all steps (StepStats::inaccurate_islands)
  double seconds = 0.0;             ///< wall time of generation
};

struct SceneDataset {
  /// The world at step 0 with the TRUE parameters (shapes, masses, inertias, friction, static
  /// geometry) and the simulator settings (dt, model, margin, ...); `steps` is the number of
  /// simulated steps.
  Scene scene;
  /// Per body its shape class (scene_shape_classes(scene.world), scene_params.hpp); −1 for static bodies.
  std::vector<int> shape_class;
  std::vector<SceneTransition> transitions;  ///< in increasing step order
  SceneGenerationStats generation;

  int num_shape_classes() const;  ///< 1 + the largest shape_class (0 without dynamic bodies)
  /// Throws InputError naming the field ("transitions[3].next_pose: 4 entries for 5 bodies",
  /// "transitions[3].velocity[2]: not finite") when sizes disagree with the scene's bodies,
  /// values are not finite, shape_class disagrees with the scene, or the scene is invalid.
  void validate() const;
};

struct SceneDatasetSettings {
  int steps = 100;                 ///< steps to simulate, ≥ 1
  std::uint64_t seed = 1;          ///< pushes and noise
  double push_fraction = 0.25;     ///< fraction of dynamic bodies pushed per interval, in [0, 1]
  int push_interval = 1;           ///< steps a push is held before new bodies are drawn, ≥ 1
  double push_force_min = 20.0;    ///< N, ≥ 0
  double push_force_max = 80.0;    ///< N, ≥ push_force_min
  double push_torque_max = 0.5;    ///< N·m, ≥ 0
  double pose_noise = 0.0;         ///< σ on recorded poses (m and rad), ≥ 0
  double velocity_noise = 0.0;     ///< σ on recorded velocities (m/s and rad/s), ≥ 0
  bool drop_without_contact = true;
  /// Keep steps where an island's contact solve failed (the simulator's fallback answer is
  /// then recorded); otherwise generation throws std::runtime_error naming the step.
  bool allow_failed_islands = false;
  int threads = 1;                 ///< simulator threads over islands (the data do not depend on it), ≥ 0
  std::string validation_error() const;  ///< empty if valid, else names the field
};

/// Simulates `scene` (its world, settings and contact model; scene.steps is ignored, the
/// dataset's scene has steps = settings.steps). Throws InputError for an invalid scene or
/// settings, std::runtime_error for a failed island unless allow_failed_islands.
SceneDataset generate_scene_dataset(const Scene& scene, const SceneDatasetSettings& settings);

/// Reads a scene JSON and a trajectory CSV (rules above). Throws InputError naming the file
/// and the line or field.
SceneDataset load_scene_dataset(const std::string& scene_json_path, const std::string& trajectory_csv_path,
                                bool drop_without_contact = false);

/// The dataset from a scene and frames already read; `source` names the CSV in errors
/// (frame lines from TrajectoryFrame::line).
SceneDataset scene_dataset_from_frames(const Scene& scene, const std::vector<TrajectoryFrame>& frames,
                                       const std::string& source, bool drop_without_contact = false);

/// True when the state (pose, velocity, applied of `t`) in the scene's world has a contact
/// by the simulator's rule (see above).
bool transition_has_contact(const Scene& scene, const SceneTransition& t);

/// Writes the scene (save_scene) and the states as a trajectory CSV with the force columns,
/// time = step·dt: each transition's pre-state with its u, and the last next state with
/// u = 0. Transitions must be at consecutive steps (generate with drop_without_contact =
/// false), else InputError; so load_scene_dataset reads the same transitions back.
void write_scene_dataset(const SceneDataset& data, const std::string& scene_json_path,
                         const std::string& trajectory_csv_path);

/// Options of the learning pile; validation_error() names the bad field.
struct LearningPileOptions {
  int bodies = 30;                         ///< 1 .. 100 000
  int classes = 3;                         ///< shape classes used, 1 .. 4 (the table of make_learning_pile)
  std::uint64_t seed = 1;                  ///< class of each body, angles, initial velocities
  ContactModel model = ContactModel::lcp;
  double mu = 0.5;                         ///< friction coefficient of every pair, ≥ 0
  double dt = 1e-2;                        ///< s, > 0
  double margin = 1e-2;                    ///< m, ≥ 0
  /// The scene's SimulatorSettings::post_stabilization_passes, ≥ 1. One, not the simulator's
  /// default of 5: the further passes project contacts onto exactly −slop overlap (their
  /// true gaps), and a transition that starts there sits on the gap term's kink, where the
  /// losses have one-sided derivatives in the gap parameters.
  int post_stabilization_passes = 1;
  std::string validation_error() const;
};

/// A pile of polygons of a few shape classes dropped into a box (ground y ≥ 0, walls
/// x = 0 and x = W): class k of the fixed table (0 square 0.1 m side at 1000 kg/m², 1
/// equilateral triangle of circumradius 0.08 m at 1500 kg/m², 2 regular pentagon of
/// circumradius 0.07 m at 800 kg/m², 3 rectangle 0.14 × 0.07 m at 1200 kg/m²); bodies
/// 0..classes−1 have classes 0..classes−1 (so scene_shape_classes numbers them the same), the
/// others a class uniform among the used ones. Layout: a grid of columns = max(1,
/// round(bodies/5)) cells of side s = 2.2·r_max (r_max the largest circumradius used), filled
/// row by row from the bottom left; each body's circumcentre is at its column's centre and
/// its lowest vertex 2 mm above its row's floor (the bottom row touches the ground within
/// the margin, no two bodies touch); random angle in [0, 2π), velocity in ±0.05 m/s and
/// ±0.5 rad/s. Walls from y = 0 to (rows + 1)·s.
/// Throws InputError for invalid options.
Scene make_learning_pile(const LearningPileOptions& options);
Scene make_learning_pile(int bodies, std::uint64_t seed, ContactModel model);

}  // namespace lcprelax::learn
