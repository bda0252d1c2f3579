// Transitions of a polygon on the ground: generation and CSV loading (polygon_dataset.hpp).
#include "random_draws.hpp"
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/math_constants.hpp>
#include <lcprelax/learn/polygon_dataset.hpp>
#include <lcprelax/learn/polygon_scene.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/world/normal_softness.hpp>

#include <cmath>
#include <random>
#include <stdexcept>

namespace lcprelax::learn {
namespace {

using detail::normal;
using detail::uniform;


bool nonneg(double x) { return std::isfinite(x) && x >= 0; }


}  // namespace

std::string PolygonDataSettings::validation_error() const {
  if (trajectories < 1) return "trajectories: must be >= 1";
  if (steps < 1) return "steps: must be >= 1";
  if (!(std::isfinite(dt) && dt > 0)) return "dt: must be finite and > 0";
  if (!nonneg(margin)) return "margin: must be finite and >= 0";
  if (!gravity.allFinite()) return "gravity: must be finite";
  if (!nonneg(drop_height)) return "drop_height: must be finite and >= 0";
  if (!nonneg(throw_speed)) return "throw_speed: must be finite and >= 0";
  if (!nonneg(spin)) return "spin: must be finite and >= 0";
  if (!nonneg(force_scale)) return "force_scale: must be finite and >= 0";
  if (!nonneg(noise)) return "noise: must be finite and >= 0";
  if (std::string e = normal_softness_value_error(compliance, erp); !e.empty()) return e;
  if ((compliance != 0.0 || erp != 0.0) && model != ContactModel::lcp)
    return "compliance, erp: the normal softness needs model lcp";
  return {};
}

PolygonDataset generate_polygon_dataset(const PolygonModel& truth, const PolygonDataSettings& settings) {
  const std::string model_error = truth.validation_error();
  if (!model_error.empty()) throw InputError("polygon model: " + model_error);
  const std::string error = settings.validation_error();
  if (!error.empty()) throw InputError("polygon data settings: " + error);

  PolygonDataset data;
  data.dt = settings.dt;
  data.gravity = settings.gravity;
  data.margin = settings.margin;
  std::mt19937_64 rng(settings.seed);
  const HalfPlane ground = ground_half_plane(truth.ground_height, truth.ground_angle);
  const double radius = polygon_radius(truth.shape);
  const double mg = truth.mass * settings.gravity.norm();

  for (int traj = 0; traj < settings.trajectories; ++traj) {
    Scene scene = polygon_scene(truth, settings.dt, settings.gravity, settings.margin);
    scene.world.friction.default_compliance = settings.compliance;
    scene.world.friction.default_erp = settings.erp;
    RigidBody& body = scene.world.bodies[0];
    const double angle = uniform(rng, -kPi, kPi);
    // Place the lowest vertex (along the ground normal) drop_height·[0.5, 1] above the
    // ground, at a random position along the ground line within ±radius of (0, h).
    body.pose = Vec3(0.0, 0.0, angle);
    double lowest = INFINITY;
    for (const Vec2& v : truth.shape.vertices) lowest = std::min(lowest, ground.normal.dot(to_world(body.pose, v)));
    const double height = settings.drop_height * uniform(rng, 0.5, 1.0);
    const Vec2 along(ground.normal.y(), -ground.normal.x());
    const Vec2 base = Vec2(0.0, truth.ground_height) + uniform(rng, -radius, radius) * along;
    const Vec2 centre = base + (height - lowest) * ground.normal;
    body.pose.head<2>() = centre;
    body.velocity = Vec3(uniform(rng, -settings.throw_speed, settings.throw_speed),
                         uniform(rng, -0.5 * settings.throw_speed, 0.5 * settings.throw_speed),
                         uniform(rng, -settings.spin, settings.spin));
    scene.settings.model = settings.model;
    scene.steps = settings.steps;
    SimulatorSettings sim_settings;
    sim_settings.threads = 1;
    Simulator sim = make_simulator(scene, sim_settings);
    for (int k = 0; k < settings.steps; ++k) {
      PolygonTransition t;
      t.trajectory = traj;
      t.step = k;
      t.q = sim.world().bodies[0].pose;
      t.v = sim.world().bodies[0].velocity;
      t.u = Vec3(uniform(rng, -1.0, 1.0) * settings.force_scale * mg, uniform(rng, -1.0, 1.0) * settings.force_scale * mg,
                 uniform(rng, -1.0, 1.0) * settings.force_scale * mg * radius);
      const StepStats stats = sim.step({t.u});
      if (stats.failed_islands > 0)
        throw std::runtime_error("generate_polygon_dataset: trajectory " + std::to_string(traj) + " step " +
                                 std::to_string(k) + ": " + stats.first_failure);
      t.q_next = sim.world().bodies[0].pose;
      t.v_next = sim.world().bodies[0].velocity;
      if (!settings.contact_only || !sim.contacts().empty()) data.transitions.push_back(t);
    }
  }
  if (settings.noise > 0) {
    std::mt19937_64 noise_rng(settings.seed ^ 0x6E6F697365ULL);  // "noise"
    for (PolygonTransition& t : data.transitions)
      for (Vec3* x : {&t.q, &t.v, &t.q_next, &t.v_next})
        for (int i = 0; i < 3; ++i) (*x)(i) += settings.noise * normal(noise_rng);
  }
  return data;
}

PolygonDataset polygon_dataset_from_frames(const std::vector<TrajectoryFrame>& frames, const std::string& source,
                                           const Vec2& gravity, double margin) {
  if (!gravity.allFinite()) throw InputError(source + ": gravity must be finite");
  if (!nonneg(margin)) throw InputError(source + ": margin must be finite and >= 0");
  if (frames.size() < 2)
    throw InputError(source + ": a trajectory of at least two frames is needed (found " +
                     std::to_string(frames.size()) + ")");
  // One body per frame: frame f is on CSV line 2 + f.
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (frames[f].pose.size() != 1)
      throw InputError(source + ":" + std::to_string(3 + f) + ": step " +
                       std::to_string(frames[f].step) + " has " + std::to_string(frames[f].pose.size()) +
                       " bodies (one polygon expected)");
    if (!frames[f].pose[0].allFinite() || !frames[f].velocity[0].allFinite() || !std::isfinite(frames[f].time))
      throw InputError(source + ":" + std::to_string(2 + f) + ": step " + std::to_string(frames[f].step) +
                       ": non-finite value");
  }
  PolygonDataset data;
  data.dt = frames[1].time - frames[0].time;
  data.gravity = gravity;
  data.margin = margin;
  if (!(data.dt > 0)) throw InputError(source + ":3: time must increase (dt = " + std::to_string(data.dt) + ")");
  for (std::size_t f = 1; f < frames.size(); ++f) {
    const std::string where = source + ":" + std::to_string(2 + f) + ": step " + std::to_string(frames[f].step);
    if (frames[f].step != frames[f - 1].step + 1)
      throw InputError(where + ": steps must be consecutive (previous step " + std::to_string(frames[f - 1].step) + ")");
    const double dt = frames[f].time - frames[f - 1].time;
    if (!(std::abs(dt - data.dt) <= 1e-6 * data.dt))
      throw InputError(where + ": time step " + std::to_string(dt) + " differs from the first (" +
                       std::to_string(data.dt) + ")");
    PolygonTransition t;
    t.q = frames[f - 1].pose[0];
    t.v = frames[f - 1].velocity[0];
    t.q_next = frames[f].pose[0];
    t.v_next = frames[f].velocity[0];
    t.step = frames[f - 1].step;
    data.transitions.push_back(t);
  }
  return data;
}

PolygonDataset load_polygon_dataset(const std::string& path, const Vec2& gravity, double margin) {
  return polygon_dataset_from_frames(load_trajectory(path), path, gravity, margin);
}

void write_polygon_trajectory(const PolygonDataset& data, int trajectory, const std::string& path) {
  TrajectoryWriter writer(path);
  const PolygonTransition* last = nullptr;
  for (const PolygonTransition& t : data.transitions) {
    if (t.trajectory != trajectory) continue;
    if (last && t.step != last->step + 1)
      throw InputError("write_polygon_trajectory: trajectory " + std::to_string(trajectory) +
                       " has a gap after step " + std::to_string(last->step) + " (generate with contact_only = false)");
    writer.write(TrajectoryFrame{t.step, t.step * data.dt, {t.q}, {t.v}});
    last = &t;
  }
  if (!last) throw InputError("write_polygon_trajectory: no transitions of trajectory " + std::to_string(trajectory));
  writer.write(TrajectoryFrame{last->step + 1, (last->step + 1) * data.dt, {last->q_next}, {last->v_next}});
  writer.flush();
}

}  // namespace lcprelax::learn
