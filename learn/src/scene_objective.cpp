// Learning on a multi-body scene (scene_objective.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/models/lcp_basis_codes.hpp>
#include <lcprelax/models/simulator.hpp>

#include "proximal_centers.hpp"

#include <algorithm>
#include <lcprelax/core/stopwatch.hpp>

#include <chrono>
#include <cmath>
#include <exception>

namespace lcprelax::learn {

namespace {
// Added to a stored basis's normal codes (lcp_basis_codes.hpp: 0 or 1) of an island whose
// answer was regularized (StepLossResult::regularized).
constexpr double kRegularizedCode = 2.0;
}  // namespace

struct SceneObjective::Workspace {
  World world;
  Vector theta;  // the θ `world` carries
  WorldGradient gradient;
  SceneObjectiveStats stats;
  Vector target, center;
  std::vector<bool> warm_basis, final_basis;  // hard method
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
  if (map_.learns_lcp_block() && settings_.method != LossMethod::hard)
    throw InputError("scene loss: the lcp model's per-contact LCP block (learn block or block_tied) is learned with the "
                     "hard loss only");
  centers_.resize(data_.transitions.size());
  perturbed_runs_.assign(data_.transitions.size(), 0);
}

bool SceneObjective::keeps_contact_values() const {
  return (settings_.method == LossMethod::relaxed && settings_.relaxed_warm_center) ||
         (settings_.method == LossMethod::hard && settings_.hard_warm_basis);
}

void SceneObjective::reset_centers() {
  for (detail::ProximalCenters& c : centers_) c.clear();
  std::fill(perturbed_runs_.begin(), perturbed_runs_.end(), static_cast<unsigned char>(0));
}

SceneObjective::~SceneObjective() = default;

void SceneObjective::save_state(StateWriter& out) const {
  out.put_string("scene: proximal centres");
  out.put_u64(centers_.size());
  for (const detail::ProximalCenters& c : centers_) c.save(out);
  out.put_string("scene: perturbed runs");
  out.put_ints(std::vector<int>(perturbed_runs_.begin(), perturbed_runs_.end()));
}

void SceneObjective::load_state(StateReader& in) {
  in.expect_tag("scene: proximal centres");
  in.get_count(centers_.size(), false, "transitions");
  for (detail::ProximalCenters& c : centers_) c.load(in);
  std::fill(perturbed_runs_.begin(), perturbed_runs_.end(), static_cast<unsigned char>(0));
  if (in.remaining() == 0) return;  // a state saved before the runs were kept: none
  in.expect_tag("scene: perturbed runs");
  const std::vector<int> runs = in.get_ints();
  if (runs.size() != perturbed_runs_.size())
    throw InputError("scene objective state: " + std::to_string(runs.size()) + " perturbed-run counts for " +
                     std::to_string(perturbed_runs_.size()) + " transitions");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (runs[i] < 0 || runs[i] > 64) throw InputError("scene objective state: a perturbed-run count outside 0…64");
    perturbed_runs_[i] = static_cast<unsigned char>(runs[i]);
  }
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

namespace {

// v* of a body in free flight: v + Δt (g + u_xy/m, u_τ/I) (+ W f, its velocity residual).
Vec3 free_flight_velocity(const World& world, const RigidBody& body, const Vec3& u, double dt) {
  const Vec3 v = body.velocity + dt * Vec3(world.gravity.x() + u.x() / body.mass,
                                           world.gravity.y() + u.y() / body.mass, u.z() / body.inertia);
  return has_velocity_residual(body) ? Vec3(v + velocity_residual_term(body)) : v;
}

std::string island_failure(Index sample, const SceneTransition& t, std::size_t k, const ContactSystem& s,
                           ContactStatus status, const std::string& message) {
  return "transition " + std::to_string(sample) + " (step " + std::to_string(t.step) + "), island " +
         std::to_string(k) + " (" + std::to_string(s.num_contacts()) + " contacts): " + to_string(status) +
         (message.empty() ? "" : ": " + message);
}

// Counts island k's outcome in `stats`; false, with `message` naming the island, when its
// solve has no solution.
bool count_island(SceneObjectiveStats& stats, Index sample, const SceneTransition& t, std::size_t k,
                  const ContactSystem& s, ContactStatus status, const std::string& why, std::string& message) {
  ++stats.islands;
  if (!has_solution(status)) {
    ++stats.failed_islands;
    message = island_failure(sample, t, k, s, status, why);
    return false;
  }
  if (status == ContactStatus::solved_inaccurate) ++stats.inaccurate_islands;
  return true;
}

}  // namespace

StepContacts SceneObjective::begin_transition(Workspace& ws, Index sample, const ParameterSet& theta) {
  if (ws.theta.size() != theta.size() || ws.theta != theta.values())
    throw std::logic_error("SceneObjective: prepare() was not called with this θ");
  const SceneTransition& t = data_.transitions.at(static_cast<std::size_t>(sample));
  World& world = ws.world;
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    world.bodies[b].pose = t.pose[b];
    world.bodies[b].velocity = t.velocity[b];
  }
  auto t0 = std::chrono::steady_clock::now();
  StepContacts found = find_step_contacts(world, data_.scene.settings, t.applied);
  ws.stats.seconds_collision += seconds_since(t0);
  ws.gradient.set_zero(world, found.contacts.size());
  ++ws.stats.transitions;
  ws.stats.contacts += static_cast<long>(found.contacts.size());
  return found;
}

