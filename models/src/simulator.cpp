// Time stepping over islands with warm starts and post-stabilization (simulator.hpp).
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/lcp_basis_codes.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/world/normal_softness.hpp>

#include "delassus.hpp"

#include <algorithm>
#include <lcprelax/core/stopwatch.hpp>

#include <chrono>
#include <cmath>
#include <exception>
#include <optional>
#include <limits>
#include <sstream>
#include <string>

#ifdef LCPRELAX_HAS_OPENMP
#include <omp.h>
#endif

namespace lcprelax {
namespace {

// Largest island (contacts) whose failed convex solve is retried with the LCP model: Lemke
// is milliseconds there, while on pile-sized islands (hundreds of contacts) it can take
// seconds to minutes with its retries (contact_step.hpp), so those keep phase 1's answer.
constexpr Index kConvexFallbackMaxContacts = 64;

// An island with more than kRedundantContactsPerDof contacts per degree of freedom (bodies
// stacked into each other: 100 coincident boxes pose 9,900 contacts on 300 DOFs, 300 boxes
// 89,700 on 900) makes every Delassus-based LCP huge, singular and degenerate: Lemke's
// lexicographic ties then ran for minutes per step, and the Delassus matrix (nnz ~ Σ_b k_b²,
// k_b the contacts of body b) exhausted the memory (300 boxes: bad_alloc at 4.4 GB). Such an
// island is solved by the interior point on the primal side only (the convex model in its
// lifted form, the QP position projection), whose size is linear in the contacts. A
// physical packing has about 1–2 contacts per DOF; 4 is far from it.
constexpr Index kRedundantContactsPerDof = 4;

bool redundant_island(const ContactSystem& s) {
  return s.num_contacts() > kRedundantContactsPerDof * s.num_dofs();
}

// Depth beyond the slop (m) below which the post-stabilization leaves an overlap alone. A
// projection leaves its contacts at exactly −slop, and a contact solve keeps them there to
// its tolerance, so a pile at rest has overlaps of slop plus roundoff (4e-16 m on a 200-body pile):
// without this margin each of its steps ran every projection pass (5 by default) to move
// bodies by roundoff, 5 Delassus products and cold Lemke solves per step (200-body LCP pile
// at rest). A millionth of the slop is far above that roundoff and far below any overlap
// a projection is meant to remove; with slop 0 every overlap is projected, as asked.
double projection_tolerance(double slop) { return 1e-6 * slop; }

// Drops the entries of a per-island map (keyed by the island's smallest body) whose island
// is gone; `islands` come in increasing order of their smallest body (find_islands).
template <class Map>
void drop_gone_islands(Map& per_island, const std::vector<Island>& islands) {
  auto island = islands.begin();
  for (auto it = per_island.begin(); it != per_island.end();) {
    while (island != islands.end() && island->bodies.front() < it->first) ++island;
    const bool used = island != islands.end() && island->bodies.front() == it->first;
    it = used ? std::next(it) : per_island.erase(it);
  }
}

struct IslandWork {
  ContactSystem system;
  ContactSolution solution;
  bool warm_started = false;
  std::string error;  // exception text, if any
};

}  // namespace

SimulatorSettings::SimulatorSettings() { qp.eps_abs = 1e-8; }

ContactModel parse_contact_model(std::string_view text) {
  for (ContactModel m : {ContactModel::lcp, ContactModel::convex})
    if (text == to_string(m)) return m;
  throw InputError("unknown contact model '" + std::string(text) + "' (expected lcp or convex)");
}

std::string SimulatorSettings::validation_error() const {
  if (!std::isfinite(dt) || !(dt > 0.0)) return "dt: must be finite and > 0";
  if (!std::isfinite(margin) || !(margin >= 0.0)) return "margin: must be finite and >= 0";
  if (model != ContactModel::lcp && model != ContactModel::convex) return "model: unknown contact model";
  if (!(penetration_slop >= 0)) return "penetration_slop: must be >= 0";
  if (post_stabilization_passes < 1) return "post_stabilization_passes: must be >= 1";
  if (!(convex_rho >= 0) || !std::isfinite(convex_rho)) return "convex_rho: must be finite and >= 0";
  if (std::string e = convex_softening.validation_error(); !e.empty()) return "convex_softening." + e;
  if (convex_formulation != ConvexFormulation::automatic && convex_formulation != ConvexFormulation::dual &&
      convex_formulation != ConvexFormulation::lifted)
    return "convex_formulation: unknown formulation";
  if (std::string e = lemke.validation_error(); !e.empty()) return "lemke." + e;
  if (std::string e = qp.validation_error(); !e.empty()) return "qp." + e;
  return {};
}

Simulator::Simulator(World world, SimulatorSettings settings) : world_(std::move(world)), settings_(std::move(settings)) {
  if (std::string e = settings_.validation_error(); !e.empty()) throw InputError("SimulatorSettings: " + e);
  for (std::size_t i = 0; i < world_.bodies.size(); ++i) {
    const RigidBody& b = world_.bodies[i];
    if (!b.is_static && (!(b.mass > 0) || !(b.inertia > 0)))
      throw InputError("bodies[" + std::to_string(i) + "]: mass and inertia must be > 0");
    if (!b.pose.allFinite() || !b.velocity.allFinite())
      throw InputError("bodies[" + std::to_string(i) + "]: pose and velocity must be finite");
    if (!std::isfinite(b.gap_offset) || !b.velocity_residual.allFinite())
      throw InputError("bodies[" + std::to_string(i) + "]: gap_offset and velocity_residual must be finite");
  }
  if (!world_.lcp_block.M.allFinite() || !world_.lcp_block.q.allFinite())
    throw InputError("lcp_block: the per-contact LCP correction must be finite");
  if (world_.lcp_block.enabled && settings_.model != ContactModel::lcp)
    throw InputError("lcp_block: the per-contact LCP correction applies to the lcp contact model only");
  const FrictionTable& ft = world_.friction;
  auto check_softness = [](double c, double e, const std::string& where) {
    if (const std::string error = normal_softness_value_error(c, e); !error.empty()) throw InputError(where + error);
  };
  check_softness(ft.default_compliance, ft.default_erp, "friction.");
  for (std::size_t i = 0; i < ft.pairs.size(); ++i)
    check_softness(ft.pairs[i].compliance, ft.pairs[i].erp, "friction.pairs[" + std::to_string(i) + "].");
  check_extreme_values();
}

// Values that are finite but overflow what a step derives from them (the speculative
// contact margin 2Δt·(|v| + |ω|·r), positions after a step) are blamed on the user's field,
// not on the derived one ("CollisionSettings: margin = inf" named no input).
void Simulator::check_extreme_values() const {
  if (!world_.gravity.allFinite() || world_.gravity.norm() > kMaxSceneMagnitude)
    throw InputError("gravity: |g| must be at most " + std::to_string(kMaxSceneMagnitude) + " m/s²");
  for (std::size_t i = 0; i < world_.bodies.size(); ++i) {
    const RigidBody& b = world_.bodies[i];
    const std::string name = "bodies[" + std::to_string(i) + "]";
    auto too_large = [&](const char* field, double value, const char* unit) {
      std::ostringstream os;
      os << name << "." << field << ": |" << value << "| exceeds " << kMaxSceneMagnitude << " " << unit;
      throw InputError(os.str());
    };
    if (b.pose.head<2>().cwiseAbs().maxCoeff() > kMaxSceneMagnitude)
      too_large("position", b.pose.head<2>().cwiseAbs().maxCoeff(), "m");
    if (std::abs(b.pose.z()) > kMaxSceneMagnitude) too_large("angle", b.pose.z(), "rad");
    if (b.velocity.head<2>().cwiseAbs().maxCoeff() > kMaxSceneMagnitude)
      too_large("velocity", b.velocity.head<2>().cwiseAbs().maxCoeff(), "m/s");
    if (std::abs(b.velocity.z()) > kMaxSceneMagnitude) too_large("angular_velocity", b.velocity.z(), "rad/s");
  }
  const double margin = speculative_contact_margin(world_, settings_);
  if (!std::isfinite(margin))
    throw InputError("bodies: velocities, gravity and dt = " + std::to_string(settings_.dt) +
                     " give a non-finite contact margin (a body moves too far in one step)");
}

std::vector<Simulator::ContactKey> Simulator::contact_keys() const {
  std::vector<ContactKey> keys(contacts_.size());
  for (std::size_t i = 0; i < contacts_.size(); ++i) keys[i] = contact_key(contacts_, i);
  return keys;
}

double Simulator::kinetic_energy() const {
  double e = 0.0;
  for (const RigidBody& b : world_.bodies)
    if (!b.is_static) e += 0.5 * (b.mass * b.velocity.head<2>().squaredNorm() + b.inertia * b.velocity(2) * b.velocity(2));
  return e;
}

double Simulator::potential_energy() const {
  double e = 0.0;
  for (const RigidBody& b : world_.bodies)
    if (!b.is_static) e -= b.mass * world_.gravity.dot(b.pose.head<2>());
  return e;
}

void Simulator::project_positions(const ContactSystem& s, const Vector& v_next, StepStats& stats) {
  const double dt = settings_.dt, slop = settings_.penetration_slop;
  const Index nc = s.num_contacts();
  if (nc == 0) return;
  const Vector phi_next = s.phi + dt * (s.Jn * v_next);
  if (phi_next.minCoeff() >= -(slop + projection_tolerance(slop))) return;
  const Vector bound = phi_next + Vector::Constant(nc, slop);  // Jn Δq + bound ≥ 0
  // Dual: the LCP 0 ≤ z ⊥ Wnn z + bound ≥ 0, Δq = M⁻¹Jnᵀz (exact, by Lemke), unless the
  // island is heavily redundant (redundant_island): then straight to the primal QP below.
  LcpResult r;
  if (!redundant_island(s)) {
    const SparseMatrix Wnn = detail::stacked_delassus(s.Jn, SparseMatrix(0, s.num_dofs()), s.minv, false);
    LemkeSettings plain = settings_.lemke;  // no retries: the interior point below is the fallback
    plain.covering_retries = 0;
    plain.regularization_retries = 0;
    LemkeSolver lemke(plain);
    lemke.setup(Wnn, bound);
    r = lemke.solve();
  }
  Vector dq;
  if (has_solution(r.info.status)) {
    dq = s.minv.cwiseProduct(s.Jn.transpose() * r.z);
  } else {
    // Primal, by the interior point: min ½ΔqᵀMΔq s.t. Jn Δq ≥ −bound. Strictly convex and
    // strictly feasible, so it is solved where Lemke fails on a singular Wnn (more
    // contacts than degrees of freedom, e.g. a pyramid whose boxes touch side to side).
    const Index nv = s.num_dofs();
    QpProblem p(nv);
    std::vector<Triplet> t;
    for (Index i = 0; i < nv; ++i) t.emplace_back(i, i, 1.0 / s.minv(i));
    p.P.resize(nv, nv);
    p.P.setFromTriplets(t.begin(), t.end());
    p.G = s.Jn;
    p.l = -bound;
    p.u = Vector::Constant(nc, std::numeric_limits<double>::infinity());
    QpSolver qp(settings_.qp);
    qp.setup(p);
    const QpResult& rq = qp.solve();
    if (!has_solution(rq.info.status)) {
      ++stats.failed_projections;  // positions stay as they are
      return;
    }
    dq = rq.x;
  }
  for (std::size_t k = 0; k < s.bodies.size(); ++k) world_.bodies[s.bodies[k]].pose += dq.segment<3>(3 * k);
  ++stats.projected_islands;
}

bool Simulator::project_overlaps(StepStats& stats) {
  const std::vector<Contact> overlaps = find_contacts(world_, CollisionSettings{0.0});
  double worst = 0.0;
  for (const Contact& c : overlaps) worst = std::max(worst, -c.gap);
  const double slop = settings_.penetration_slop;
  if (worst <= slop + projection_tolerance(slop)) return false;
  for (const Island& island : find_islands(world_, overlaps)) {
    const ContactSystem s = assemble_contact_system(world_, overlaps, island, settings_.dt, {});
    project_positions(s, Vector::Zero(s.num_dofs()), stats);  // φ itself: no velocity term
  }
  return true;
}

double speculative_contact_margin(const World& world, const SimulatorSettings& settings,
                                  const std::vector<Vec3>& applied) {
  // Speculative margin: contacts enter before they can close during this step, so fast
  // bodies do not pass the margin in one step and penetrate (the gap term φ/Δt then lets
  // them close exactly). Each body can move |v| + |ω|·r per unit time, with v and ω the
  // larger of the current and the free velocity v* = v + Δt·M⁻¹f (gravity and applied
  // forces act within the step: a body at rest falls g·Δt² in its first step, 9.8 cm at
  // Δt = 0.1 s, measured in tests/dynamics_penetration_test.cpp); two bodies twice.
  const double dt = settings.dt;
  double fastest = 0.0;
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const RigidBody& b = world.bodies[i];
    if (b.is_static) continue;
    double r = 0.0;
    for (const Vec2& p : b.shape.vertices) r = std::max(r, p.norm());
    Vec3 f(b.mass * world.gravity.x(), b.mass * world.gravity.y(), 0.0);
    if (!applied.empty()) f += applied[i];
    Vec3 free = b.velocity + dt * Vec3(f(0) / b.mass, f(1) / b.mass, f(2) / b.inertia);
    if (has_velocity_residual(b)) free += velocity_residual_term(b);
    for (const Vec3& v : {b.velocity, free}) fastest = std::max(fastest, v.head<2>().norm() + std::abs(v(2)) * r);
  }
  // Negative gap offsets (RigidBody::gap_offset) make contacts act before the shapes meet:
  // a pair of bodies up to twice the most negative offset earlier.
  double most_negative = 0.0;
  for (const RigidBody& b : world.bodies) most_negative = std::max(most_negative, -b.gap_offset);
  const double margin = settings.margin + 2.0 * fastest * dt;
  return most_negative > 0.0 ? margin + 2.0 * most_negative : margin;
}

