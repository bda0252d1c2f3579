// Scene datasets from and to a scene JSON plus a trajectory CSV, and the contact test of a
// transition (scene_dataset.hpp states the rules).
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/learn/scene_params.hpp>
#include <lcprelax/scenes/scene_json.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lcprelax::learn {
namespace {

constexpr double kDtTolerance = 1e-6;      // relative, consecutive frame times vs the scene's dt
constexpr double kStaticTolerance = 1e-9;  // static bodies: |frame − scene| ≤ tol·(1 + |scene|)

bool close(const Vec3& a, const Vec3& b) {
  for (int c = 0; c < 3; ++c)
    if (!(std::abs(a(c) - b(c)) <= kStaticTolerance * (1.0 + std::abs(b(c))))) return false;
  return true;
}

std::string vec(const Vec3& x) {
  std::ostringstream os;
  os.precision(17);
  os << "(" << x(0) << ", " << x(1) << ", " << x(2) << ")";
  return os.str();
}

}  // namespace

bool transition_has_contact(const Scene& scene, const SceneTransition& t) {
  // The simulator's rule (simulator.hpp, step 1): the speculative margin covers the
  // fastest body's current and free velocity v* = v + Δt·M⁻¹(m g + u).
  const World& w = scene.world;
  const double dt = scene.settings.dt;
  World state = w;
  double fastest = 0.0;
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    RigidBody& b = state.bodies[i];
    b.pose = t.pose[i];
    b.velocity = t.velocity[i];
    if (b.is_static) continue;
    double r = 0.0;
    for (const Vec2& p : b.shape.vertices) r = std::max(r, p.norm());
    const Vec3 f = Vec3(b.mass * w.gravity.x(), b.mass * w.gravity.y(), 0.0) + t.applied[i];
    const Vec3 free = b.velocity + dt * Vec3(f(0) / b.mass, f(1) / b.mass, f(2) / b.inertia);
    for (const Vec3& v : {b.velocity, free}) fastest = std::max(fastest, v.head<2>().norm() + std::abs(v(2)) * r);
  }
  return !find_contacts(state, CollisionSettings{scene.settings.margin + 2.0 * fastest * dt}).empty();
}

