#pragma once
// The 2-D rigid-body world shared by collision, time stepping, scenes and learning.
//
// Conventions (SI units; docs/conventions.md):
// - A body's configuration is (x, y, θ): the world position of its centre of mass (m) and
//   its rotation angle (rad, counter-clockwise). Its velocity is (vx, vy, ω) (m/s, rad/s).
// - Polygon vertices are given in the body frame, counter-clockwise, with the centroid at
//   the origin (so that (x, y) is the centre of mass); 3 to 12 vertices, strictly convex.
// - A world point of a body: p = (x, y) + R(θ) v, R(θ) = [[cos θ, −sin θ], [sin θ, cos θ]].
// - Static shapes (half-planes, segments, static polygons) have no degrees of freedom.
// - Contact normals point from body b to body a: a positive normal impulse λn pushes a
//   along +normal and b along −normal. The gap φ is the signed distance along the normal
//   (m), negative when the shapes overlap.
#include <Eigen/Core>

#include <vector>

namespace lcprelax {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
/// 3×4, unaligned (a member of RigidBody, which lives in std::vector).
using Mat34 = Eigen::Matrix<double, 3, 4, Eigen::DontAlign>;
/// 4×4 and 4-vector, unaligned (members of structs that live in std::vector).
using Mat44 = Eigen::Matrix<double, 4, 4, Eigen::DontAlign>;
using Vec4 = Eigen::Matrix<double, 4, 1, Eigen::DontAlign>;

struct Polygon {
  std::vector<Vec2> vertices;  ///< body frame, counter-clockwise, centroid at the origin (m)
};

struct RigidBody {
  Polygon shape;
  double mass = 1.0;     ///< kg (> 0 unless is_static)
  double inertia = 1.0;  ///< kg·m² about the centre of mass (> 0 unless is_static)
  Vec3 pose = Vec3::Zero();      ///< (x, y, θ)
  Vec3 velocity = Vec3::Zero();  ///< (vx, vy, ω)
  int material = 0;              ///< index into the friction table
  bool is_static = false;        ///< static polygons never move and have no unknowns
  // Structured nonphysical terms (learned per shape class, learn/scene_params.hpp; both 0 by
  // default, and then nothing changes, bit for bit). They act where a step's contact problem
  // is assembled (models/contact_system.hpp), so the Simulator and learning agree.
  /// Gap offset (m), added to the gap φ of every contact row this body takes part in: a
  /// contact of bodies a and b gets φ + gap_offset_a + gap_offset_b (a static body's counts
  /// too; half-planes and segments have none). > 0 lets the body sink that far into what it
  /// touches, < 0 keeps it that far off. Contacts are still found on the geometric gap (the
  /// Simulator widens its margin by twice the most negative offset). Both contact models close
  /// gaps at velocity level by max(φ, 0)/Δt: a negative effective gap φ + offsets acts through
  /// the position projection (post-stabilization) and the convex model's softening only.
  double gap_offset = 0.0;
  /// Linear residual on the free velocity: v* += W f with f = (vx, vy, ω, 1) the body's
  /// velocity at the start of the step (a free-flying body's next velocity gets it too).
  /// Rows (vx, vy, ω); units: rows 0–1 m/s, row 2 rad/s per unit of f's entry (column 3:
  /// m/s, m/s, rad/s). Dynamic bodies only.
  Mat34 velocity_residual = Mat34::Zero();
};

/// Static half-plane: free space is {p : normal·p ≥ offset}, solid below it.
struct HalfPlane {
  Vec2 normal{0.0, 1.0};  ///< unit, pointing out of the solid into free space
  double offset = 0.0;    ///< m
  int material = 0;
};

/// Static two-sided segment of zero thickness (container walls, ledges).
struct Segment {
  Vec2 a{0.0, 0.0}, b{1.0, 0.0};  ///< end points (m)
  int material = 0;
};

/// The contact material table: per pair of materials the friction coefficient μ and the
/// normal row's softness (compliance c, erp e); the defaults where no pair is listed.
///
/// Softness (models/contact_step.hpp: stewart_trinkle_lcp, and the convex model): contact i's
/// normal row of the Stewart–Trinkle LCP becomes
///     w_n,i = (Jn v⁺)_i + (max(φ_i, 0) + e·min(φ_i, 0))/Δt + c·λn_i ≥ 0  ⊥  λn_i ≥ 0,
/// c in 1/kg (velocity per normal impulse, m/s per N·s), e dimensionless in [0, 1]. Where
/// the contact is active (w_n = 0) this is the implicit spring–damper of stiffness k (N/m)
/// and damping d (N·s/m) in constraint-force-mixing form (Smith, Open Dynamics Engine
/// manual, CFM/ERP; Catto, "Soft Constraints", GDC 2011): c = 1/(Δt(Δt·k + d)) and
/// e = Δt·k/(Δt·k + d), i.e. k = e/(c·Δt²), d = (1 − e)/(c·Δt). e is the fraction of an
/// overlap that the step's velocity removes (the position projection removes the rest);
/// a positive gap keeps the rigid term φ/Δt. The rigid model is c = 0, e = 0 (defaults).
/// The convex model takes them on top of its own normal softening (models/normal_softening.hpp
/// add_pair_softness: c on phase 2's λn diagonal, the push-out −e·min(φ, 0)/Δt in its target
/// velocity); the relaxed-dual loss refuses a nonzero c or e (InputError).
struct FrictionTable {
  double default_mu = 0.5;
  double default_compliance = 0.0;  ///< c (1/kg), ≥ 0
  double default_erp = 0.0;         ///< e, in [0, 1]
  struct Pair {
    int material_a = 0, material_b = 0;
    double mu = 0.5;
    double compliance = 0.0;  ///< c (1/kg), ≥ 0
    double erp = 0.0;         ///< e, in [0, 1]
  };
  std::vector<Pair> pairs;  ///< symmetric: (a, b) also applies to (b, a)

