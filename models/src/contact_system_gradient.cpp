// Reverse-mode pullback of an island's ContactSystem to the world's primitives (see
// models/contact_system_gradient.hpp). Per contact, forward-mode automatic differentiation
// (Eigen's AutoDiffScalar) over the local primitives of its two shapes — at most 2·12
// body-frame vertex coordinates of a, and 2·12 of b, or a half-plane's normal and offset,
// or a segment's end points — of the contact's scalar share ⟨ct, (Jn row, Jt row, φ)⟩,
// the rows recomputed from the contact's recorded feature (contact/contact_features.hpp).
// contact_system_tangent uses the same per-contact derivatives in forward mode.
#include <lcprelax/models/contact_system_gradient.hpp>
#include <lcprelax/contact/contact_features.hpp>
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/errors.hpp>

#include <unsupported/Eigen/AutoDiff>

#include <cmath>
#include <sstream>
#include <string>

namespace lcprelax {
namespace {

constexpr int kMaxDirections = 4 * kMaxPolygonVertices;  // 2 coordinates × 12 vertices × 2 shapes
using Derivatives = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxDirections, 1>;
using AD = Eigen::AutoDiffScalar<Derivatives>;
using Vec2AD = Vec2Of<AD>;

// World vertices x + R(θ) v of a body as functions of its body-frame vertices, which are
// the directions first, first + 1, ... (2 per vertex) of `directions`. The same operations
// as make_shape (convex_shape.cpp), so values agree bit for bit.
int seed_body(const RigidBody& body, int first, int directions, Vec2AD* out) {
  const double c = std::cos(body.pose.z()), sn = std::sin(body.pose.z());
  const int n = static_cast<int>(body.shape.vertices.size());
  for (int i = 0; i < n; ++i) {
    const Vec2& v = body.shape.vertices[i];
    const AD vx(v.x(), directions, first + 2 * i), vy(v.y(), directions, first + 2 * i + 1);
    out[i] = Vec2AD(AD(body.pose.x()) + c * vx - sn * vy, AD(body.pose.y()) + sn * vx + c * vy);
  }
  return n;
}

// Σ_j ct(row, 3·block + j) · (±)(d_x, d_y, r × d): a row's share of ⟨ct, J⟩.
AD row_share(const SparseMatrix& ct, Index row, Index block, const Vec2AD& d, const Vec2AD& r) {
  const double cx = ct.coeff(row, 3 * block), cy = ct.coeff(row, 3 * block + 1), cw = ct.coeff(row, 3 * block + 2);
  return cx * d.x() + cy * d.y() + cw * (r.x() * d.y() - r.y() * d.x());
}

// Throws InputError (prefixed by `caller`) unless the shapes fit; ct may be null, g is named `g_name`.
void check_sizes(const char* caller, const World& world, const std::vector<Contact>& contacts, const ContactSystem& s,
                 double dt, const std::vector<Vec3>& applied, const ContactSystemCotangent* ct, const WorldGradient& g,
                 const std::string& g_name) {
  const Index nc = s.num_contacts(), nf = s.num_friction(), nd = s.num_dofs();
  auto fail = [caller](const std::string& what) { throw InputError(std::string(caller) + ": " + what); };
  if (!(dt > 0.0) || !std::isfinite(dt)) fail("dt: must be finite and > 0");
  if (ct) {
    if (ct->Jn.rows() != nc || ct->Jn.cols() != nd) fail("ct.Jn: must have the shape of s.Jn (ContactSystemCotangent::set_zero)");
    if (ct->Jt.rows() != nf || ct->Jt.cols() != nd) fail("ct.Jt: must have the shape of s.Jt");
    if (ct->phi.size() != nc) fail("ct.phi: one entry per contact of the island expected");
    if (ct->mu.size() != nf) fail("ct.mu: one entry per friction row expected");
    if (ct->compliance.size() != nc || ct->erp.size() != nc)
      fail("ct.compliance, ct.erp: one entry per contact of the island expected");
    if (ct->minv.size() != nd) fail("ct.minv: one entry per dof expected");
    if (ct->v_star.size() != nd) fail("ct.v_star: one entry per dof expected");
  }
  if (!applied.empty() && applied.size() != world.bodies.size()) fail("applied: one (fx, fy, torque) per body or empty");
  if (g.bodies.size() != world.bodies.size() || g.half_plane_normal.size() != world.half_planes.size() ||
      g.half_plane_offset.size() != world.half_planes.size() || g.segment_ends.size() != world.segments.size() ||
      g.contact_mu.size() != contacts.size() || g.contact_compliance.size() != contacts.size() ||
      g.contact_erp.size() != contacts.size())
    fail(g_name + ": shapes differ from the world's or the contact list's (WorldGradient::set_zero)");
  for (std::size_t b = 0; b < world.bodies.size(); ++b)
    if (g.bodies[b].vertices.size() != world.bodies[b].shape.vertices.size())
      fail(g_name + ".bodies[" + std::to_string(b) + "].vertices: one entry per body vertex expected");
  for (const int c : s.contacts) {
    if (c < 0 || c >= static_cast<int>(contacts.size())) fail("s.contacts: index outside the contact list");
    const std::string e = contact_feature_error(world, contacts[c]);
    if (!e.empty()) fail("contacts[" + std::to_string(c) + "]: " + e);
    if (static_cast<int>(world.bodies[contacts[c].body_a].shape.vertices.size()) > kMaxPolygonVertices ||
        (contacts[c].body_b >= 0 &&
         static_cast<int>(world.bodies[contacts[c].body_b].shape.vertices.size()) > kMaxPolygonVertices))
      fail("contacts[" + std::to_string(c) + "]: a body has more than kMaxPolygonVertices vertices");
  }
}

// A contact's geometry as a function of its local primitives, the AD directions: shape a's
// body-frame vertices (2 per vertex), then shape b's body-frame vertices, or the half-plane's
// normal (2) and offset, or the segment's end points a, b (2 each).
struct LocalContact {
  int na = 0;          // vertices of a
  int directions = 0;  // local primitives
  FeatureGeometry<AD> geo;
};

LocalContact local_geometry(const World& world, const Contact& c) {
  LocalContact lc;
  const RigidBody& body_a = world.bodies[c.body_a];
  const int na = lc.na = static_cast<int>(body_a.shape.vertices.size());
  int directions = 2 * na;
  if (c.static_kind == Contact::StaticKind::half_plane) directions += 3;
  else if (c.static_kind == Contact::StaticKind::segment) directions += 4;
  else directions += 2 * static_cast<int>(world.bodies[c.body_b].shape.vertices.size());
  lc.directions = directions;

  Vec2AD va[kMaxPolygonVertices], vb[kMaxPolygonVertices];
  seed_body(body_a, 0, directions, va);
  if (c.static_kind == Contact::StaticKind::half_plane) {
    const HalfPlane& hp = world.half_planes[c.static_index];
    const Vec2AD normal(AD(hp.normal.x(), directions, 2 * na), AD(hp.normal.y(), directions, 2 * na + 1));
    lc.geo = feature_geometry<AD>(c.feature, va, normal, AD(hp.offset, directions, 2 * na + 2));
  } else if (c.static_kind == Contact::StaticKind::segment) {
    const Segment& sg = world.segments[c.static_index];
    vb[0] = Vec2AD(AD(sg.a.x(), directions, 2 * na), AD(sg.a.y(), directions, 2 * na + 1));
    vb[1] = Vec2AD(AD(sg.b.x(), directions, 2 * na + 2), AD(sg.b.y(), directions, 2 * na + 3));
    lc.geo = feature_geometry<AD>(c.feature, va, na, vb, 2);
  } else {
    const int nb = seed_body(world.bodies[c.body_b], 2 * na, directions, vb);
    lc.geo = feature_geometry<AD>(c.feature, va, na, vb, nb);
  }
  return lc;
}

// Adds a local derivative vector d (LocalContact's directions) to the world's entries of g.
void scatter(const Contact& c, int na, const Derivatives& d, WorldGradient& g) {
  for (int k = 0; k < na; ++k) g.bodies[c.body_a].vertices[k] += Vec2(d(2 * k), d(2 * k + 1));
  if (c.static_kind == Contact::StaticKind::half_plane) {
    g.half_plane_normal[c.static_index] += Vec2(d(2 * na), d(2 * na + 1));
    g.half_plane_offset[c.static_index] += d(2 * na + 2);
  } else if (c.static_kind == Contact::StaticKind::segment) {
    g.segment_ends[c.static_index][0] += Vec2(d(2 * na), d(2 * na + 1));
    g.segment_ends[c.static_index][1] += Vec2(d(2 * na + 2), d(2 * na + 3));
  } else {
    std::vector<Vec2>& gb = g.bodies[c.body_b].vertices;
    for (std::size_t k = 0; k < gb.size(); ++k) gb[k] += Vec2(d(2 * na + 2 * k), d(2 * na + 2 * k + 1));
  }
}

// The local direction (LocalContact's directions) of a world tangent `dir`.
Derivatives gather(const Contact& c, int na, int directions, const WorldGradient& dir) {
  Derivatives d(directions);
  for (int k = 0; k < na; ++k) d.segment<2>(2 * k) = dir.bodies[c.body_a].vertices[k];
  if (c.static_kind == Contact::StaticKind::half_plane) {
    d.segment<2>(2 * na) = dir.half_plane_normal[c.static_index];
    d(2 * na + 2) = dir.half_plane_offset[c.static_index];
  } else if (c.static_kind == Contact::StaticKind::segment) {
    d.segment<2>(2 * na) = dir.segment_ends[c.static_index][0];
    d.segment<2>(2 * na + 2) = dir.segment_ends[c.static_index][1];
  } else {
    const std::vector<Vec2>& vb = dir.bodies[c.body_b].vertices;
    for (std::size_t k = 0; k < vb.size(); ++k) d.segment<2>(2 * na + 2 * static_cast<int>(k)) = vb[k];
  }
  return d;
}

// Adds the geometric part (Jn, Jt rows and φ) of local contact i to g.
void pull_back_contact(const World& world, const Contact& c, Index i, Index friction_row, const std::vector<int>& block,
                       const ContactSystemCotangent& ct, WorldGradient& g) {
  const LocalContact lc = local_geometry(world, c);
  const Vec2AD& n = lc.geo.normal;
  const Vec2AD t(-n.y(), n.x());
  const Vec2AD ra = lc.geo.point - world.bodies[c.body_a].pose.head<2>().cast<AD>();
  AD share = ct.phi(i) * lc.geo.gap;
  share += row_share(ct.Jn, i, block[c.body_a], n, ra);
  if (friction_row >= 0) share += row_share(ct.Jt, friction_row, block[c.body_a], t, ra);
  if (world.is_dynamic(c.body_b)) {
    const Vec2AD rb = lc.geo.point - world.bodies[c.body_b].pose.head<2>().cast<AD>();
    share -= row_share(ct.Jn, i, block[c.body_b], n, rb);
    if (friction_row >= 0) share -= row_share(ct.Jt, friction_row, block[c.body_b], t, rb);
  }
  if (share.derivatives().size() == 0) return;  // the cotangent does not touch this contact
  scatter(c, lc.na, share.derivatives(), g);
}

// Sets the entries of a row's tangent: d/dε of (±)(d_x, d_y, r × d) along `dir`.
void push_row(SparseMatrix& out, Index row, Index block, const Vec2AD& d, const Vec2AD& r, double sign,
              const Derivatives& dir) {
  const AD w = r.x() * d.y() - r.y() * d.x();
  out.coeffRef(row, 3 * block) = sign * d.x().derivatives().dot(dir);
  out.coeffRef(row, 3 * block + 1) = sign * d.y().derivatives().dot(dir);
  out.coeffRef(row, 3 * block + 2) = sign * w.derivatives().dot(dir);
}

}  // namespace

void ContactSystemCotangent::set_zero(const ContactSystem& s) {
  Jn = s.Jn;
  Jn.makeCompressed();
  Jn.coeffs().setZero();
  Jt = s.Jt;
  Jt.makeCompressed();
  Jt.coeffs().setZero();
  phi = Vector::Zero(s.num_contacts());
  mu = Vector::Zero(s.num_friction());
  compliance = Vector::Zero(s.num_contacts());
  erp = Vector::Zero(s.num_contacts());
  minv = Vector::Zero(s.num_dofs());
  v_star = Vector::Zero(s.num_dofs());
  lcp_block_M.setZero();
  lcp_block_q.setZero();
}

void WorldGradient::set_zero(const World& world, std::size_t num_contacts) {
  bodies.assign(world.bodies.size(), Body{});
  for (std::size_t b = 0; b < world.bodies.size(); ++b)
    bodies[b].vertices.assign(world.bodies[b].shape.vertices.size(), Vec2::Zero());
  half_plane_normal.assign(world.half_planes.size(), Vec2::Zero());
  half_plane_offset.assign(world.half_planes.size(), 0.0);
  segment_ends.assign(world.segments.size(), {Vec2::Zero(), Vec2::Zero()});
  contact_mu.assign(num_contacts, 0.0);
  contact_compliance.assign(num_contacts, 0.0);
  contact_erp.assign(num_contacts, 0.0);
  lcp_block_M.setZero();
  lcp_block_q.setZero();
}

void accumulate_world_gradient(const World& world, const std::vector<Contact>& contacts, const ContactSystem& s,
                               double dt, const std::vector<Vec3>& applied, const ContactSystemCotangent& ct,
                               WorldGradient& g) {
  check_sizes("accumulate_world_gradient", world, contacts, s, dt, applied, &ct, g, "g");
  std::vector<int> block(world.bodies.size(), -1);
  for (std::size_t k = 0; k < s.bodies.size(); ++k) block[s.bodies[k]] = static_cast<int>(k);
  g.lcp_block_M += ct.lcp_block_M;
  g.lcp_block_q += ct.lcp_block_q;

  // M⁻¹ = (1/m, 1/m, 1/I) and v* = v + Δt (g + u_xy/m, u_τ/I).
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    const RigidBody& b = world.bodies[s.bodies[k]];
    WorldGradient::Body& gb = g.bodies[s.bodies[k]];
    const Index j = static_cast<Index>(3 * k);
    const double m2 = b.mass * b.mass, i2 = b.inertia * b.inertia;
    gb.mass -= (ct.minv(j) + ct.minv(j + 1)) / m2;
    gb.inertia -= ct.minv(j + 2) / i2;
    gb.velocity_residual += ct.v_star.segment<3>(j) * velocity_residual_features(b).transpose();
    if (!applied.empty()) {
      const Vec3& u = applied[s.bodies[k]];
      gb.mass -= dt * (ct.v_star(j) * u.x() + ct.v_star(j + 1) * u.y()) / m2;
      gb.inertia -= dt * ct.v_star(j + 2) * u.z() / i2;
    }
  }

