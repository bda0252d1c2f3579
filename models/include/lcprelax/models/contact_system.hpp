#pragma once
// Islands of touching bodies and the sparse contact Jacobians of one island.
//
// Generalized velocity of an island: v = (vx, vy, ω) per dynamic body, in the order of
// ContactSystem::bodies (3 columns per body; static bodies have no columns). The mass
// matrix is diag(m, m, I) per body (vertices are centred on the centre of mass), so
// M⁻¹ is the vector minv.
//
// Rows: for contact c with point p, unit normal n (from b to a) and tangent
// t = (−n_y, n_x), the relative velocity of a with respect to b at p is
//     u = v_a + ω_a × (p − x_a) − v_b − ω_b × (p − x_b),   ω × r = ω (−r_y, r_x),
// so the normal row on body a is (n_x, n_y, r_a × n) with r × n = r_x n_y − r_y n_x, and
// the negated row (with r_b) on a dynamic body b; the tangent row likewise with t. Jn has
// one row per contact; Jt has one row per contact with μ > 0 only (no tangential
// unknowns where μ = 0). Impulses λ act as M Δv = Jnᵀ λn + Jtᵀ λt.
//
// Nonphysical terms (RigidBody::gap_offset, RigidBody::velocity_residual, world.hpp): the
// gap of contact c is φ = c.gap + gap_offset_a (+ gap_offset_b when b is a body), and v* of
// a body gets + W (vx, vy, ω, 1). Both are skipped where they are exactly 0, so a world
// without them assembles bit for bit as before. World::lcp_block is copied as it is (the
// lcp model's stewart_trinkle_lcp applies it). Each contact's normal softness (compliance c,
// erp e: FrictionTable, world.hpp) is copied per contact when some contact of the island has
// one (else both vectors stay empty = all zero, as a hand-made system may leave them);
// stewart_trinkle_lcp and the learning losses read the normal row as (Jn v⁺)ᵢ +
// normal_gap_rate(s, Δt)ᵢ + cᵢ λnᵢ.
#include <lcprelax/world/world.hpp>
#include <lcprelax/sparse/types.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace lcprelax {

/// Bodies and contacts that interact: connected through contacts between dynamic bodies
/// (contacts with static shapes or static bodies do not connect islands).
struct Island {
  std::vector<int> bodies;    ///< dynamic body indices, increasing
  std::vector<int> contacts;  ///< contact indices, increasing
};

/// Islands of the dynamic bodies that have at least one contact, in increasing order of
/// their smallest body index (deterministic).
std::vector<Island> find_islands(const World& world, const std::vector<Contact>& contacts);

/// One island's contact problem data.
struct ContactSystem {
  std::vector<int> bodies;    ///< global index of each 3-column block
  std::vector<int> contacts;  ///< global contact index of each Jn row
  std::vector<int> friction_rows;  ///< Jn row (local contact) of each Jt row
  Vector minv;                ///< 3·bodies: 1/m, 1/m, 1/I
  SparseMatrix Jn;            ///< contacts × 3·bodies
  SparseMatrix Jt;            ///< friction rows × 3·bodies
  Vector phi;                 ///< gap per contact (m)
  Vector mu;                  ///< μ per friction row
  Vector compliance;          ///< normal compliance c per contact (1/kg), or empty (all 0)
  Vector erp;                 ///< erp e per contact (in [0, 1]), or empty (all 0)
  Vector v_star;              ///< free velocity v + Δt M⁻¹ f (3·bodies)
  /// Identity of each contact across time steps (contact_identity of its contact_key), set
  /// by assemble_contact_system; empty: contact c is known by its index only. The lcp model
  /// keys its perturbation by it (contact_step.hpp, lcp_perturbation_pattern).
  std::vector<std::uint64_t> ids;
  ContactLcpBlock lcp_block;  ///< the world's per-contact LCP correction (world.hpp; lcp model only)

  Index num_contacts() const { return static_cast<Index>(contacts.size()); }
  Index num_friction() const { return static_cast<Index>(friction_rows.size()); }
  Index num_dofs() const { return static_cast<Index>(3 * bodies.size()); }
};

/// contacts[i]'s key: (body_a, body_b, static kind, static index, ordinal among the run of
/// consecutive contacts with those four), the same pair and feature pattern from step to
/// step while the collision order (contact/collision.hpp) keeps a pair's points together.
using ContactKey = std::array<int, 5>;
ContactKey contact_key(const std::vector<Contact>& contacts, std::size_t i);
/// A 64-bit hash (FNV-1a over the five fields) of a contact key.
std::uint64_t contact_identity(const ContactKey& key);

/// Assembles an island: Jacobians, gaps, μ, M⁻¹ and the free velocity v* = v + Δt·g
/// (gravity; applied generalized forces enter through `applied`, 3 per world body, N and
/// N·m, or empty).
ContactSystem assemble_contact_system(const World& world, const std::vector<Contact>& contacts,
                                      const Island& island, double dt, const std::vector<Vec3>& applied = {});

/// The residual's features of a body: f = (vx, vy, ω, 1) at its current velocity.
Eigen::Vector4d velocity_residual_features(const RigidBody& body);
/// Whether a body's velocity residual is nonzero (any entry ≠ 0).
bool has_velocity_residual(const RigidBody& body);
/// W f, the residual's share of the body's free velocity (m/s, m/s, rad/s).
Vec3 velocity_residual_term(const RigidBody& body);
/// The offset contact c's gap gets (m): body a's gap_offset, plus body b's when body_b ≥ 0.
double contact_gap_offset(const World& world, const Contact& c);

/// Whether any contact of s has a nonzero compliance or erp (FrictionTable, world.hpp).
bool has_normal_softness(const ContactSystem& s);
/// The normal rows' gap term (m/s): (max(φᵢ, 0) + eᵢ·min(φᵢ, 0))/Δt per contact (eᵢ = 0 when
/// s.erp is empty).
Vector normal_gap_rate(const ContactSystem& s, double dt);
/// Empty when s.compliance and s.erp are empty or one finite entry per contact with c ≥ 0
/// and e in [0, 1]; else a message naming the field.
std::string normal_softness_error(const ContactSystem& s);

/// W = J M⁻¹ Jᵀ for J = [Jn; Jt] (rows: contacts, then friction rows); compressed CSC,
/// sorted rows, exact zeros not stored (models/src/delassus.cpp). Throws InputError when
/// Jn, Jt or minv do not match the numbers of contacts, friction rows and 3·bodies.
SparseMatrix delassus(const ContactSystem& s);

}  // namespace lcprelax
