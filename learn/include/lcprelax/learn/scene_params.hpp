#pragma once
// The learnable parameters θ of a multi-body scene and their map onto the World: which
// body, material pair and static shape each parameter sets, and the pullback of a
// WorldGradient (models/contact_system_gradient.hpp) to ∂ℓ/∂θ.
//
// Parameter layout (names in quotes; units SI; transforms of parameters.hpp):
//   "mu" (log)                       the friction table's default μ; with per-pair friction
//                                    also "mu[a,b]" (log) per listed material pair (a ≤ b);
//                                    without it every pair takes "mu" (one global μ)
//   per shape class c (bodies with identical shape, mass, inertia, gap offset and velocity
//   residual; scene_shape_classes):
//   "class<c>.mass" (log, kg), "class<c>.inertia" (log, kg·m²),
//   "class<c>.vertex<i>.x", "class<c>.vertex<i>.y" (identity, m, body frame)
//   per half-plane h: "half_plane<h>.angle" (identity, rad: outward normal (cos ψ, sin ψ);
//                     the floor y ≥ 0 has ψ = π/2), "half_plane<h>.offset" (identity, m)
//   per segment s: "segment<s>.a.x", "segment<s>.a.y", "segment<s>.b.x", "segment<s>.b.y" (m)
//   structured nonphysical terms, in the layout only when learned (flags gap, residual),
//   after the segments, so that a run without them keeps its layout and random draws:
//   per class c "class<c>.gap" (identity, m): RigidBody::gap_offset of the class's bodies,
//   added to the gap φ of each of their contacts (a contact of classes a and b gets
//   gap_a + gap_b; > 0 lets bodies sink in); then per class c the 12 entries
//   "class<c>.residual<r><j>" (identity; r = 0, 1, 2 the row vx, vy, ω; j = 0..3 the
//   feature vx, vy, ω, 1): W of v* += W (vx, vy, ω, 1) (RigidBody::velocity_residual, units
//   there). Held, they are not in θ and every body keeps the world's values.
//   Last, the elementwise per-contact correction of the lcp model's LCP (World::lcp_block,
//   world.hpp; the hard loss only: the relaxed and convex losses refuse it), one for the
//   whole scene, identity transforms, units of world.hpp, truth 0:
//   flag block      (20) "lcp_block.M<k><l>" (k, l = 0..3: λn, β⁺, β⁻, γ) and
//                        "lcp_block.q<k>": B and d entry by entry, nothing imposed;
//   flag block_tied  (7) "lcp_block.Wnn", "lcp_block.Wnt", "lcp_block.Wtn", "lcp_block.Wtt"
//                        (a 2×2 correction ΔW of the contact's Delassus block, entered in B
//                        with the LCP's signs: β⁻'s row and column are −β⁺'s), "lcp_block.mu"
//                        (B₃₀, the cone row's μ), "lcp_block.qn", "lcp_block.qt"
//                        (d = (qn, qt, −qt, 0)): the friction rows' antisymmetry imposed.
//   apply() enables the world's correction when either flag is set; parameters() reads each
//   entry's value from the world (the first entry a tied parameter sets).
//   Last, flag softness (every SceneObjective loss; the relaxed-dual step loss refuses it):
//   the normal softness of the friction table (world.hpp FrictionTable),
//   "compliance" (identity, ≥ 0, 1/kg, scale the classes' mean 1/m) and "erp" (identity, in
//   [0, 1]) for the table's default, then per material pair with its own μ (mu_per_pair)
//   "compliance[a,b]", "erp[a,b]"; the rigid model is 0 for both.
// Flags choose which kinds are learned (Parameter::learn); held parameters keep their
// values. Static bodies have no class (they are static geometry held at their values).
//
// The body frame is FIXED while vertices are learned (as for the polygon, polygon_params.hpp):
// its origin stays the point whose pose the state holds and about which the inertia is
// taken; a learned vertex moves only itself, the polygon is not recentred. Mass and inertia
// are independent parameters (not derived from a density).
#include <lcprelax/learn/parameters.hpp>
#include <lcprelax/models/contact_system_gradient.hpp>
#include <lcprelax/world/world.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace lcprelax::learn {

/// Which parameter kinds are learned.
struct SceneLearnFlags {
  bool mu = true, mass = true, inertia = true, vertices = true, ground = false;
  bool gap = false, residual = false;  ///< class<c>.gap, class<c>.residual<r><j>
  bool block = false, block_tied = false;  ///< World::lcp_block, free or tied (at most one of the two)
  bool softness = false;  ///< the friction table's normal compliance and erp (per pair with mu_per_pair)
};

/// Parses a comma-separated list of "mu", "mass", "inertia", "vertices", "ground", "gap",
/// "residual", "block", "block_tied", "softness" (each at most once, at least one, not both block
/// forms); throws InputError("--learn: ...") naming an unknown entry.
SceneLearnFlags parse_scene_learn_flags(const std::string& list);

