#pragma once
// Scene files: JSON (docs/formats.md). SI units (m, kg, s, rad); angles counter-clockwise.
//
// Schema (every key optional unless marked "required"; unknown keys are errors):
//   {
//     "name": "box on ground",              // string, default ""
//     "gravity": [gx, gy],                  // m/s², default [0, -9.81]
//     "dt": 0.01,                           // s, > 0, default 0.01
//     "steps": 100,                         // integer ≥ 0, default 100
//     "model": "lcp",                       // "lcp" | "convex", default "lcp"
//     "softening": "exp_phi",               // the convex model's normal softening
//                                           // (models/normal_softening.hpp): "exp_phi" |
//                                           // "linear_penalty" | "mujoco_impedance" (or
//                                           // "exp" | "penalty" | "impedance"), default
//                                           // "exp_phi" (impedance: MuJoCo's default
//                                           // solimp/solref)
//     "margin": 0.01,                       // m, ≥ 0, default 0.01
//     "friction": {                         // default {"default": 0.5, "pairs": []}
//       "default": 0.5,                     // μ ≥ 0 for pairs not listed
//       "pairs": [{"materials": [a, b], "mu": 0.3}]   // integers ≥ 0, μ ≥ 0; symmetric,
//     },                                              // each unordered pair at most once
//     "bodies": [{
//       "vertices": [[x, y], ...],          // required; 3..12, counter-clockwise, strictly
//                                           // convex (polygon_validation_error); m, relative to
//                                           // "position" in the body frame (rotated by
//                                           // "angle")
//       "density": 1000,                    // kg/m², > 0 — OR both of:
//       "mass": 1.0, "inertia": 0.1667,     // kg > 0, kg·m² > 0 about the centroid
//       "position": [x, y],                 // m, default [0, 0]
//       "angle": 0.0,                       // rad, default 0
//       "velocity": [vx, vy],               // m/s of the centre of mass, default [0, 0]
//       "angular_velocity": 0.0,            // rad/s, default 0
//       "material": 0,                      // integer ≥ 0, default 0
//       "static": false,                    // default false
//       "gap_offset": 0.0,                  // m, default 0 (RigidBody::gap_offset): added
//                                           // to the gap of the body's contacts
//       "velocity_residual": [[..4], [..4], [..4]]  // default 0: W of v* += W (vx, vy, ω, 1),
//                                           // rows vx, vy, ω (RigidBody::velocity_residual)
//     }],
//     "half_planes": [{"normal": [nx, ny], "offset": d, "material": k}],
//     "segments": [{"a": [x, y], "b": [x, y], "material": k}],
//     "warm_start": [[a, b, kind, index, ordinal, normal, friction], ...]  // default []
//   }
// Meaning:
// - A body's world shape is p = position + R(angle) v for its listed vertices v. The
//   vertices are recentred on their centroid C, so the body's pose (its centre of mass) is
//   position + R(angle) C; a polygon whose centroid is already at its origin is unchanged
//   (contact/polygon.hpp: recentre).
// - "density" gives mass ρA and inertia ρJ (contact/polygon.hpp: mass_properties). Static
//   bodies need no mass: when given, "mass"/"inertia" must be ≥ 0 (default 0) or
//   "density" > 0.
// - Half-plane: free space is {p : normal·p ≥ offset}; "normal" must be non-zero and is
//   normalized (normal and offset are both divided by |normal|); "offset" default 0.
// - Segment: static, two-sided; a ≠ b.
// - "warm_start" (Scene::warm_start, Simulator::warm_start_state): the state a simulator's
//   next step warm-starts from, one entry per contact of the last step: its identity (body
//   a ≥ 0, body b or −1 for a static shape, static kind 0 none / 1 half-plane / 2 segment,
//   static index or −1, ordinal among the pair's contacts) and its codes (lcp_basis_codes.hpp:
//   normal 0/1, friction 0..7). All integers. Written when the scene has one (lcprelax pile
//   --save-scene); a file without it starts cold.
// - "gap_offset" and "velocity_residual" are nonphysical terms a learned model may carry
//   (world/world.hpp); the writer writes them only where they are nonzero.
// Errors: lcprelax::InputError whose message names the field path, e.g.
//   "bodies[3].vertices: vertices are clockwise", "bodies[0].mass: must be > 0",
//   "unknown key 'densty' in bodies[2]", "dt: expected a number, got string",
//   "duplicate key 'mass' in bodies[1]", "invalid JSON: ..." (with nlohmann's position).
// JSON has no NaN or Inf; numbers written as strings ("nan") are type errors, and numbers
// that overflow a double are rejected by the parser.
// Limits: load_scene reads at most kMaxSceneBytes (256 MiB; a larger file or a device such as
// /dev/zero is an InputError); a leading UTF-8 BOM is skipped; keys and strings echoed in
// messages are cut to 64 characters and messages to 1 KiB (core/text_input.hpp).
#include <lcprelax/scenes/scene.hpp>

#include <cstddef>
#include <string>
#include <string_view>

namespace lcprelax {

/// Largest scene file load_scene reads: 256 MiB.
inline constexpr std::size_t kMaxSceneBytes = std::size_t{256} << 20;

/// Parses scene JSON text (the schema above). Throws InputError.
Scene parse_scene(std::string_view json_text);

/// Reads and parses a scene file; error messages are prefixed by "PATH: ".
Scene load_scene(const std::string& path);

/// Serializes a scene as JSON text in the schema above: every body with "mass" and
/// "inertia" (static bodies omit them when both are 0), body-frame vertices and its centre of
/// mass as "position"; numbers with round-trip precision, so parse_scene(write_scene(s))
/// reproduces s exactly for a valid scene. Throws InputError naming the field for
/// non-finite numbers or invalid settings.
std::string write_scene(const Scene& scene);

/// write_scene to a file; throws std::runtime_error if the file cannot be written.
void save_scene(const std::string& path, const Scene& scene);

}  // namespace lcprelax
