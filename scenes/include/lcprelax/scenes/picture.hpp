#pragma once
// Pictures of a world (PNG or SVG) drawn with Cairo; optional at build time
// (LCPRELAX_WITH_CAIRO → LCPRELAX_HAS_CAIRO). Without Cairo every function here throws
// std::runtime_error("built without Cairo").
//
// What is drawn (world units m, y up; the picture maps them uniformly onto pixels):
// - the view box fits every body and every segment, plus a 10% margin on each side; it is
//   widened or heightened to an aspect ratio between 1:4 and 4:1; an empty world shows
//   [-1, 1]²;
// - half-planes as a grey band filling their solid side {p : normal·p < offset}, clipped to
//   the view, with the boundary line; segments as dark lines;
// - dynamic bodies filled with a viridis-like colormap of their contact count (contacts
//   whose body_a or body_b is the body) or of their speed |(vx, vy)| (m/s), scaled from 0 to
//   the largest value; static bodies in grey; all outlined;
// - optionally every contact: a red dot at its point and a red line along its normal
//   (from b to a, 4% of the view width);
// - a legend line (title, colour scale range) at the top left.
#include <lcprelax/world/world.hpp>

#include <string>
#include <vector>

namespace lcprelax {

struct PictureOptions {
  enum class Color { contacts, speed } color = Color::contacts;  ///< what the fill shows
  bool draw_contacts = false;  ///< draw contact points and normals
  int width_px = 1200;         ///< picture width (pixels, 16..16384); height from the view
  std::string title;           ///< shown in the legend line when non-empty
};

/// Writes a picture of `world` with its `contacts`: SVG if `path` ends in ".svg", PNG if
/// ".png" (case-insensitive), otherwise InputError. InputError also for non-finite body
/// poses or vertices or an out-of-range width; std::runtime_error if the file cannot be
/// written.
void write_picture(const std::string& path, const World& world, const std::vector<Contact>& contacts,
                   const PictureOptions& options);

/// Writes `dir`/frame_NNNNNN.png (index ≥ 0, zero-padded to six digits), creating `dir` if
/// needed, and returns that path. For movies: ffmpeg -i dir/frame_%06d.png.
std::string write_frame(const std::string& dir, int index, const World& world,
                        const std::vector<Contact>& contacts, const PictureOptions& options);

}  // namespace lcprelax