StepContacts find_step_contacts(const World& world, const SimulatorSettings& settings,
                                const std::vector<Vec3>& applied) {
  if (!applied.empty() && applied.size() != world.bodies.size())
    throw InputError("applied forces need one (fx, fy, torque) per body (" + std::to_string(applied.size()) +
                     " given, " + std::to_string(world.bodies.size()) + " bodies)");
  StepContacts out;
  out.margin = speculative_contact_margin(world, settings, applied);
  out.contacts = find_contacts(world, CollisionSettings{out.margin});
  out.islands = find_islands(world, out.contacts);
  return out;
}

StepStats Simulator::step(const std::vector<Vec3>& applied) {
  World& world = world_;
  const double dt = settings_.dt;
  if (!applied.empty() && applied.size() != world.bodies.size())
    throw InputError("Simulator::step: applied forces need one (fx, fy, torque) per body");
  StepStats stats;
  auto t0 = std::chrono::steady_clock::now();
  StepContacts found = find_step_contacts(world, settings_, applied);
  contacts_ = std::move(found.contacts);
  stats.contacts = static_cast<int>(contacts_.size());
  for (const Contact& c : contacts_) stats.max_penetration = std::max(stats.max_penetration, -c.gap);
  const std::vector<Island>& islands = found.islands;
  const std::vector<ContactKey> keys = contact_keys();
  warm_.find_sorted(keys, previous_);  // each contact's warm-start entry, or nullptr
  stats.islands = static_cast<int>(islands.size());
  stats.collision_seconds = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  std::vector<IslandWork> work(islands.size());
  const bool lcp = settings_.model == ContactModel::lcp;
  const int n_islands = static_cast<int>(islands.size());
  // Convex model: each island's cached phase solvers (convex_solver_cache.hpp), matched by
  // the island's smallest body; caches of islands that are gone are dropped below.
  std::vector<ConvexSolverCache*> caches(islands.size(), nullptr);
  std::vector<ConvexSolverStats> before;  // counters at the start of the step
  if (!lcp && settings_.reuse_convex_solvers) {
    before.reserve(islands.size());
    for (int i = 0; i < n_islands; ++i) {
      caches[i] = &convex_caches_.try_emplace(islands[i].bodies.front(), settings_.qp).first->second;
      before.push_back(caches[i]->stats);
    }
  }
  // LCP model: each island's factorization of its warm basis, matched the same way (the
  // symbolic analysis is reused while the island's basis pattern repeats: at rest).
  // An island whose last answers were perturbed takes step 1b's perturbed answer as it is,
  // except where lcp_retry_exact says to run every attempt (contact_step.hpp).
  std::vector<LcpIslandMemory*> lcp_memory(islands.size(), nullptr);
  if (lcp && settings_.warm_start) {
    for (int i = 0; i < n_islands; ++i) lcp_memory[i] = &lcp_islands_[islands[i].bodies.front()];
    drop_gone_islands(lcp_islands_, islands);
  }
#ifdef LCPRELAX_HAS_OPENMP
  const int threads = settings_.threads > 0 ? settings_.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic) num_threads(threads)
