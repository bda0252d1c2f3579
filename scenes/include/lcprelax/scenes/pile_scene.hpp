#pragma once
// Generated scenes shared by tests, benchmarks and demos: a random pile of convex polygons
// in a container, and the exact resting configurations of the physical validation tests
// (a column of boxes, a pyramid of boxes, a box on an incline).
//
// Conventions (models/world.hpp, scenes/scene.hpp): SI units (m, kg/m², s, rad); body
// vertices are centred on the centroid, the pose is the centre of mass, and mass and
// inertia come from the density (contact/polygon.hpp); every body and static shape has
// material 0 and every pair the friction coefficient `mu` (FrictionTable::default_mu);
// gravity is (0, −9.81) m/s²; other settings are SimulationSettings' defaults unless listed.
//
// Pile layout: the container is the ground half-plane y ≥ 0 and two vertical wall segments
// x = 0 and x = W, from y = 0 to the wall height H. Each polygon lies inside the disc of
// its circumradius r ∈ [min_size, max_size]; the discs are centred in the square cells
// (side s = 2.2·max_size) of a grid filled row by row from the bottom left, whose first
// row is centred at y = s/2 and whose columns are centred between the walls;
// H = (rows + 1)·s. So initially no two shapes touch: every gap is at least 0.1·max_size
// (to the walls and the ground) or 0.2·max_size (between polygons).
// Random draws come from std::mt19937_64 (whose output the C++ standard fixes) mapped to
// [0, 1) by the top 53 bits, never through <random>'s distributions, so a seed gives the
// same draws (vertex counts, sizes, angles) with every standard library; coordinates can
// differ between platforms only by the rounding of std::sin and std::cos.
#include <lcprelax/scenes/scene.hpp>

#include <cstdint>

namespace lcprelax {

/// Options of make_pile_scene; check_pile_options gives the valid ranges.
struct PileOptions {
  int bodies = 200;                         ///< number of polygons, 1..1 000 000
  std::uint64_t seed = 1;                   ///< std::mt19937_64 seed
  double min_size = 0.05, max_size = 0.15;  ///< circumradius range (m), 1e-6 ≤ min ≤ max ≤ 1e6
  int min_vertices = 3, max_vertices = 8;   ///< vertex count range, 3 ≤ min ≤ max ≤ 12
  double density = 1000;                    ///< area density (kg/m²), > 0
  double mu = 0.5;                          ///< friction coefficient of every pair, ≥ 0
  /// Container width W (m); 0 chooses W ≈ bodies·(min_size + max_size)/5, about five
  /// layers of average diameter deep once settled; otherwise
  /// 2.2·max_size ≤ W ≤ bodies·2.2·max_size (one grid cell to one cell per body).
  double container_width = 0;
  double dt = 1e-2;                         ///< time step (s), > 0
  ContactModel model = ContactModel::lcp;   ///< contact model of the scene
};

/// Throws InputError naming the field ("PileOptions.max_size: must be >= min_size ...")
/// unless every option is finite and in its range.
void check_pile_options(const PileOptions& options);

/// A pile of `options.bodies` random convex polygons above the ground, between two walls
/// (layout above). Each polygon has n ∈ [min_vertices, max_vertices] vertices on its
/// circumcircle at angles φ₀ + 2π(k + ξ_k)/n, ξ_k ∈ [−0.3, 0.3] (strictly convex,
/// polygon_validation_error), a random angle θ ∈ [0, 2π), velocity components in ±0.5·max_size/s
/// and angular velocity in ±1 rad/s. The same options give the same scene, bit for bit
/// (on one platform; see above).
/// Throws InputError for invalid options (check_pile_options).
Scene make_pile_scene(const PileOptions& options);

/// `boxes` square boxes of side `size` (m) stacked in a column on the ground half-plane
/// y ≥ 0: box i has its centre at (0, (i + ½)·size), so every gap is 0 (up to rounding);
/// density 1000 kg/m². Contacts: 2 with the ground, 2 per box-on-box interface.
/// Throws InputError unless boxes ≥ 1, size > 0 and mu ≥ 0 (all finite).
Scene make_box_stack_scene(int boxes, double size, double mu);

/// A pyramid of square boxes of side `size` (m) on the ground y ≥ 0: row r = 0..base−1
/// has base − r boxes, box j of row r centred at ((j + (r + 1)/2)·size, (r + ½)·size), so
/// each box above the ground rests on two boxes (half a face each) and touches its row
/// neighbours side to side, all with gap 0 (up to rounding); density 1000 kg/m².
/// Contacts (2 per touching pair): 2·base with the ground, 2·base·(base − 1) between rows
/// and base·(base − 1) between row neighbours. Throws InputError unless base ≥ 1,
/// size > 0 and mu ≥ 0.
Scene make_pyramid_scene(int base, double size, double mu);

/// A square box of side `size` (m, density `density` kg/m²) resting on the half-plane
/// through the origin tilted by `angle` (rad, counter-clockwise; normal
/// (−sin angle, cos angle)): the box is rotated by `angle` so that its bottom face lies on
/// the plane (gap 0 up to rounding) and its centre is at (size/2)·normal. With
/// μ < tan|angle| it slides down (towards −x for angle > 0), otherwise it sticks.
/// Throws InputError unless |angle| < π/2, mu ≥ 0, size > 0 and density > 0.
Scene make_incline_scene(double angle, double mu, double size = 1.0, double density = 1000);

}  // namespace lcprelax
