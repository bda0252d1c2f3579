#pragma once
// Broad phase: candidate pairs for the narrow phase from axis-aligned bounding boxes.
//
// Body–body: a uniform grid (spatial hashing by sorting; Ericson, "Real-Time Collision
// Detection", 2005, §7.1). The cell size is the median of the boxes' larger extents, so a
// typical box covers at most 2×2 cells; boxes covering more than kMaxGridCellsPerBox cells
// (walls, large static polygons) are kept out of the grid and tested against every other
// box. Each overlapping pair is reported once, from the cell that holds the lower corner
// of the two boxes' intersection. Cost O(n log n) for n similar boxes (the sort), plus
// O(n) per large box. Output sorted by (a, b), a < b, deterministic; pairs of two static
// bodies are never reported.
//
// Body–static shape: every dynamic body's box against every half-plane and segment
// (scenes have few of them): O(n · shapes).
//
// Margins: broad_phase(world, margin) expands every body box and segment box by margin/2,
// so that two shapes within `margin` of each other always have overlapping boxes; a body
// is paired with a half-plane when its box comes within margin/2 of the plane.
#include <lcprelax/contact/aabb.hpp>
#include <lcprelax/world/world.hpp>

#include <vector>

namespace lcprelax {

/// Boxes covering more grid cells than this are tested against all boxes instead.
constexpr int kMaxGridCellsPerBox = 64;

struct BodyPair {
  int a = -1, b = -1;  ///< body indices, a < b
  bool operator==(const BodyPair& o) const { return a == o.a && b == o.b; }
};

struct ShapePair {
  int body = -1;                                            ///< dynamic body index
  Contact::StaticKind kind = Contact::StaticKind::none;     ///< half_plane or segment
  int index = -1;                                           ///< into World::half_planes / segments
};

struct BroadPhasePairs {
  std::vector<BodyPair> body_pairs;    ///< sorted by (a, b)
  std::vector<ShapePair> shape_pairs;  ///< sorted by (body, kind, index)
};

/// All pairs i < j whose boxes overlap, excluding pairs where both are static.
/// `is_static` has one entry per box. Throws InputError for a non-finite box or
/// mismatched sizes.
std::vector<BodyPair> overlapping_pairs(const std::vector<Aabb>& boxes, const std::vector<bool>& is_static);

/// Candidate body–body and body–static-shape pairs of `world` for contacts with gap ≤
/// margin (m, ≥ 0). Throws InputError for a bad margin, non-finite poses or vertices, a
/// half-plane normal that is not unit (±1e-6) or a degenerate segment.
BroadPhasePairs broad_phase(const World& world, double margin);

}  // namespace lcprelax
