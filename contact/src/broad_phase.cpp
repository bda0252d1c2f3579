// Broad phase: uniform grid by sorting cell keys (see contact/broad_phase.hpp).
#include <lcprelax/contact/broad_phase.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <utility>

namespace lcprelax {
namespace {

// Cell indices stay below 2^30 per axis so that keys fit in 64 bits.
constexpr double kMaxCellsPerAxis = 1073741824.0;

struct CellRange {
  std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

std::uint64_t cell_key(std::int64_t x, std::int64_t y) {
  return (static_cast<std::uint64_t>(y) << 32) | static_cast<std::uint64_t>(x);
}

double grid_cell_size(const std::vector<Aabb>& boxes, const Vec2& span) {
  std::vector<double> size(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) size[i] = boxes[i].extent().maxCoeff();
  const auto mid = size.begin() + static_cast<std::ptrdiff_t>(size.size() / 2);
  std::nth_element(size.begin(), mid, size.end());
  double h = *mid;
  if (!(h > 0.0)) h = *std::max_element(size.begin(), size.end());
  if (!(h > 0.0)) h = 1.0;  // all boxes are points: any cell size works
  return std::max(h, span.maxCoeff() / kMaxCellsPerAxis);
}

}  // namespace

std::vector<BodyPair> overlapping_pairs(const std::vector<Aabb>& boxes, const std::vector<bool>& is_static) {
  const int n = static_cast<int>(boxes.size());
  if (is_static.size() != boxes.size()) throw InputError("overlapping_pairs: is_static and boxes differ in size");
  for (int i = 0; i < n; ++i)
    if (!boxes[i].is_finite()) {
      std::ostringstream os;
      os << "overlapping_pairs: box " << i << " is not finite";
      throw InputError(os.str());
    }
  std::vector<BodyPair> pairs;
  if (n < 2) return pairs;

  Vec2 origin = boxes[0].lower, top = boxes[0].upper;
  for (const Aabb& b : boxes) origin = origin.cwiseMin(b.lower), top = top.cwiseMax(b.upper);
  const double h = grid_cell_size(boxes, top - origin);

  std::vector<CellRange> cells(n);
  std::vector<bool> is_large(n, false);
  std::vector<int> large;
  std::vector<std::pair<std::uint64_t, int>> entries;  // (cell key, box)
  entries.reserve(4 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    CellRange& c = cells[i];
    c.x0 = static_cast<std::int64_t>(std::floor((boxes[i].lower.x() - origin.x()) / h));
    c.y0 = static_cast<std::int64_t>(std::floor((boxes[i].lower.y() - origin.y()) / h));
    c.x1 = static_cast<std::int64_t>(std::floor((boxes[i].upper.x() - origin.x()) / h));
    c.y1 = static_cast<std::int64_t>(std::floor((boxes[i].upper.y() - origin.y()) / h));
    if ((c.x1 - c.x0 + 1) * (c.y1 - c.y0 + 1) > kMaxGridCellsPerBox) {
      is_large[i] = true;
      large.push_back(i);
      continue;
    }
    for (std::int64_t y = c.y0; y <= c.y1; ++y)
      for (std::int64_t x = c.x0; x <= c.x1; ++x) entries.emplace_back(cell_key(x, y), i);
  }
  std::sort(entries.begin(), entries.end());

  // Pairs sharing a cell, reported only from the cell of their intersection's lower corner
  // (floor is monotone, so that cell is (max x0, max y0), covered by both boxes).
  for (std::size_t begin = 0; begin < entries.size();) {
    std::size_t end = begin;
    while (end < entries.size() && entries[end].first == entries[begin].first) ++end;
    for (std::size_t p = begin; p < end; ++p)
      for (std::size_t q = p + 1; q < end; ++q) {
        const int i = entries[p].second, j = entries[q].second;  // i < j (sorted)
        if ((is_static[i] && is_static[j]) || !overlaps(boxes[i], boxes[j])) continue;
        const std::int64_t x = std::max(cells[i].x0, cells[j].x0), y = std::max(cells[i].y0, cells[j].y0);
        if (cell_key(x, y) == entries[begin].first) pairs.push_back({i, j});
      }
    begin = end;
  }

  // Large boxes against everything (a pair of two large boxes from the lower index only).
  for (int i : large)
    for (int j = 0; j < n; ++j) {
      if (j == i || (is_large[j] && j < i) || (is_static[i] && is_static[j])) continue;
      if (overlaps(boxes[i], boxes[j])) pairs.push_back({std::min(i, j), std::max(i, j)});
    }

  std::sort(pairs.begin(), pairs.end(),
            [](const BodyPair& l, const BodyPair& r) { return l.a != r.a ? l.a < r.a : l.b < r.b; });
  return pairs;
}

BroadPhasePairs broad_phase(const World& world, double margin) {
  if (!(margin >= 0.0) || !std::isfinite(margin)) {
    std::ostringstream os;
    os << "margin = " << margin << " must be finite and >= 0";
    throw InputError(os.str());
  }
  const double half = 0.5 * margin;
  const int n = static_cast<int>(world.bodies.size());
  std::vector<Aabb> boxes(n);
  std::vector<bool> is_static(n);
  for (int i = 0; i < n; ++i) {
    const RigidBody& body = world.bodies[i];
    boxes[i] = aabb(body, half);
    is_static[i] = body.is_static;
    if (!body.pose.allFinite() || !boxes[i].is_finite()) {
      std::ostringstream os;
      os << "body " << i << " has a non-finite pose or vertex";
      throw InputError(os.str());
    }
  }
  for (std::size_t k = 0; k < world.half_planes.size(); ++k) {
    const HalfPlane& hp = world.half_planes[k];
    if (!hp.normal.allFinite() || !std::isfinite(hp.offset) || std::abs(hp.normal.norm() - 1.0) > 1e-6) {
      std::ostringstream os;
      os << "half-plane " << k << " needs a finite unit normal and a finite offset";
      throw InputError(os.str());
    }
  }
  for (std::size_t k = 0; k < world.segments.size(); ++k) {
    const Segment& s = world.segments[k];
    if (!s.a.allFinite() || !s.b.allFinite() || !((s.b - s.a).norm() > 0.0)) {
      std::ostringstream os;
      os << "segment " << k << " needs finite, distinct end points";
      throw InputError(os.str());
    }
  }
  BroadPhasePairs out;
  out.body_pairs = overlapping_pairs(boxes, is_static);

  std::vector<Aabb> segment_boxes;
  segment_boxes.reserve(world.segments.size());
  for (const Segment& s : world.segments) segment_boxes.push_back(aabb(s, half));
  for (int i = 0; i < n; ++i) {
    if (is_static[i]) continue;
    for (int k = 0; k < static_cast<int>(world.half_planes.size()); ++k)
      if (box_near_half_plane(boxes[i], world.half_planes[k], half))
        out.shape_pairs.push_back({i, Contact::StaticKind::half_plane, k});
    for (int k = 0; k < static_cast<int>(segment_boxes.size()); ++k)
      if (overlaps(boxes[i], segment_boxes[k])) out.shape_pairs.push_back({i, Contact::StaticKind::segment, k});
  }
  return out;
}

}  // namespace lcprelax
