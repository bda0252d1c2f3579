#pragma once
// The learnable parameters θ of one convex polygon tumbling on a ground half-plane: the
// physical model and its ParameterSet (parameters.hpp).
//
// Model (SI units):
// - shape: body-frame vertices (m), counter-clockwise. The BODY FRAME IS FIXED: its origin is
//   the centre of mass by definition (the point whose (x, y) the state holds, about which
//   `inertia` is taken) and the vertices are positions relative to it. Vertices are never
//   recentred on their centroid while learning, so a vertex change moves only that vertex
//   and not the pose; mass and inertia are independent parameters (not derived from a
//   density), so a learned polygon need not be a uniform lamina.
// - mu: Coulomb friction coefficient polygon–ground (> 0); mass (kg, > 0); inertia about the
//   centre of mass (kg·m², > 0).
// - ground: the half-plane {p : n·p ≥ h cos α} with outward unit normal
//   n(α) = (−sin α, cos α): the ground line passes through (0, h) and rises at angle α
//   (rad, counter-clockwise from the +x axis); α = 0, h = 0 is the floor y ≥ 0.
//
// Parameter layout (fixed order, names in quotes), N = number of vertices:
//   0 "mu" (log), 1 "mass" (log), 2 "inertia" (log),
//   3 + 2i "vertex<i>.x", 4 + 2i "vertex<i>.y" (identity, m) for i = 0..N−1,
//   3 + 2N "ground_height" (identity, m), 4 + 2N "ground_angle" (identity, rad).
// Each kind can be learned or held (PolygonLearnFlags → Parameter::learn); held parameters
// keep their value (their gradient entries are still computed, chain_gradient zeroes them).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/parameters.hpp>
#include <lcprelax/learn/scene_params.hpp>
#include <lcprelax/world/world.hpp>

#include <cstdint>
#include <string>

namespace lcprelax::learn {

struct PolygonModel {
  Polygon shape;               ///< body frame, counter-clockwise (m); origin = centre of mass
  double mu = 0.5;             ///< friction coefficient, > 0
  double mass = 1.0;           ///< kg, > 0
  double inertia = 1.0;        ///< kg·m², > 0
  double ground_height = 0.0;  ///< h (m)
  double ground_angle = 0.0;   ///< α (rad), |α| < π/2

  /// Empty if valid, else a message naming the bad field (3..12 finite vertices, μ, mass,
  /// inertia > 0 and finite, finite ground, |α| < π/2).
  std::string validation_error() const;
};

/// The reference quadrilateral of `lcprelax learn polygon` (its ground truth), also used by
/// the polygon tests and benchmarks: vertices (−0.30, −0.22), (0.34, −0.18), (0.26, 0.24),
/// (−0.22, 0.20) m recentred on their centroid, μ = 0.4, mass 1.5 kg, inertia 0.06 kg·m²,
/// ground y = 0 (h = 0, α = 0).
PolygonModel reference_polygon_model();

/// The ground half-plane of the model: normal (−sin α, cos α), offset h cos α.
HalfPlane ground_half_plane(double height, double angle);

/// Which parameter kinds are learned: the same kinds as a scene's (scene_params.hpp).
using PolygonLearnFlags = SceneLearnFlags;

/// parse_scene_learn_flags (scene_params.hpp), without "gap", "residual", "block",
/// "block_tied" and "softness" (scene learning only): InputError("--learn: ...") for them.
inline PolygonLearnFlags parse_polygon_learn_flags(const std::string& list) {
  const PolygonLearnFlags f = parse_scene_learn_flags(list);
  if (f.gap || f.residual || f.block || f.block_tied || f.softness)
    throw InputError("--learn: gap, residual, block, block_tied and softness are learned by `learn scene` only");
  return f;
}

/// Index arithmetic of the layout above.
struct PolygonLayout {
  static constexpr Index kMu = 0, kMass = 1, kInertia = 2, kFirstVertex = 3;
  Index vertices = 0;
  Index vertex_x(Index i) const { return kFirstVertex + 2 * i; }
  Index vertex_y(Index i) const { return kFirstVertex + 2 * i + 1; }
  Index ground_height() const { return kFirstVertex + 2 * vertices; }
  Index ground_angle() const { return kFirstVertex + 2 * vertices + 1; }
  Index size() const { return kFirstVertex + 2 * vertices + 2; }
};

/// θ for `model` with the learn flags; throws InputError if the model is invalid.
ParameterSet make_polygon_parameters(const PolygonModel& model, const PolygonLearnFlags& flags);

/// The model that θ describes (θ must have the layout of an N-vertex polygon, checked by
/// size and names; InputError otherwise).
PolygonModel polygon_model(const ParameterSet& theta);

/// Deterministic perturbation of a model for initial values: μ, mass and inertia are scaled
/// by (1 ± fraction) with a random sign each; every vertex coordinate moves by
/// ±fraction·0.5·radius (radius = largest vertex distance from the origin), ground height by
/// ±fraction·0.5·radius and angle by ±fraction·0.1 rad, only for kinds that `flags` learns.
/// std::mt19937_64 seeded with `seed`; signs drawn in layout order.
PolygonModel perturb_polygon_model(const PolygonModel& truth, const PolygonLearnFlags& flags, double fraction,
                                   std::uint64_t seed);

/// Relative error of parameter k of `estimate` against `truth` (same layout): |Δ|/|truth|
/// for μ, mass and inertia; |Δ|/radius(truth) for vertex coordinates and ground height (a
/// coordinate near 0 has no meaningful relative error); |Δ| in rad for the ground angle.
double polygon_relative_error(const ParameterSet& estimate, const ParameterSet& truth, Index k);

/// Largest vertex distance from the body origin (m).
double polygon_radius(const Polygon& shape);

}  // namespace lcprelax::learn