  /// The listed pair (a, b) or (b, a), else nullptr.
  const Pair* find(int material_a, int material_b) const {
    for (const Pair& p : pairs)
      if ((p.material_a == material_a && p.material_b == material_b) ||
          (p.material_a == material_b && p.material_b == material_a))
        return &p;
    return nullptr;
  }
  double mu(int material_a, int material_b) const {
    const Pair* p = find(material_a, material_b);
    return p ? p->mu : default_mu;
  }
  double compliance(int material_a, int material_b) const {
    const Pair* p = find(material_a, material_b);
    return p ? p->compliance : default_compliance;
  }
  double erp(int material_a, int material_b) const {
    const Pair* p = find(material_a, material_b);
    return p ? p->erp : default_erp;
  }
  /// Whether any entry (default or pair) has a nonzero compliance or erp.
  bool has_softness() const {
    if (default_compliance != 0.0 || default_erp != 0.0) return true;
    for (const Pair& p : pairs)
      if (p.compliance != 0.0 || p.erp != 0.0) return true;
    return false;
  }
};

/// A nonphysical, elementwise correction of the lcp contact model (models/contact_step.hpp,
/// stewart_trinkle_lcp): the same 4×4 block B and 4-vector d added to every contact's own
/// rows and columns of the Stewart–Trinkle LCP, in the order k = 0 λn (normal impulse),
/// 1 β⁺, 2 β⁻ (friction impulses along ±t), 3 γ (sliding speed):
///     M[idx_c, idx_c] += B,   q[idx_c] += d,
/// where idx_c are contact c's LCP indices (a contact without a friction row, μ = 0, takes
/// B₀₀ and d₀ only). Units follow the LCP's rows and columns: rows 0–2 are velocities (m/s)
/// and row 3 an impulse (N·s); columns 0–2 impulses (N·s) and column 3 a velocity, so
/// B_kl is in 1/kg for k, l ≤ 2, dimensionless for (k ≤ 2, l = 3) and (k = 3, l ≤ 2), kg for
/// (3, 3); d₀–d₂ in m/s, d₃ in N·s. The physical model is B = 0, d = 0. Learning it
/// (learn/scene_params.hpp, flags block and block_tied) asks how much structure a learned
/// contact model needs: with B and d free, the friction rows' antisymmetry (row β⁻ = −row β⁺
/// in the impulse columns, d₂ = −d₁) is no longer imposed and, as docs/structure.md derives,
/// a sticking contact slides at any ε < 0 in it. The convex model has no LCP: a world with
/// the correction enabled is refused there (InputError). When `enabled` is false nothing is
/// added (and the LCP's sparsity pattern is the physical one); when true all 16 entries are
/// stored, zeros included, so that every entry has a gradient.
struct ContactLcpBlock {
  bool enabled = false;
  Mat44 M = Mat44::Zero();
  Vec4 q = Vec4::Zero();
};

struct World {
  std::vector<RigidBody> bodies;
  std::vector<HalfPlane> half_planes;
  std::vector<Segment> segments;
  Vec2 gravity{0.0, -9.81};  ///< m/s²
  FrictionTable friction;
  ContactLcpBlock lcp_block;  ///< lcp model only; disabled (physical) by default

