#pragma once
// One sample's contact problem data for a polygon on the ground, as a differentiable
// function of θ (polygon_params.hpp), with hand-written derivatives (chain rule) with
// respect to every parameter (checked against central differences in
// tests/learn_polygon_assembly_test.cpp).
//
// Active set: the contacts are the polygon–half-plane manifold of the library's narrow
// phase (contact/narrow_phase.hpp: the at most two deepest vertices with gap ≤ margin) at
// the sample's pre-state and the CURRENT θ, with the simulator's speculative margin
//     margin + 2Δt·max over {v, v*} of (|v_xy| + |ω|·radius)      (models/simulator.hpp).
// For learning, further candidate vertices within an extra margin can be added
// (polygon_active_vertices). Each contact is identified by its vertex index; the set is
// then held fixed while differentiating (a vertex entering or leaving the set is a kink
// the derivative ignores).
//
// Per contact with body-frame vertex b (vertex i), pose (x, y, θ), R = R(θ), ground
// normal n = (−sin α, cos α), tangent t = (−n_y, n_x) (contact_system.hpp), offset
// o = h cos α:
//     φ   = n·((x, y) + R b) − o                         gap (m, < 0 overlapping)
//     p   = (x, y) + R b − ½ φ n                         point midway (narrow phase)
//     r   = p − (x, y) = R b − ½ φ n                     lever arm
//     Jn  = (n_x, n_y, r × n) = (n, (R b) × n)
//     Jt  = (t_x, t_y, r × t) = (t, (R b) × t − ½ φ)     (n × t = 1)
// with a × c = a_x c_y − a_y c_x. Derivatives (dn/dα = t, dt/dα = −n):
//     ∂/∂b_k:  d(Rb) = R e_k;  dφ = n·d(Rb);  d(r×n) = d(Rb)×n;  d(r×t) = d(Rb)×t − ½dφ
//     ∂/∂h:    dφ = −cos α;   d(r×t) = −½ dφ
//     ∂/∂α:    dφ = t·((x,y) + R b) + h sin α;  dJn = (t, (Rb)×t);
//              dJt = (−n, −(Rb)×n − ½ dφ)
// Mass matrix M = diag(m, m, I), M⁻¹ = (1/m, 1/m, 1/I); free velocity
//     v* = v + Δt·(g + u_xy/m, u_τ/I),   ∂v*/∂m = −Δt u_xy/m²,  ∂v*/∂I = −Δt u_τ/I²;
//     ∂M⁻¹/∂m = (−1/m², −1/m², 0),  ∂M⁻¹/∂I = (0, 0, −1/I²).
// μ: one friction row per contact (μ > 0 always under the log transform), ∂μ_f/∂μ = 1.
// Units: Jn, Jt rows (1, 1, m); φ m; M⁻¹ (1/kg, 1/kg, 1/(kg·m²)); v* (m/s, m/s, rad/s).
#include <lcprelax/learn/polygon_dataset.hpp>
#include <lcprelax/learn/polygon_params.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/sparse/types.hpp>

#include <vector>

namespace lcprelax::learn {

/// Dense contact data of one sample (3 dofs, at most 2 contacts).
struct PolygonContactData {
  DenseMatrix Jn;   ///< nc×3
  DenseMatrix Jt;   ///< nc×3 (one friction row per contact)
  Vector phi;       ///< nc
  Vector mu;        ///< nc
  Vector minv;      ///< 3
  Vector v_star;    ///< 3

  Index num_contacts() const { return static_cast<Index>(phi.size()); }
  /// Sets every entry to zero with the sizes of a problem of nc contacts.
  void set_zero(Index nc);
};

/// Value and derivatives: tangent[k] = ∂(data)/∂θ_k for every parameter k of the layout.
struct PolygonAssembly {
  std::vector<int> vertices;   ///< vertex index of each contact (increasing)
  PolygonContactData value;
  std::vector<PolygonContactData> tangent;
};

/// The speculative margin used to find the active set (above).
double polygon_speculative_margin(const PolygonModel& model, const PolygonTransition& sample, const PolygonDataset& data);

/// Vertex indices of the contacts the narrow phase finds at the sample's pre-state for
/// `model` (increasing; at most two), plus, when extra_margin > 0 (m), every other vertex
/// whose gap is ≤ speculative margin + extra_margin (learning candidates: with a wrong
/// geometry the vertex that touched in the data can lie beyond the simulator's margin; as a
/// contact it can still receive an impulse, and a gradient, in the relaxed loss, while
/// left out its sample has no contact and no gradient towards the ground).
std::vector<int> polygon_active_vertices(const PolygonModel& model, const PolygonTransition& sample,
                                         const PolygonDataset& data, double extra_margin = 0.0);

/// Assembles value and derivatives for the given active vertices (not re-detected).
void assemble_polygon(const PolygonModel& model, const std::vector<int>& vertices, const PolygonTransition& sample,
                      const PolygonDataset& data, PolygonAssembly& out);

/// The same data as the library's ContactSystem (sparse; one body, one half-plane), e.g.
/// to run the library's stewart_trinkle_lcp or contact models on it.
ContactSystem to_contact_system(const PolygonContactData& d);

}  // namespace lcprelax::learn
