// Learning on a multi-body scene (scene_objective.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/models/simulator.hpp>

#include "proximal_centers.hpp"

#include <algorithm>
#include <chrono>
#include <exception>

namespace lcprelax::learn {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

struct SceneObjective::Workspace {
  World world;
  Vector theta;  // the θ `world` carries
  WorldGradient gradient;
  SceneObjectiveStats stats;
  Vector target, center;
  std::unique_ptr<RelaxedStepLossWorkspace> relaxed;  // keeps the QpSolver between islands
};

std::string SceneLossSettings::validation_error() const {
  std::string e = hard.validation_error();
  if (!e.empty()) return "hard." + e;
  e = relaxed.validation_error();
  if (!e.empty()) return "relaxed." + e;
  e = convex.validation_error();
  if (!e.empty()) return "convex." + e;
  if (relaxed_cold_iterations < 1) return "relaxed_cold_iterations: must be >= 1";
  return {};
}

SceneObjective::SceneObjective(const SceneDataset& data, const SceneParameterMap& map, SceneLossSettings settings)
    : data_(data), map_(map), settings_(std::move(settings)) {
  const std::string e = settings_.validation_error();
  if (!e.empty()) throw InputError("scene loss settings: " + e);
  if (data_.transitions.empty()) throw InputError("scene dataset: no transitions");
  data_.validate();
  if (map_.body_class().size() != data_.scene.world.bodies.size())
    throw InputError("scene parameters: the map was built for another scene");
  centers_.resize(data_.transitions.size());
}

void SceneObjective::reset_centers() {
  for (detail::ProximalCenters& c : centers_) c.clear();
}

SceneObjective::~SceneObjective() = default;

void SceneObjective::save_state(StateWriter& out) const {
  out.put_string("scene: proximal centres");
  out.put_u64(centers_.size());
  for (const detail::ProximalCenters& c : centers_) c.save(out);
}

void SceneObjective::load_state(StateReader& in) {
  in.expect_tag("scene: proximal centres");
  in.get_count(centers_.size(), false, "transitions");
  for (detail::ProximalCenters& c : centers_) c.load(in);
}

Index SceneObjective::num_samples() const { return static_cast<Index>(data_.transitions.size()); }

void SceneObjective::prepare(const ParameterSet& theta, int threads) {
  if (theta.size() != map_.size()) throw InputError("scene parameters: θ does not have the scene's layout");
  while (static_cast<int>(workspaces_.size()) < threads) {
    auto ws = std::make_unique<Workspace>();
    ws->world = data_.scene.world;
    ws->relaxed = std::make_unique<RelaxedStepLossWorkspace>(settings_.relaxed);
    workspaces_.push_back(std::move(ws));
  }
  const Vector values = theta.values();
  for (auto& ws : workspaces_) {
    if (ws->theta.size() == values.size() && ws->theta == values) continue;
    map_.apply(theta, ws->world);
    ws->theta = values;
  }
}

SampleResult SceneObjective::evaluate(Index sample, const ParameterSet& theta, int thread) {
  Workspace& ws = *workspaces_.at(static_cast<std::size_t>(thread));
  if (ws.theta.size() != theta.size() || ws.theta != theta.values())
    throw std::logic_error("SceneObjective::evaluate: prepare() was not called with this θ");
  const SceneTransition& t = data_.transitions.at(static_cast<std::size_t>(sample));
  World& world = ws.world;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    world.bodies[b].pose = t.pose[b];
    world.bodies[b].velocity = t.velocity[b];
  }
  const SimulatorSettings& sim = data_.scene.settings;
  const double dt = sim.dt;
  SampleResult out;
  auto t0 = std::chrono::steady_clock::now();
  const StepContacts found = find_step_contacts(world, sim, t.applied);
  ws.stats.seconds_collision += seconds_since(t0);
  ws.gradient.set_zero(world, found.contacts.size());
  ++ws.stats.transitions;
  ws.stats.contacts += static_cast<long>(found.contacts.size());