ContactSystem SceneObjective::island_system(Workspace& ws, const StepContacts& found, std::size_t k,
                                            const SceneTransition& t, std::vector<bool>& in_island) const {
  ContactSystem s = assemble_contact_system(ws.world, found.contacts, found.islands[k], data_.scene.settings.dt, t.applied);
  ws.target.resize(s.num_dofs());
  for (std::size_t j = 0; j < s.bodies.size(); ++j) {
    const std::size_t b = static_cast<std::size_t>(s.bodies[j]);
    ws.target.segment<3>(3 * static_cast<Index>(j)) = t.next_velocity[b];
    in_island[b] = true;
  }
  return s;
}

SampleResult SceneObjective::evaluate(Index sample, const ParameterSet& theta, int thread) {
  Workspace& ws = *workspaces_.at(static_cast<std::size_t>(thread));
  const StepContacts found = begin_transition(ws, sample, theta);
  const SceneTransition& t = data_.transitions[static_cast<std::size_t>(sample)];
  World& world = ws.world;
  const double dt = data_.scene.settings.dt;
  SampleResult out;

  if (keeps_contact_values()) centers_[static_cast<std::size_t>(sample)].begin();
  std::vector<bool> in_island(world.bodies.size(), false);
  unsigned char& perturbed_runs = perturbed_runs_[static_cast<std::size_t>(sample)];
  const bool skip_exact_cold = perturbed_runs > 0 && perturbed_runs % kExactRetryEvery != 0;
  bool inaccurate = false;  // some island of this evaluation ended solved_inaccurate (hard, stored bases)
  for (std::size_t k = 0; k < found.islands.size(); ++k) {
    auto t0 = std::chrono::steady_clock::now();
    const ContactSystem s = island_system(ws, found, k, t, in_island);
    StepLossResult r;
    switch (settings_.method) {
      case LossMethod::hard: {
        if (!settings_.hard_warm_basis) {
          ws.stats.cold_contacts += s.num_contacts();
          r = hard_step_loss(s, ws.target, dt, settings_.hard);
          break;
        }
        detail::ProximalCenters& bases = centers_[static_cast<std::size_t>(sample)];
        const Index nc = s.num_contacts(), nf = s.num_friction();
        ws.warm_basis.clear();
        // A stored normal code of 2 or 3 (kRegularizedCode + 0/1) marks a contact of an island
        // whose answer was regularized: as the simulator's warm-start entries
        // (ContactWarmRecord::regularized), the island then starts with step 1c.
        bool warm_from_regularized = false;
        if (!bases.empty()) {
          ws.stats.cold_contacts += bases.lookup(found.contacts, s, ws.center);
          for (Index c = 0; c < nc; ++c) {
            if (ws.center(c) < kRegularizedCode) continue;
            warm_from_regularized = true;
            ws.center(c) -= kRegularizedCode;
          }
          decode_lcp_basis(ws.center, nc, nf, ws.warm_basis);
        } else {
          ws.stats.cold_contacts += nc;
        }
        r = hard_step_loss(s, ws.target, dt, settings_.hard, ws.warm_basis, &ws.final_basis,
                           skip_exact_cold && !ws.warm_basis.empty(), warm_from_regularized && !ws.warm_basis.empty());
        inaccurate = inaccurate || r.status == ContactStatus::solved_inaccurate;
        if (has_solution(r.status) && static_cast<Index>(ws.final_basis.size()) == nc + 3 * nf) {
          encode_lcp_basis(ws.final_basis, nc, nf, ws.center);
          if (r.regularized) ws.center.head(nc).array() += kRegularizedCode;
          bases.record(found.contacts, s, ws.center);
        }
        break;
      }
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
    ws.stats.solver_work += r.work;
    if (!count_island(ws.stats, sample, t, k, s, r.status, r.message, out.message)) {
      out.ok = false;
      return out;
    }
    out.loss += r.loss;
    t0 = std::chrono::steady_clock::now();
    accumulate_world_gradient(world, found.contacts, s, dt, t.applied, r.grad, ws.gradient);
    ws.stats.seconds_pullback += seconds_since(t0);
  }

  // Free flight: v⁺ = v*, whose gradient reaches mass and inertia through u.
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const RigidBody& body = world.bodies[b];
    if (body.is_static || in_island[b]) continue;
    const Vec3 u = t.applied.empty() ? Vec3::Zero() : t.applied[b];
    const Vec3 e = free_flight_velocity(world, body, u, dt) - t.next_velocity[b];
    out.loss += e.squaredNorm();
    ws.gradient.bodies[b].mass += -2.0 * dt * (e.x() * u.x() + e.y() * u.y()) / (body.mass * body.mass);
    ws.gradient.bodies[b].inertia += -2.0 * dt * e.z() * u.z() / (body.inertia * body.inertia);
    ws.gradient.bodies[b].velocity_residual += 2.0 * e * velocity_residual_features(body).transpose();
  }
  if (keeps_contact_values()) centers_[static_cast<std::size_t>(sample)].commit();
  if (settings_.method == LossMethod::hard && settings_.hard_warm_basis)
    perturbed_runs = inaccurate ? static_cast<unsigned char>(1 + perturbed_runs % 64) : 0;
  out.gradient = map_.gradient(world, found.contacts, ws.gradient);
  return out;
}