  // μ per friction row, and the friction row of each contact.
  std::vector<Index> friction_row(static_cast<std::size_t>(s.num_contacts()), -1);
  for (Index f = 0; f < s.num_friction(); ++f) {
    friction_row[static_cast<std::size_t>(s.friction_rows[f])] = f;
    g.contact_mu[static_cast<std::size_t>(s.contacts[s.friction_rows[f]])] += ct.mu(f);
  }
  for (Index i = 0; i < s.num_contacts(); ++i) {
    const Contact& c = contacts[s.contacts[i]];
    if (block[c.body_a] < 0 || (world.is_dynamic(c.body_b) && block[c.body_b] < 0))
      throw InputError("accumulate_world_gradient: s.contacts[" + std::to_string(i) + "]: a body is not in the island");
    g.contact_compliance[static_cast<std::size_t>(s.contacts[i])] += ct.compliance(i);
    g.contact_erp[static_cast<std::size_t>(s.contacts[i])] += ct.erp(i);
    g.bodies[c.body_a].gap_offset += ct.phi(i);
    if (c.body_b >= 0) g.bodies[c.body_b].gap_offset += ct.phi(i);
    pull_back_contact(world, contacts[s.contacts[i]], i, friction_row[static_cast<std::size_t>(i)], block, ct, g);
  }
}