struct SceneParameterSettings {
  SceneLearnFlags learn;
  bool mu_per_pair = false;  ///< one μ (and softness) per listed material pair, else one global value
};

/// Shape class of every body: dynamic bodies with identical vertices, mass, inertia, gap_offset
/// and velocity_residual (world.hpp; 0 unless a scene sets them) share
/// a class, numbered 0, 1, … in order of first appearance; static bodies get −1.
std::vector<int> scene_shape_classes(const World& world);

/// The map from θ to a World: built once for a scene, then apply() sets a world's
/// parameters from θ and gradient() pulls ∂ℓ/∂(world primitives) back to ∂ℓ/∂θ.
class SceneParameterMap {
 public:
  /// θ's layout for `world` (its current values are θ's initial values). Throws InputError
  /// when the world has no dynamic body or when bodies of one class differ in vertex count.
  SceneParameterMap(const World& world, const SceneParameterSettings& settings);

  /// The parameters at the values of `world` (same layout for any world of the scene).
  ParameterSet parameters(const World& world) const;
  /// Sets the world's parameters from θ (bodies by class, friction table, static shapes).
  void apply(const ParameterSet& theta, World& world) const;
  /// ∂ℓ/∂θ (θ's order) from ∂ℓ/∂(world primitives) of `world`'s `contacts` (the contact
  /// list the WorldGradient's contact_mu refers to).
  Vector gradient(const World& world, const std::vector<Contact>& contacts, const WorldGradient& g) const;

  Index size() const { return size_; }
  /// Whether θ holds World::lcp_block's entries (flag block or block_tied).
  bool learns_lcp_block() const { return settings_.learn.block || settings_.learn.block_tied; }
  /// Whether θ holds the friction table's normal compliance and erp (flag softness).
  bool learns_softness() const { return settings_.learn.softness; }
  const std::vector<int>& body_class() const { return body_class_; }
  int num_classes() const { return static_cast<int>(class_vertices_.size()); }

  enum class Kind { mu, mass, inertia, vertex, angle, offset, segment_end, gap, residual, lcp_block, compliance, erp };
  Kind kind(Index k) const { return kind_[static_cast<std::size_t>(k)]; }
  /// Length scale of parameter k (m), also its Parameter::scale (ξ = θ/scale): its class's radius for vertices and
  /// gaps, the mean class radius for offsets and segment ends, 1 otherwise (residual entries included).
  double length_scale(Index k) const { return scale_[static_cast<std::size_t>(k)]; }

 private:
  Index mu_index(const World& world, int material_a, int material_b) const;
  static int material_of_b(const World& world, const Contact& c);

  SceneParameterSettings settings_;
  std::vector<int> body_class_;       ///< per body, −1 static
  std::vector<int> class_vertices_;   ///< vertex count per class
  std::vector<Index> class_first_;    ///< index of "class<c>.mass"
  std::vector<std::pair<int, int>> pairs_;  ///< material pairs with their own μ (per-pair mode)
  Index first_half_plane_ = 0, first_segment_ = 0;
  Index first_gap_ = 0, first_residual_ = 0;  ///< end of the segments; end of the gaps
  Index first_block_ = 0;                     ///< end of the residual entries
  Index first_softness_ = 0;                  ///< end of the lcp_block entries
  Index size_ = 0;
  std::vector<Kind> kind_;
  std::vector<double> scale_;
};

/// Deterministic perturbation of θ for initial values: log parameters (μ, mass, inertia)
/// scaled by (1 ± fraction), vertex coordinates moved by ±fraction·0.5·(class radius),
/// half-plane offsets and segment ends by ±fraction·0.5·(mean class radius), angles by
/// ±0.1·fraction rad, gaps by ±fraction·0.5·(class radius), residual entries by ±0.1·fraction
/// (in their own units); lcp_block, compliance and erp entries are kept (their units differ entry by entry and a
/// fixed size can make the LCP unsolvable); random signs from std::mt19937_64(seed) in layout
/// order (a sign is drawn for every parameter); only learned parameters move.
ParameterSet perturb_scene_parameters(const ParameterSet& truth, const SceneParameterMap& map, double fraction,
                                      std::uint64_t seed);

/// Relative error of parameter k: |Δ|/|truth| for log parameters, |Δ|/(class radius) for
/// vertex coordinates and gaps, |Δ|/(mean class radius) for offsets and segment ends, |Δ| (rad) for
/// angles, |Δ| (the entry's units) for residual, lcp_block and erp entries, |Δ|/scale for compliance.
double scene_relative_error(const ParameterSet& estimate, const ParameterSet& truth, const SceneParameterMap& map,
                            Index k);

}  // namespace lcprelax::learn