  /// Whether body index b names a moving body: b ≥ 0 (−1 is a static shape) and not static.
  bool is_dynamic(int b) const { return b >= 0 && !bodies[b].is_static; }
};

/// One contact point between a dynamic body a and a body b (dynamic, static, or a static
/// shape). Which static shape b is: body_b ≥ 0 is a body index (possibly a static body);
/// body_b = −1 with static_kind/static_index naming the half-plane or segment.
///
/// `feature` records which geometric features of the two shapes produced the point, so that
/// (point, normal, gap) can be recomputed from the shapes' vertices with the features held
/// fixed (contact/contact_features.hpp). Vertex and edge indices refer to the world-frame
/// vertex loops of shape a (the body's polygon) and shape b (a body's polygon, or a
/// segment's end points a = 0, b = 1 with edges 0: a→b and 1: b→a); edge e runs from
/// vertex e to vertex e + 1 (mod count), its outward normal n_e = (e_y, −e_x)/|e|.
struct Contact {
  enum class StaticKind { none, half_plane, segment };
  struct Feature {
    enum class Kind {
      none,             ///< not recorded (a contact made by hand): cannot be recomputed
      incident_vertex,  ///< vertex `vertex` of the incident shape, inside the reference slab
      clipped_edge,     ///< incident edge (vertex, vertex+1) ∩ the side line of the reference
                        ///< face through its vertex edge + side (t·p = t·r, t along the face)
      deepest_vertex,   ///< vertex `vertex` of the incident shape, below reference face `edge`
      closest,          ///< separated shapes: vertex `vertex` of the non-face shape and its
                        ///< closest point on edge `edge` of the face shape (side −1: interior,
                        ///< 0 / 1: the edge's start / end vertex); normal along their difference
      plane_vertex      ///< half-plane: vertex `vertex` of shape a
    };
    Kind kind = Kind::none;
    bool face_on_a = false;  ///< the edge `edge` is shape a's (else b's); the vertex is the other's
    int edge = -1;           ///< reference face, or the face shape's edge (closest)
    int vertex = -1;         ///< vertex / incident edge start on the other shape (plane: on a)
    int side = -1;           ///< clipped_edge: 0 or 1; closest: −1, 0 or 1; else −1
  };
  int body_a = -1;
  int body_b = -1;
  StaticKind static_kind = StaticKind::none;
  int static_index = -1;
  Vec2 point{0.0, 0.0};   ///< world point (m), midway between the two surfaces
  Vec2 normal{0.0, 1.0};  ///< unit, from b to a
  double gap = 0.0;       ///< φ (m), negative when overlapping
  double mu = 0.0;        ///< friction coefficient of the pair
  double compliance = 0.0;  ///< the pair's normal compliance c (1/kg; FrictionTable)
  double erp = 0.0;         ///< the pair's erp e (FrictionTable)
  Feature feature;        ///< what produced the point (filled by find_contacts)
};

}  // namespace lcprelax
