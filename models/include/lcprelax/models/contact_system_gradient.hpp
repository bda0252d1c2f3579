#pragma once
// Reverse-mode derivatives of an island's ContactSystem (contact_system.hpp) with respect to
// the world's physical primitives: the adjoint input and output of learning on scenes.
//
// A scalar function ℓ of one island's data (a learning loss) hands its partial derivatives
// ∂ℓ/∂(Jn, Jt, φ, μ, M⁻¹, v*) as a ContactSystemCotangent; accumulate_world_gradient()
// pulls them back to ∂ℓ/∂(world primitives): every body's body-frame vertices, mass and
// inertia, every half-plane's normal and offset, every segment's end points, and every
// contact's μ, normal compliance and erp. Each contact row depends only on the two shapes that touch, so the pullback
// costs O(contacts + bodies) and never forms a dense Jacobian with one column per parameter.
//
// Conventions (contact_system.hpp, world.hpp): Jn, Jt rows (1, 1, m) per body block; φ (m);
// M⁻¹ = (1/m, 1/m, 1/I) per body; v* = v + Δt (g + u_xy/m, u_τ/I) with u the applied
// generalized force (N, N·m). The contacts (which features of which shapes touch) are held
// fixed while differentiating: a contact appearing or disappearing is a kink the derivative
// ignores. Each contact's point p, normal n and gap φ are recomputed from its recorded
// feature (Contact::Feature; contact/contact_features.hpp gives the formulas) as functions
// of the body-frame vertices of both shapes (world vertex x + R(θ) v; poses and velocities
// are state, not parameters) and of the static shape's parameters, and differentiated by
// forward-mode automatic differentiation (Eigen's AutoDiffScalar) over those local
// primitives, then the rows (n, r × n) and (t, r × t), r = p − x_body, t = (−n_y, n_x).
// M⁻¹ gives ∂/∂m = −(ct_x + ct_y)/m², ∂/∂I = −ct_ω/I²; v* gives ∂/∂m = −Δt ct·u_xy/m²,
// ∂/∂I = −Δt ct_ω u_τ/I² (v + Δt g does not depend on m). The nonphysical terms
// (contact_system.hpp): φ_c = gap_c + gap_offset_a + gap_offset_b gives ∂/∂gap_offset of a
// body = Σ ct_φ over its contacts; v* += W f gives ∂/∂W = ct_v* fᵀ (f = (vx, vy, ω, 1)),
// for every body of the island whether its W is zero or not. The lcp model's per-contact
// block (World::lcp_block) is data of the LCP, not of the system: its cotangent is passed
// through (g.lcp_block_* += ct.lcp_block_*; the tangent's lcp_block holds the direction's).
//
// Half-plane normals: the derivative is with respect to the normal's two components taken
// as free (the contact formulas use the normal as given, without normalizing), offset
// separate. For a parametrization of a unit normal, e.g. n = (−sin α, cos α), chain with
// ∂n/∂α; only the component tangent to the unit circle has a meaning for a world (whose
// half-plane normals are unit). Vertices are free too: mass and inertia are their own
// parameters, not functions of the vertices, and the centroid is not re-centred.
//
// Verified against central finite differences of ⟨ct, data⟩ with the features held fixed
// (refresh_contacts + assemble_contact_system), tests/contact_system_gradient_test.cpp.
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/sparse/types.hpp>
#include <lcprelax/world/world.hpp>

#include <array>
#include <vector>