std::string SceneObjective::residuals_unavailable() const {
  if (settings_.method == LossMethod::convex) return {};
  return std::string("the ") + to_string(settings_.method) +
         " loss gives no residual Jacobian (the convex loss does: --method convex)";
}

ResidualResult SceneObjective::evaluate_residuals(Index sample, const ParameterSet& theta, int thread) {
  const std::string why = residuals_unavailable();
  if (!why.empty()) throw std::logic_error("SceneObjective::evaluate_residuals: " + why);
  Workspace& ws = *workspaces_.at(static_cast<std::size_t>(thread));
  const StepContacts found = begin_transition(ws, sample, theta);
  const SceneTransition& t = data_.transitions[static_cast<std::size_t>(sample)];
  World& world = ws.world;
  const double dt = data_.scene.settings.dt;
  const Index rows = 3 * static_cast<Index>(world.bodies.size());
  ResidualResult out;
  out.residual = Vector::Zero(rows);
  out.jacobian = DenseMatrix::Zero(rows, theta.size());

  std::vector<bool> in_island(world.bodies.size(), false);
  for (std::size_t k = 0; k < found.islands.size(); ++k) {
    auto t0 = std::chrono::steady_clock::now();
    const ContactSystem s = island_system(ws, found, k, t, in_island);
    const StepJacobianResult r = convex_step_jacobian(s, ws.target, dt, settings_.convex);
    ws.stats.seconds_loss += seconds_since(t0);
    ws.stats.solver_work += r.work;
    if (!count_island(ws.stats, sample, t, k, s, r.status, r.message, out.message)) {
      out.ok = false;
      return out;
    }
    t0 = std::chrono::steady_clock::now();
    for (std::size_t j = 0; j < s.bodies.size(); ++j) {
      const Index row0 = 3 * static_cast<Index>(s.bodies[j]);
      for (Index c = 0; c < 3; ++c) {
        const Index local = 3 * static_cast<Index>(j) + c;
        out.residual(row0 + c) = r.v_next(local) - ws.target(local);
        ws.gradient.set_zero(world, found.contacts.size());
        accumulate_world_gradient(world, found.contacts, s, dt, t.applied, r.rows[static_cast<std::size_t>(local)],
                                  ws.gradient);
        out.jacobian.row(row0 + c) = map_.gradient(world, found.contacts, ws.gradient).transpose();
      }
    }
    ws.stats.seconds_pullback += seconds_since(t0);
  }

  // Free flight: r = v* − v̄, ∂v*_xy/∂m = −Δt u_xy/m², ∂v*_ω/∂I = −Δt u_τ/I².
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const RigidBody& body = world.bodies[b];
    if (body.is_static || in_island[b]) continue;
    const Vec3 u = t.applied.empty() ? Vec3::Zero() : t.applied[b];
    const Index row0 = 3 * static_cast<Index>(b);
    out.residual.segment<3>(row0) = free_flight_velocity(world, body, u, dt) - t.next_velocity[b];
    const double dm[3] = {-dt * u.x() / (body.mass * body.mass), -dt * u.y() / (body.mass * body.mass), 0.0};
    for (Index c = 0; c < 3; ++c) {
      ws.gradient.set_zero(world, found.contacts.size());
      ws.gradient.bodies[b].mass = dm[c];
      ws.gradient.bodies[b].inertia = c == 2 ? -dt * u.z() / (body.inertia * body.inertia) : 0.0;
      ws.gradient.bodies[b].velocity_residual.row(c) = velocity_residual_features(body).transpose();
      out.jacobian.row(row0 + c) = map_.gradient(world, found.contacts, ws.gradient).transpose();
    }
  }
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
    s.solver_work += ws->stats.solver_work;
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