#endif
  for (int i = 0; i < n_islands; ++i) {
    IslandWork& wk = work[i];
    try {
      wk.system = assemble_contact_system(world, contacts_, islands[i], dt, applied);
      const ContactSystem& s = wk.system;
      // The lcp model's fallbacks use the convex model, which has no LCP to correct: they take
      // the physical model (World::lcp_block off); the island counts as failed either way.
      std::optional<ContactSystem> stripped;  // made only when a fallback runs with the block on
      auto without_block = [&s, &stripped]() -> const ContactSystem& {
        if (!s.lcp_block.enabled) return s;
        if (!stripped) {
          stripped = s;
          stripped->lcp_block = ContactLcpBlock{};
        }
        return *stripped;
      };
      if (lcp && redundant_island(s)) {  // see kRedundantContactsPerDof: the convex model, reported
        wk.solution = solve_convex_model(without_block(), dt, settings_.qp, settings_.convex_rho, settings_.convex_formulation,
                                         settings_.convex_softening);
        const std::string why = std::to_string(s.num_contacts()) + " contacts on " + std::to_string(s.num_dofs()) +
                                " degrees of freedom (bodies inside each other?): too redundant for the LCP model; ";
        wk.solution.message = why + (has_solution(wk.solution.status) ? "convex model used"
                                                                      : "convex model: " + wk.solution.message);
        wk.solution.status = ContactStatus::failed;
      } else if (lcp) {
        const Index nc = s.num_contacts(), nf = s.num_friction();
        std::vector<bool> warm;
        if (settings_.warm_start) {
          Vector code = Vector::Zero(nc + nf);  // a contact not in warm_: nothing basic
          for (Index c = 0; c < nc; ++c) {
            if (const ContactWarmTable::Entry* e = previous_[static_cast<std::size_t>(s.contacts[c])]) code(c) = e->normal;
          }
          for (Index f = 0; f < nf; ++f) {
            if (const ContactWarmTable::Entry* e = previous_[static_cast<std::size_t>(s.contacts[s.friction_rows[f]])])
              code(nc + f) = e->friction;
          }
          decode_lcp_basis(code, nc, nf, warm);
        }
        // Step 1c first when any contact's entry came from a regularized answer or a failed
        // step (ContactWarmRecord::regularized): a part of the basis that is singular in M
        // leaves the whole basis singular in M, whichever islands merged since.
        bool warm_from_regularized = false;
        for (Index c = 0; c < nc && settings_.warm_start && !warm_from_regularized; ++c)
          if (const ContactWarmTable::Entry* e = previous_[static_cast<std::size_t>(s.contacts[c])])
            warm_from_regularized = e->regularized;
        const LcpIslandMemory* memory = lcp_memory[i];
        const bool accept_perturbed = memory && !lcp_retry_exact(memory->perturbed_steps);
        wk.solution = solve_lcp_model(s, dt, settings_.lemke, warm, memory ? memory->factorization : nullptr,
                                      accept_perturbed, warm_from_regularized);
      } else if (settings_.convex_solver == ConvexSolver::active_set_newton) {
        const Index nc = s.num_contacts(), nf = s.num_friction();
        std::vector<signed char> warm;
        if (settings_.warm_start) {
          warm.assign(static_cast<std::size_t>(nc + nf), 0);
          for (Index c = 0; c < nc; ++c) {
            const ContactWarmTable::Entry* e = previous_[static_cast<std::size_t>(s.contacts[c])];
            warm[c] = !e ? -1 : (e->normal > 0.5 ? 1 : 0);
          }
          for (Index f = 0; f < nf; ++f) {
            const ContactWarmTable::Entry* e = previous_[static_cast<std::size_t>(s.contacts[s.friction_rows[f]])];
            if (!e) continue;
            const int bits = friction_basis_bits(e->friction);
            warm[nc + f] = (bits & kBasisPlus) ? 1 : ((bits & kBasisMinus) ? -1 : 0);
          }
        }
        wk.solution = solve_convex_model_newton(s, dt, settings_.qp, settings_.convex_rho, settings_.convex_formulation,
                                                settings_.convex_softening, caches[i], warm, -1,
                                                settings_.convex_release_open_contacts);
      } else {
        wk.solution = solve_convex_model(s, dt, settings_.qp, settings_.convex_rho, settings_.convex_formulation,
                                         settings_.convex_softening, caches[i], settings_.convex_release_open_contacts);
      }
      // A fallback's answer is used, but the island still counts as failed.
      if (!has_solution(wk.solution.status) && lcp && !redundant_island(s)) {  // fallback: the convex model
        ContactSolution fallback = solve_convex_model(without_block(), dt, settings_.qp, settings_.convex_rho,
                                                      settings_.convex_formulation, settings_.convex_softening);
        fallback.message = wk.solution.message + (has_solution(fallback.status) ? "; convex model used"
                                                                                : "; convex fallback: " + fallback.message);
        fallback.residual = std::max(fallback.residual, wk.solution.residual);
        wk.solution = std::move(fallback);
        wk.solution.status = ContactStatus::failed;
      }
      if (!has_solution(wk.solution.status) && !lcp && s.num_contacts() <= kConvexFallbackMaxContacts &&
          !redundant_island(s)) {
        // fallback: the Stewart–Trinkle LCP (Lemke, cold), kept only if Lemke solves it
        ContactSolution fallback = solve_lcp_model(s, dt, settings_.lemke, {});
        if (has_solution(fallback.status)) {
          fallback.message = wk.solution.message + "; lcp model used";
          fallback.residual = std::max(fallback.residual, wk.solution.residual);
          fallback.work += wk.solution.work;
          fallback.z_basic.clear();
          wk.solution = std::move(fallback);
          wk.solution.status = ContactStatus::failed;
        }
      }
      // Last resort: a failed convex solve's frictionless phase-1 velocities, else v*.
      if (!has_solution(wk.solution.status) && wk.solution.v_next.size() != s.num_dofs()) wk.solution.v_next = s.v_star;
    } catch (const std::exception& e) {
      wk.error = e.what();
      if (caches[i]) *caches[i] = ConvexSolverCache(settings_.qp);  // no half-set-up solver kept
    }
  }
  for (const IslandWork& wk : work)
    if (!wk.error.empty()) throw std::runtime_error("contact solve failed: " + wk.error);

  // Velocities: islands from their solutions, free bodies by gravity and applied forces.
  std::vector<bool> in_island(world.bodies.size(), false);
  next_warm_.clear();
  Vector code;
  // Each contact's codes (NaN: none), written to the table below in contact order, which is
  // key order (find_contacts' canonical order): then finish() need not sort.
  const double none = std::numeric_limits<double>::quiet_NaN();
  warm_normal_.assign(contacts_.size(), none);
  warm_friction_.assign(contacts_.size(), none);
  warm_regularized_.assign(contacts_.size(), 0);
  for (std::size_t i = 0; i < work.size(); ++i) {
    const ContactSystem& s = work[i].system;
    const ContactSolution& sol = work[i].solution;
    for (std::size_t k = 0; k < s.bodies.size(); ++k) {
      in_island[s.bodies[k]] = true;
      world.bodies[s.bodies[k]].velocity = sol.v_next.segment<3>(3 * k);
    }
    stats.work += sol.work;
    stats.max_residual = std::max(stats.max_residual, sol.residual);
    stats.largest_island_unknowns = std::max<int>(stats.largest_island_unknowns,
                                                  static_cast<int>(s.num_contacts() + (lcp ? 3 : 1) * s.num_friction()));
    if (sol.warm_started) ++stats.warm_started_islands;
    switch (sol.status) {
      case ContactStatus::solved: ++stats.solved_islands; break;
      case ContactStatus::solved_inaccurate:
        if (++stats.inaccurate_islands == 1) stats.first_inaccurate = sol.message;
        break;
      default:
        if (++stats.failed_islands == 1) stats.first_failure = sol.message;
    }
    const Index nc = s.num_contacts(), nf = s.num_friction();
    if (sol.newton_fallback) ++stats.newton_fallbacks;
    if (lcp_memory[i]) {  // inexact or failed: the next step may take an inexact answer
      const bool failed = sol.status == ContactStatus::failed;
      lcp_memory[i]->perturbed_steps = sol.perturbed || sol.regularized || failed ? lcp_memory[i]->perturbed_steps + 1 : 0;
    }
    const char regularized = lcp && (sol.regularized || sol.status == ContactStatus::failed);
    for (Index c = 0; c < nc; ++c) warm_regularized_[static_cast<std::size_t>(s.contacts[c])] = regularized;
    // The LCP's final basis, or the convex active-set method's final active states.
    if (static_cast<Index>(sol.z_basic.size()) == nc + 3 * nf) {
      encode_lcp_basis(sol.z_basic, nc, nf, code);
      for (Index c = 0; c < nc; ++c) warm_normal_[static_cast<std::size_t>(s.contacts[c])] = code(c);
      for (Index f = 0; f < nf; ++f) warm_friction_[static_cast<std::size_t>(s.contacts[s.friction_rows[f]])] = code(nc + f);
    } else if (sol.status == ContactStatus::failed) {
      // A failed island has no basis of its own: its contacts keep the entries this step
      // started from, so that the next step starts warm from the last basis that solved
      // rather than cold (a cold Lemke path on a 1,000-body pile's island runs past every
      // cap, and then the step after it fails the same way).
      for (Index c = 0; c < nc; ++c)
        if (const ContactWarmTable::Entry* e = previous_[static_cast<std::size_t>(s.contacts[c])])
          warm_normal_[static_cast<std::size_t>(s.contacts[c])] = e->normal;
      for (Index f = 0; f < nf; ++f) {
        const std::size_t c = static_cast<std::size_t>(s.contacts[s.friction_rows[f]]);
        if (const ContactWarmTable::Entry* e = previous_[c]) warm_friction_[c] = e->friction;
      }
    }
  }
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    if (!std::isnan(warm_normal_[c])) next_warm_.set_normal(keys[c], warm_normal_[c]);
    if (!std::isnan(warm_friction_[c])) next_warm_.set_friction(keys[c], warm_friction_[c]);
    if (warm_regularized_[c] && !std::isnan(warm_normal_[c])) next_warm_.set_regularized(keys[c], true);
  }
  next_warm_.finish();
  warm_.swap(next_warm_);
  if (!lcp && settings_.reuse_convex_solvers) {
    for (int i = 0; i < n_islands; ++i) {
      const ConvexSolverStats& c = caches[i]->stats;
      stats.solver_setups += c.setups - before[i].setups;
      stats.solver_updates += c.updates - before[i].updates;
      stats.qp_assemble_seconds += c.assemble_seconds - before[i].assemble_seconds;
      stats.qp_prepare_seconds += c.prepare_seconds - before[i].prepare_seconds;
      stats.qp_solve_seconds += c.solve_seconds - before[i].solve_seconds;
      stats.qp_factor_seconds += c.factor_seconds - before[i].factor_seconds;
    }
    drop_gone_islands(convex_caches_, islands);
  }
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    RigidBody& body = world.bodies[b];
    if (body.is_static || in_island[b]) continue;
    Vec3 f(body.mass * world.gravity.x(), body.mass * world.gravity.y(), 0.0);
    if (!applied.empty()) f += applied[b];
    const bool residual = has_velocity_residual(body);
    const Vec3 r = residual ? velocity_residual_term(body) : Vec3::Zero();  // at the step's start velocity
    body.velocity += dt * Vec3(f(0) / body.mass, f(1) / body.mass, f(2) / body.inertia);
    if (residual) body.velocity += r;  // v* = v + Δt M⁻¹f + W f, as assemble_contact_system
  }
  for (RigidBody& body : world.bodies)
    if (!body.is_static) body.pose += dt * body.velocity;
  if (settings_.post_stabilization) {
    for (const IslandWork& wk : work) project_positions(wk.system, wk.solution.v_next, stats);
    for (int pass = 1; pass < settings_.post_stabilization_passes; ++pass)
      if (!project_overlaps(stats)) break;
  }
  stats.solve_seconds = seconds_since(t0);
  time_ += dt;
  ++steps_;
  return stats;
}

}  // namespace lcprelax