namespace lcprelax {

/// ∂ℓ/∂(data) of a scalar ℓ of one island's ContactSystem, in the system's local indexing.
struct ContactSystemCotangent {
  SparseMatrix Jn;  ///< ∂ℓ/∂Jn, Jn's shape; only entries on Jn's sparsity pattern are used
  SparseMatrix Jt;  ///< ∂ℓ/∂Jt, Jt's shape; only entries on Jt's sparsity pattern are used
  Vector phi;       ///< ∂ℓ/∂φ per contact (1/m · unit of ℓ)
  Vector mu;        ///< ∂ℓ/∂μ per friction row
  Vector compliance;  ///< ∂ℓ/∂c per contact (normal compliance, kg · unit of ℓ)
  Vector erp;         ///< ∂ℓ/∂e per contact (normal erp)
  Vector minv;      ///< ∂ℓ/∂M⁻¹ per dof
  Vector v_star;    ///< ∂ℓ/∂v* per dof
  /// ∂ℓ/∂(ContactLcpBlock M, q) (world.hpp), zero unless the loss uses the lcp model's LCP
  Mat44 lcp_block_M = Mat44::Zero();
  Vec4 lcp_block_q = Vec4::Zero();

  /// Zero values with the shapes of `s` (Jn, Jt: s's sparsity patterns, zero values).
  void set_zero(const ContactSystem& s);
};

/// ∂ℓ/∂(world primitives), accumulated (+=) over islands.
struct WorldGradient {
  struct Body {
    std::vector<Vec2> vertices;  ///< per body-frame vertex (m⁻¹·unit of ℓ)
    double mass = 0.0;           ///< per kg
    double inertia = 0.0;        ///< per kg·m²
    double gap_offset = 0.0;     ///< per m of RigidBody::gap_offset
    Mat34 velocity_residual = Mat34::Zero();  ///< per unit of each RigidBody::velocity_residual entry
  };
  std::vector<Body> bodies;               ///< per world body (static bodies: vertices and gap_offset only)
  std::vector<Vec2> half_plane_normal;    ///< per half-plane: ∂ℓ/∂normal (the unit normal's components held free)
  std::vector<double> half_plane_offset;  ///< per half-plane
  std::vector<std::array<Vec2, 2>> segment_ends;  ///< per segment: ∂ℓ/∂a, ∂ℓ/∂b
  std::vector<double> contact_mu;         ///< per world contact (index into the contact list)
  std::vector<double> contact_compliance;  ///< ∂ℓ/∂c per world contact (FrictionTable's normal compliance)
  std::vector<double> contact_erp;         ///< ∂ℓ/∂e per world contact
  /// ∂ℓ/∂World::lcp_block (M, q), summed over islands
  Mat44 lcp_block_M = Mat44::Zero();
  Vec4 lcp_block_q = Vec4::Zero();

  /// Zero with the shapes of `world` and `num_contacts` contacts.
  void set_zero(const World& world, std::size_t num_contacts);
};

/// Adds ∂ℓ/∂(world primitives) of one island to g, for the island's system `s` assembled by
/// assemble_contact_system(world, contacts, island, dt, applied) and the cotangent `ct` of
/// ℓ at s. Every contact of the island must carry a recorded feature (find_contacts fills
/// them). Throws InputError when ct's or g's shapes do not match s, the world or the
/// contact list (set_zero gives the right ones), when a contact's feature cannot be
/// evaluated (contact_feature_error), or when dt is not finite and > 0.
void accumulate_world_gradient(const World& world, const std::vector<Contact>& contacts, const ContactSystem& s,
                               double dt, const std::vector<Vec3>& applied, const ContactSystemCotangent& ct,
                               WorldGradient& g);

/// Forward mode (for tests, and for tangents along a few parameter directions): the
/// directional derivative of s's data along `direction`, a WorldGradient read as a tangent
/// of the primitives (same shapes, same meaning per entry). Returned as a ContactSystem with
/// s's index fields whose Jn, Jt (on s's patterns), φ, μ, compliance, erp, M⁻¹ and v* hold
/// d(data)/dε.
/// ⟨ct, contact_system_tangent(…, dir)⟩ = ⟨accumulate_world_gradient(…, ct), dir⟩.
/// Throws InputError as accumulate_world_gradient does.
ContactSystem contact_system_tangent(const World& world, const std::vector<Contact>& contacts, const ContactSystem& s,
                                     double dt, const std::vector<Vec3>& applied, const WorldGradient& direction);

}  // namespace lcprelax