SceneDataset scene_dataset_from_frames(const Scene& scene, const std::vector<TrajectoryFrame>& frames,
                                       const std::string& source, bool drop_without_contact) {
  scene.validate();
  const std::vector<RigidBody>& bodies = scene.world.bodies;
  const std::size_t n = bodies.size();
  auto at = [&](const TrajectoryFrame& f) { return source + ":" + std::to_string(f.line) + ": "; };
  if (frames.size() < 2)
    throw InputError(source + ": " + std::to_string(frames.size()) +
                     " frame(s); at least two consecutive frames are needed for a transition");
  const double dt = scene.settings.dt;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const TrajectoryFrame& f = frames[k];
    if (f.pose.size() != n)
      throw InputError(at(f) + "frame has " + std::to_string(f.pose.size()) + " bodies, the scene has " +
                       std::to_string(n));
    if (f.velocity.size() != n || (!f.applied.empty() && f.applied.size() != n))
      throw InputError(at(f) + "step " + std::to_string(f.step) + ": velocity or applied sizes differ from the poses");
    for (std::size_t i = 0; i < n; ++i) {
      const std::string body = "step " + std::to_string(f.step) + ", body " + std::to_string(i) + ": ";
      const Vec3 u = f.applied.empty() ? Vec3::Zero() : f.applied[i];
      if (!f.pose[i].allFinite() || !f.velocity[i].allFinite() || !u.allFinite() || !std::isfinite(f.time))
        throw InputError(at(f) + body + "non-finite value");
      if (!bodies[i].is_static) continue;
      if (!close(f.pose[i], bodies[i].pose))
        throw InputError(at(f) + body + "static body moves: pose " + vec(f.pose[i]) + ", the scene has " +
                         vec(bodies[i].pose));
      if (!close(f.velocity[i], bodies[i].velocity))
        throw InputError(at(f) + body + "static body has velocity " + vec(f.velocity[i]) + ", the scene has " +
                         vec(bodies[i].velocity));
      if (u != Vec3::Zero()) throw InputError(at(f) + body + "static body has an applied force " + vec(u));
    }
    if (f.step > scene.steps)
      throw InputError(at(f) + "step " + std::to_string(f.step) + " is beyond the scene's " +
                       std::to_string(scene.steps) + " steps");
    if (k == 0) continue;
    const TrajectoryFrame& p = frames[k - 1];
    if (f.step != p.step + 1)
      throw InputError(at(f) + "step " + std::to_string(f.step) + " follows step " + std::to_string(p.step) +
                       " (steps must be consecutive)");
    const double step_dt = f.time - p.time;
    if (!(std::abs(step_dt - dt) <= kDtTolerance * dt))
      throw InputError(at(f) + "step " + std::to_string(f.step) + ": time difference " + std::to_string(step_dt) +
                       " s to the previous frame differs from the scene's dt " + std::to_string(dt) + " s");
  }

  SceneDataset data;
  data.scene = scene;
  data.shape_class = scene_shape_classes(scene.world);
  for (std::size_t k = 1; k < frames.size(); ++k) {
    const TrajectoryFrame& p = frames[k - 1];
    SceneTransition t;
    t.step = p.step;
    t.pose = p.pose;
    t.velocity = p.velocity;
    t.applied = p.applied.empty() ? std::vector<Vec3>(n, Vec3::Zero()) : p.applied;
    t.next_pose = frames[k].pose;
    t.next_velocity = frames[k].velocity;
    if (drop_without_contact && !transition_has_contact(scene, t)) continue;
    data.transitions.push_back(std::move(t));
  }
  return data;
}

SceneDataset load_scene_dataset(const std::string& scene_json_path, const std::string& trajectory_csv_path,
                                bool drop_without_contact) {
  const Scene scene = load_scene(scene_json_path);
  try {
    scene.validate();
  } catch (const InputError& e) {
    throw InputError(scene_json_path + ": " + e.what());
  }
  return scene_dataset_from_frames(scene, load_trajectory(trajectory_csv_path), trajectory_csv_path,
                                   drop_without_contact);
}

void write_scene_dataset(const SceneDataset& data, const std::string& scene_json_path,
                         const std::string& trajectory_csv_path) {
  data.validate();
  if (data.transitions.empty()) throw InputError("write_scene_dataset: the dataset has no transitions");
  for (std::size_t t = 1; t < data.transitions.size(); ++t)
    if (data.transitions[t].step != data.transitions[t - 1].step + 1)
      throw InputError("write_scene_dataset: transitions[" + std::to_string(t) + "].step: step " +
                       std::to_string(data.transitions[t].step) + " follows step " +
                       std::to_string(data.transitions[t - 1].step) +
                       " (a trajectory needs consecutive steps; generate with drop_without_contact = false)");
    else if (data.transitions[t].pose != data.transitions[t - 1].next_pose ||
             data.transitions[t].velocity != data.transitions[t - 1].next_velocity)
      throw InputError("write_scene_dataset: transitions[" + std::to_string(t) +
                       "]: the state differs from the previous transition's next state");
  save_scene(scene_json_path, data.scene);
  const double dt = data.scene.settings.dt;
  TrajectoryWriter writer(trajectory_csv_path, true);
  for (const SceneTransition& t : data.transitions)
    writer.write(TrajectoryFrame{t.step, t.step * dt, t.pose, t.velocity, t.applied});
  const SceneTransition& last = data.transitions.back();
  writer.write(TrajectoryFrame{last.step + 1, (last.step + 1) * dt, last.next_pose, last.next_velocity, {}});
  writer.flush();
}

}  // namespace lcprelax::learn
