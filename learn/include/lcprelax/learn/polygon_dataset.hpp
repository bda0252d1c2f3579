#pragma once
// Transitions (x_k, u_k, x_{k+1}) of one polygon on the ground, x = (q, v) with
// q = (x, y, θ) (m, m, rad; (x, y) the centre of mass, the body-frame origin of
// polygon_params.hpp) and v = (vx, vy, ω) (m/s, rad/s), u = (fx, fy, τ) the applied
// generalized force during the step (N, N, N·m), gravity acting in addition.
//
// Generated data: the library's Simulator on the one-body scene polygon_scene(truth, ...)
// (polygon_scene.hpp; models/simulator.hpp, contact model `lcp`
// = Stewart & Trinkle 1996 by Lemke, or `convex`) integrates the ground-truth model from
// seeded random throws: the lowest vertex starts drop_height·[0.5, 1] above the ground,
// pose angle uniform in [−π, π), velocity uniform in ±throw_speed (vx) and
// ±0.5·throw_speed (vy), spin uniform in ±spin (rad/s). In each step an applied force u_k
// with components uniform in ±force_scale·m·g (fx, fy) and ±force_scale·m·g·radius (τ)
// acts: without known forces only the ratios of mass and inertia are identifiable from
// velocities (scaling both scales λ and leaves v⁺ unchanged). Transitions whose pre-state
// has no contact within the simulator's speculative margin are dropped when contact_only
// (free flight carries no information about μ or the geometry). Noise: independent
// N(0, noise²) added to every recorded component of q and v (both x_k and x_{k+1}; units
// as above), after the simulation. std::mt19937_64 with `seed`; the same data for every
// thread count and run.
//
// Loaded data: a trajectory CSV (scenes/trajectory_csv.hpp) of exactly one
// body; u = 0 (the CSV has no force columns). Δt is the time difference of consecutive
// frames, which must be the same for all (relative tolerance 1e-6) and steps must be
// consecutive. Errors are InputError naming the source, line and step.
#include <lcprelax/learn/polygon_params.hpp>
#include <lcprelax/scenes/scene.hpp>
#include <lcprelax/scenes/trajectory_csv.hpp>
#include <lcprelax/sparse/types.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace lcprelax::learn {

struct PolygonTransition {
  Vec3 q = Vec3::Zero(), v = Vec3::Zero();            ///< pre-state x_k
  Vec3 u = Vec3::Zero();                              ///< applied force during step k
  Vec3 q_next = Vec3::Zero(), v_next = Vec3::Zero();  ///< x_{k+1}
  int trajectory = 0;                                 ///< source trajectory
  int step = 0;                                       ///< k within it
};

struct PolygonDataset {
  double dt = 1e-2;                  ///< s
  Vec2 gravity{0.0, -9.81};          ///< m/s²
  double margin = 1e-2;              ///< contact margin (m) before the speculative part
  std::vector<PolygonTransition> transitions;
};

struct PolygonDataSettings {
  int trajectories = 8;         ///< ≥ 1
  int steps = 60;               ///< steps per trajectory, ≥ 1
  double dt = 1e-2;             ///< s, > 0
  double margin = 1e-2;         ///< m, ≥ 0
  Vec2 gravity{0.0, -9.81};     ///< m/s²
  double drop_height = 0.4;     ///< m, ≥ 0
  double throw_speed = 2.0;     ///< m/s, ≥ 0
  double spin = 6.0;            ///< rad/s, ≥ 0
  double force_scale = 0.5;     ///< ≥ 0, fraction of m·g (see above)
  double noise = 0.0;           ///< σ of the Gaussian noise, ≥ 0
  bool contact_only = true;
  ContactModel model = ContactModel::lcp;
  /// The truth's normal softness (world.hpp FrictionTable: compliance c in 1/kg ≥ 0, erp e in
  /// [0, 1]; nonzero needs model lcp). PolygonModel has no such parameter: a rigid model
  /// learned from soft data is misspecified on purpose (the structure experiments).
  double compliance = 0.0, erp = 0.0;
  std::uint64_t seed = 1;
  std::string validation_error() const;  ///< empty if valid, else names the field
};

/// Simulates `truth` (InputError for an invalid model or settings; std::runtime_error if a
/// simulator step fails to solve its contacts).
PolygonDataset generate_polygon_dataset(const PolygonModel& truth, const PolygonDataSettings& settings);

/// Transitions of a one-body trajectory (frames as read by read_trajectory). `source` and
/// the CSV layout (header + one row per frame) name the line in errors.
PolygonDataset polygon_dataset_from_frames(const std::vector<TrajectoryFrame>& frames, const std::string& source,
                                           const Vec2& gravity = Vec2(0.0, -9.81), double margin = 1e-2);

/// Reads a trajectory CSV file and converts it (errors of both steps as InputError).
PolygonDataset load_polygon_dataset(const std::string& path, const Vec2& gravity = Vec2(0.0, -9.81),
                                    double margin = 1e-2);

/// Writes the pre-states and next states of consecutive transitions of one trajectory as a
/// trajectory CSV (for tests and for inspecting generated data); only transitions of
/// `trajectory` are written, each x_k once, plus the last x_{k+1}.
void write_polygon_trajectory(const PolygonDataset& data, int trajectory, const std::string& path);

}  // namespace lcprelax::learn