ContactSystem contact_system_tangent(const World& world, const std::vector<Contact>& contacts, const ContactSystem& s,
                                     double dt, const std::vector<Vec3>& applied, const WorldGradient& direction) {
  check_sizes("contact_system_tangent", world, contacts, s, dt, applied, nullptr, direction, "direction");
  ContactSystem out = s;
  out.Jn.makeCompressed();
  out.Jn.coeffs().setZero();
  out.Jt.makeCompressed();
  out.Jt.coeffs().setZero();
  out.lcp_block.M = direction.lcp_block_M;
  out.lcp_block.q = direction.lcp_block_q;
  std::vector<int> block(world.bodies.size(), -1);
  for (std::size_t k = 0; k < s.bodies.size(); ++k) block[s.bodies[k]] = static_cast<int>(k);
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    const RigidBody& b = world.bodies[s.bodies[k]];
    const WorldGradient::Body& db = direction.bodies[s.bodies[k]];
    const Index j = static_cast<Index>(3 * k);
    const double dm = -db.mass / (b.mass * b.mass), di = -db.inertia / (b.inertia * b.inertia);  // d(1/m), d(1/I)
    out.minv.segment<3>(j) << dm, dm, di;
    const Vec3 u = applied.empty() ? Vec3::Zero() : applied[s.bodies[k]];
    out.v_star.segment<3>(j) << dt * u.x() * dm, dt * u.y() * dm, dt * u.z() * di;
    out.v_star.segment<3>(j) += db.velocity_residual * velocity_residual_features(b);
  }
  for (Index f = 0; f < s.num_friction(); ++f) out.mu(f) = direction.contact_mu[s.contacts[s.friction_rows[f]]];
  out.compliance.resize(s.num_contacts());
  out.erp.resize(s.num_contacts());
  for (Index i = 0; i < s.num_contacts(); ++i) {
    out.compliance(i) = direction.contact_compliance[static_cast<std::size_t>(s.contacts[i])];
    out.erp(i) = direction.contact_erp[static_cast<std::size_t>(s.contacts[i])];
  }
  std::vector<Index> friction_row(static_cast<std::size_t>(s.num_contacts()), -1);
  for (Index f = 0; f < s.num_friction(); ++f) friction_row[static_cast<std::size_t>(s.friction_rows[f])] = f;
  for (Index i = 0; i < s.num_contacts(); ++i) {
    const Contact& c = contacts[s.contacts[i]];
    if (block[c.body_a] < 0 || (world.is_dynamic(c.body_b) && block[c.body_b] < 0))
      throw InputError("contact_system_tangent: s.contacts[" + std::to_string(i) + "]: a body is not in the island");
    const LocalContact lc = local_geometry(world, c);
    const Derivatives dir = gather(c, lc.na, lc.directions, direction);
    const Vec2AD& n = lc.geo.normal;
    const Vec2AD t(-n.y(), n.x());
    const Index fr = friction_row[static_cast<std::size_t>(i)];
    out.phi(i) = lc.geo.gap.derivatives().dot(dir) + direction.bodies[c.body_a].gap_offset +
                 (c.body_b >= 0 ? direction.bodies[c.body_b].gap_offset : 0.0);
    const Vec2AD ra = lc.geo.point - world.bodies[c.body_a].pose.head<2>().cast<AD>();
    push_row(out.Jn, i, block[c.body_a], n, ra, 1.0, dir);
    if (fr >= 0) push_row(out.Jt, fr, block[c.body_a], t, ra, 1.0, dir);
    if (world.is_dynamic(c.body_b)) {
      const Vec2AD rb = lc.geo.point - world.bodies[c.body_b].pose.head<2>().cast<AD>();
      push_row(out.Jn, i, block[c.body_b], n, rb, -1.0, dir);
      if (fr >= 0) push_row(out.Jt, fr, block[c.body_b], t, rb, -1.0, dir);
    }
  }
  return out;
}

}  // namespace lcprelax
