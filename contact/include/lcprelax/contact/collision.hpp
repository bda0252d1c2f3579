#pragma once
// Collision detection for a World: broad phase (broad_phase.hpp) + narrow phase
// (narrow_phase.hpp) → a deterministic list of contact points.
//
// Conventions (models/world.hpp): body_a is always a dynamic body; for two dynamic bodies
// it is the lower index; when b is a static body, a half-plane or a segment, a is the
// dynamic one. body_b = −1 with static_kind/static_index for half-planes and segments.
// normal: unit, from b to a; gap φ (m): signed distance along the normal, negative when
// overlapping; point: world, midway between the surfaces; mu from
// world.friction.mu(material_a, material_b). Contacts with φ ≤ margin are reported (near
// contacts enter before they touch); at most two per pair. feature: the features of the two
// shapes that produced the point (narrow_phase.hpp), from which refresh_contacts
// (contact_features.hpp) recomputes point, normal and gap at other shapes or poses.
//
// Order: sorted by (body_a, body_b, static_kind, static_index, point.x, point.y); the
// result depends only on the world, not on memory layout or timing.
//
// Preconditions: body polygons are valid (polygon_validation_error; checked here only for the
// vertex count and finiteness), static bodies are never paired with each other.
#include <lcprelax/world/world.hpp>

#include <string>
#include <vector>

namespace lcprelax {

struct CollisionSettings {
  double margin = 1e-2;  ///< m, ≥ 0: contacts with gap φ ≤ margin are reported

  /// Empty when valid, else a message naming the bad field.
  std::string validation_error() const;
};

/// All contacts of `world` with gap ≤ settings.margin, in the order above.
/// Throws InputError for invalid settings or world data (non-finite poses or vertices,
/// vertex counts outside 3..12, non-unit half-plane normals, degenerate segments).
std::vector<Contact> find_contacts(const World& world, const CollisionSettings& settings = {});

/// Strict weak order used by find_contacts.
bool contact_less(const Contact& l, const Contact& r);

}  // namespace lcprelax