  if (settings_.method == LossMethod::relaxed) centers_[static_cast<std::size_t>(sample)].begin();
  std::vector<bool> in_island(world.bodies.size(), false);
  for (std::size_t k = 0; k < found.islands.size(); ++k) {
    t0 = std::chrono::steady_clock::now();
    const ContactSystem s = assemble_contact_system(world, found.contacts, found.islands[k], dt, t.applied);
    ws.target.resize(s.num_dofs());
    for (std::size_t j = 0; j < s.bodies.size(); ++j) {
      const std::size_t b = static_cast<std::size_t>(s.bodies[j]);
      ws.target.segment<3>(3 * static_cast<Index>(j)) = t.next_velocity[b];
      in_island[b] = true;
    }
    StepLossResult r;
    switch (settings_.method) {
      case LossMethod::hard: r = hard_step_loss(s, ws.target, dt, settings_.hard); break;
      case LossMethod::relaxed: {
        detail::ProximalCenters& centers = centers_[static_cast<std::size_t>(sample)];
        const bool warm = settings_.relaxed_warm_center && !centers.empty();
        const int cold = warm ? centers.lookup(found.contacts, s, ws.center) : static_cast<int>(s.num_contacts());
        ws.stats.cold_contacts += cold;
        const int iterations = settings_.relaxed_warm_center && cold > 0
                                   ? std::max(settings_.relaxed_cold_iterations, settings_.relaxed.proximal_iterations)
                                   : 0;
        const int solves0 = ws.relaxed->proximal_solves();
        r = ws.relaxed->evaluate(s, ws.target, dt, warm ? &ws.center : nullptr, iterations);
        ws.stats.proximal_solves += ws.relaxed->proximal_solves() - solves0;
        if (settings_.relaxed_warm_center && has_solution(r.status))
          centers.record(found.contacts, s, ws.relaxed->proximal_point());
        break;
      }
      case LossMethod::convex: r = convex_step_loss(s, ws.target, dt, settings_.convex); break;
    }
    ws.stats.seconds_loss += seconds_since(t0);
    ++ws.stats.islands;
    if (!has_solution(r.status)) {
      ++ws.stats.failed_islands;
      out.ok = false;
      out.message = "transition " + std::to_string(sample) + " (step " + std::to_string(t.step) + "), island " +
                    std::to_string(k) + " (" + std::to_string(s.num_contacts()) + " contacts): " + to_string(r.status) +
                    (r.message.empty() ? "" : ": " + r.message);
      return out;
    }
    if (r.status == ContactStatus::solved_inaccurate) ++ws.stats.inaccurate_islands;
    out.loss += r.loss;
    t0 = std::chrono::steady_clock::now();
    accumulate_world_gradient(world, found.contacts, s, dt, t.applied, r.grad, ws.gradient);
    ws.stats.seconds_pullback += seconds_since(t0);
  }

  // Free flight: v⁺ = v* = v + Δt (g + u_xy/m, u_τ/I).
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const RigidBody& body = world.bodies[b];
    if (body.is_static || in_island[b]) continue;
    const Vec3 u = t.applied.empty() ? Vec3::Zero() : t.applied[b];
    const Vec3 v_star = body.velocity + dt * Vec3(world.gravity.x() + u.x() / body.mass,
                                                  world.gravity.y() + u.y() / body.mass, u.z() / body.inertia);
    const Vec3 e = v_star - t.next_velocity[b];
    out.loss += e.squaredNorm();
    ws.gradient.bodies[b].mass += -2.0 * dt * (e.x() * u.x() + e.y() * u.y()) / (body.mass * body.mass);
    ws.gradient.bodies[b].inertia += -2.0 * dt * e.z() * u.z() / (body.inertia * body.inertia);
  }
  if (settings_.method == LossMethod::relaxed && settings_.relaxed_warm_center)
    centers_[static_cast<std::size_t>(sample)].commit();
  out.gradient = map_.gradient(world, found.contacts, ws.gradient);
  return out;
}

SceneObjectiveStats SceneObjective::stats() const {
  SceneObjectiveStats s;
  for (const auto& ws : workspaces_) {
    s.transitions += ws->stats.transitions;
    s.islands += ws->stats.islands;
    s.contacts += ws->stats.contacts;
    s.inaccurate_islands += ws->stats.inaccurate_islands;
    s.failed_islands += ws->stats.failed_islands;
    s.cold_contacts += ws->stats.cold_contacts;
    s.proximal_solves += ws->stats.proximal_solves;
    s.seconds_collision += ws->stats.seconds_collision;
    s.seconds_loss += ws->stats.seconds_loss;
    s.seconds_pullback += ws->stats.seconds_pullback;
  }
  return s;
}

void SceneObjective::reset_stats() {
  for (auto& ws : workspaces_) ws->stats = SceneObjectiveStats{};
}

}  // namespace lcprelax::learn
