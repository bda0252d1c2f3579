// Scene datasets: shape classes, validation and generation by the Simulator
// (scene_dataset.hpp states the rules).
#include "random_draws.hpp"
#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/core/math_constants.hpp>
#include <lcprelax/learn/scene_params.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

namespace lcprelax::learn {
namespace {

using detail::normal;
using detail::uniform;


bool nonneg(double x) { return std::isfinite(x) && x >= 0; }


// An integer uniform in [0, n) (n ≥ 1) from the top 53 bits.
std::size_t below(std::mt19937_64& rng, std::size_t n) {
  const auto k = static_cast<std::size_t>(uniform(rng, 0.0, 1.0) * static_cast<double>(n));
  return std::min(k, n - 1);
}

// Adds N(0, σ²) to the dynamic bodies' components of `x`.
void add_noise(std::vector<Vec3>& x, const World& world, double sigma, std::mt19937_64& rng) {
  if (sigma <= 0) return;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!world.bodies[i].is_static)
      for (int c = 0; c < 3; ++c) x[i](c) += sigma * normal(rng);
}

void check_states(const std::vector<Vec3>& x, std::size_t bodies, const std::string& field) {
  if (x.size() != bodies)
    throw InputError(field + ": " + std::to_string(x.size()) + " entries for " + std::to_string(bodies) + " bodies");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!x[i].allFinite()) throw InputError(field + "[" + std::to_string(i) + "]: not finite");
}

}  // namespace

int SceneDataset::num_shape_classes() const {
  int n = 0;
  for (int c : shape_class) n = std::max(n, c + 1);
  return n;
}

void SceneDataset::validate() const {
  scene.validate();
  const std::size_t n = scene.world.bodies.size();
  if (shape_class != scene_shape_classes(scene.world))
    throw InputError("shape_class: does not match the scene's bodies (scene_shape_classes(scene.world))");
  for (std::size_t t = 0; t < transitions.size(); ++t) {
    const SceneTransition& tr = transitions[t];
    const std::string f = "transitions[" + std::to_string(t) + "].";
    if (tr.step < 0) throw InputError(f + "step: must be >= 0");
    if (t > 0 && tr.step <= transitions[t - 1].step) throw InputError(f + "step: steps must increase");
    check_states(tr.pose, n, f + "pose");
    check_states(tr.velocity, n, f + "velocity");
    check_states(tr.applied, n, f + "applied");
    check_states(tr.next_pose, n, f + "next_pose");
    check_states(tr.next_velocity, n, f + "next_velocity");
  }
}

std::string SceneDatasetSettings::validation_error() const {
  if (steps < 1) return "steps: must be >= 1";
  if (!(std::isfinite(push_fraction) && push_fraction >= 0 && push_fraction <= 1))
    return "push_fraction: must be in [0, 1]";
  if (push_interval < 1) return "push_interval: must be >= 1";
  if (!nonneg(push_force_min)) return "push_force_min: must be finite and >= 0";
  if (!(std::isfinite(push_force_max) && push_force_max >= push_force_min))
    return "push_force_max: must be finite and >= push_force_min";
  if (!nonneg(push_torque_max)) return "push_torque_max: must be finite and >= 0";
  if (!nonneg(pose_noise)) return "pose_noise: must be finite and >= 0";
  if (!nonneg(velocity_noise)) return "velocity_noise: must be finite and >= 0";
  if (threads < 0) return "threads: must be >= 0";
  return {};
}

SceneDataset generate_scene_dataset(const Scene& scene, const SceneDatasetSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string error = settings.validation_error();
  if (!error.empty()) throw InputError("scene dataset settings: " + error);
  scene.validate();

  SceneDataset data;
  data.scene = scene;
  data.scene.steps = settings.steps;
  data.shape_class = scene_shape_classes(scene.world);
  SimulatorSettings sim_settings = scene.settings;
  sim_settings.threads = settings.threads;
  Simulator sim = make_simulator(scene, sim_settings);

  const World& world = sim.world();
  const std::size_t n = world.bodies.size();
  std::vector<std::size_t> dynamic;
  for (std::size_t i = 0; i < n; ++i)
    if (!world.bodies[i].is_static) dynamic.push_back(i);
  const auto pushed = static_cast<std::size_t>(std::lround(settings.push_fraction * static_cast<double>(dynamic.size())));
  data.generation.pushed_bodies = static_cast<int>(pushed);

  std::mt19937_64 push_rng(settings.seed);
  std::mt19937_64 noise_rng(settings.seed ^ 0x6E6F697365ULL);  // "noise"
  // The recorded (noisy) state of the current step: drawn once per state, shared by the
  // transition that ends and the one that starts there.
  auto record = [&](std::vector<Vec3>& pose, std::vector<Vec3>& velocity) {
    pose.resize(n);
    velocity.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      pose[i] = world.bodies[i].pose;
      velocity[i] = world.bodies[i].velocity;
    }
    add_noise(pose, world, settings.pose_noise, noise_rng);
    add_noise(velocity, world, settings.velocity_noise, noise_rng);
  };

  std::vector<Vec3> applied(n, Vec3::Zero()), pose, velocity;
  record(pose, velocity);
  std::vector<std::size_t> order = dynamic;
  for (int k = 0; k < settings.steps; ++k) {
    if (k % settings.push_interval == 0) {
      std::fill(applied.begin(), applied.end(), Vec3::Zero());
      // Partial Fisher–Yates: the first `pushed` entries of `order` are a uniform sample.
      std::copy(dynamic.begin(), dynamic.end(), order.begin());
      for (std::size_t j = 0; j < pushed; ++j) {
        std::swap(order[j], order[j + below(push_rng, order.size() - j)]);
        const double magnitude = uniform(push_rng, settings.push_force_min, settings.push_force_max);
        const double angle = uniform(push_rng, 0.0, 2.0 * kPi);
        const double torque = uniform(push_rng, -settings.push_torque_max, settings.push_torque_max);
        applied[order[j]] = Vec3(magnitude * std::cos(angle), magnitude * std::sin(angle), torque);
      }
    }
    const StepStats stats = sim.step(applied);
    ++data.generation.steps;
    data.generation.inaccurate_islands += stats.inaccurate_islands;
    if (stats.failed_islands > 0 && !settings.allow_failed_islands)
      throw std::runtime_error("generate_scene_dataset: step " + std::to_string(k) + ": " +
                               std::to_string(stats.failed_islands) + " island(s) failed: " + stats.first_failure);
    SceneTransition t;
    t.step = k;
    t.pose = std::move(pose);
    t.velocity = std::move(velocity);
    t.applied = applied;
    record(t.next_pose, t.next_velocity);
    pose = t.next_pose;
    velocity = t.next_velocity;
    if (settings.drop_without_contact && stats.contacts == 0) {
      ++data.generation.dropped_without_contact;
      continue;
    }
    data.generation.contacts += stats.contacts;
    data.transitions.push_back(std::move(t));
  }
  data.generation.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return data;
}

}  // namespace lcprelax::learn
