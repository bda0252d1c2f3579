// Islands (union–find) and contact Jacobian assembly (contact_system.hpp).
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/world/normal_softness.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace lcprelax {
namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// Appends the 3 entries of a row for body block k: direction d at lever arm r.
void add_row(std::vector<Triplet>& t, Index row, Index block, const Vec2& d, const Vec2& r, double sign) {
  t.emplace_back(row, 3 * block, sign * d.x());
  t.emplace_back(row, 3 * block + 1, sign * d.y());
  t.emplace_back(row, 3 * block + 2, sign * (r.x() * d.y() - r.y() * d.x()));
}

}  // namespace

std::vector<Island> find_islands(const World& world, const std::vector<Contact>& contacts) {
  const int nb = static_cast<int>(world.bodies.size());
  std::vector<int> parent(nb);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<bool> touched(nb, false);
  for (const Contact& c : contacts) {
    if (!world.is_dynamic(c.body_a))
      throw InputError("contact with body_a = " + std::to_string(c.body_a) + " that is not a dynamic body");
    touched[c.body_a] = true;
    if (world.is_dynamic(c.body_b)) {
      touched[c.body_b] = true;
      const int ra = find_root(parent, c.body_a), rb = find_root(parent, c.body_b);
      if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  std::vector<int> island_of(nb, -1);
  std::vector<Island> islands;
  for (int b = 0; b < nb; ++b) {
    if (!touched[b]) continue;
    const int root = find_root(parent, b);
    if (island_of[root] < 0) {
      island_of[root] = static_cast<int>(islands.size());
      islands.emplace_back();
    }
    islands[island_of[root]].bodies.push_back(b);
  }
  for (int c = 0; c < static_cast<int>(contacts.size()); ++c)
    islands[island_of[find_root(parent, contacts[c].body_a)]].contacts.push_back(c);
  return islands;
}

Eigen::Vector4d velocity_residual_features(const RigidBody& body) {
  return Eigen::Vector4d(body.velocity.x(), body.velocity.y(), body.velocity.z(), 1.0);
}

bool has_velocity_residual(const RigidBody& body) { return (body.velocity_residual.array() != 0.0).any(); }

Vec3 velocity_residual_term(const RigidBody& body) { return body.velocity_residual * velocity_residual_features(body); }

double contact_gap_offset(const World& world, const Contact& c) {
  const double a = world.bodies[c.body_a].gap_offset;
  return c.body_b >= 0 ? a + world.bodies[c.body_b].gap_offset : a;
}

ContactKey contact_key(const std::vector<Contact>& contacts, std::size_t i) {
  auto head = [&](std::size_t k) {
    const Contact& c = contacts[k];
    return std::array<int, 4>{c.body_a, c.body_b, static_cast<int>(c.static_kind), c.static_index};
  };
  const std::array<int, 4> h = head(i);
  int ordinal = 0;
  for (std::size_t k = i; k > 0 && head(k - 1) == h; --k) ++ordinal;
  return {h[0], h[1], h[2], h[3], ordinal};
}

std::uint64_t contact_identity(const ContactKey& key) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (int v : key) h = (h ^ static_cast<std::uint32_t>(v)) * 0x100000001b3ULL;
  return h;
}

ContactSystem assemble_contact_system(const World& world, const std::vector<Contact>& contacts,
                                      const Island& island, double dt, const std::vector<Vec3>& applied) {
  if (!applied.empty() && applied.size() != world.bodies.size())
    throw InputError("applied forces: one (fx, fy, torque) per body expected");
  ContactSystem s;
  s.bodies = island.bodies;
  s.contacts = island.contacts;
  s.lcp_block = world.lcp_block;
  const Index nb = static_cast<Index>(s.bodies.size());
  std::vector<int> block(world.bodies.size(), -1);
  s.minv.resize(3 * nb);
  s.v_star.resize(3 * nb);
  for (Index k = 0; k < nb; ++k) {
    const RigidBody& b = world.bodies[s.bodies[k]];
    block[s.bodies[k]] = static_cast<int>(k);
    s.minv.segment<3>(3 * k) << 1.0 / b.mass, 1.0 / b.mass, 1.0 / b.inertia;
    Vec3 f(b.mass * world.gravity.x(), b.mass * world.gravity.y(), 0.0);
    if (!applied.empty()) f += applied[s.bodies[k]];
    s.v_star.segment<3>(3 * k) = b.velocity + dt * s.minv.segment<3>(3 * k).cwiseProduct(f);
    if (has_velocity_residual(b)) s.v_star.segment<3>(3 * k) += velocity_residual_term(b);
  }
  const Index nc = s.num_contacts();
  s.ids.resize(static_cast<std::size_t>(nc));
  for (Index i = 0; i < nc; ++i)
    s.ids[static_cast<std::size_t>(i)] = contact_identity(contact_key(contacts, static_cast<std::size_t>(s.contacts[i])));
  s.phi.resize(nc);
  std::vector<Triplet> tn, tt;
  std::vector<double> mu;
  bool soft = false;  // the per-contact softness vectors stay empty for a rigid island
  for (Index i = 0; i < nc && !soft; ++i) {
    const Contact& c = contacts[s.contacts[i]];
    soft = c.compliance != 0.0 || c.erp != 0.0;
  }
  if (soft) {
    s.compliance.resize(nc);
    s.erp.resize(nc);
  }
  for (Index i = 0; i < nc; ++i) {
    const Contact& c = contacts[s.contacts[i]];
    if (soft) s.compliance(i) = c.compliance, s.erp(i) = c.erp;
    if (block[c.body_a] < 0) throw InputError("contact body_a is not in the island");
    const double offset = contact_gap_offset(world, c);
    s.phi(i) = offset == 0.0 ? c.gap : c.gap + offset;
    const Vec2 n = c.normal, t(-n.y(), n.x());
    const Vec2 ra = c.point - world.bodies[c.body_a].pose.head<2>();
    const bool b_dynamic = world.is_dynamic(c.body_b);
    const Vec2 rb = b_dynamic ? Vec2(c.point - world.bodies[c.body_b].pose.head<2>()) : Vec2::Zero();
    add_row(tn, i, block[c.body_a], n, ra, 1.0);
    if (b_dynamic) add_row(tn, i, block[c.body_b], n, rb, -1.0);
    if (c.mu > 0) {
      const Index f = static_cast<Index>(s.friction_rows.size());
      s.friction_rows.push_back(static_cast<int>(i));
      mu.push_back(c.mu);
      add_row(tt, f, block[c.body_a], t, ra, 1.0);
      if (b_dynamic) add_row(tt, f, block[c.body_b], t, rb, -1.0);
    }
  }
  s.Jn.resize(nc, 3 * nb);
  s.Jn.setFromTriplets(tn.begin(), tn.end());
  s.Jt.resize(s.num_friction(), 3 * nb);
  s.Jt.setFromTriplets(tt.begin(), tt.end());
  s.mu = Eigen::Map<const Vector>(mu.data(), static_cast<Index>(mu.size()));
  return s;
}

bool has_normal_softness(const ContactSystem& s) {
  return (s.compliance.size() > 0 && (s.compliance.array() != 0.0).any()) ||
         (s.erp.size() > 0 && (s.erp.array() != 0.0).any());
}

Vector normal_gap_rate(const ContactSystem& s, double dt) {
  Vector rate = s.phi.cwiseMax(0.0);
  if (s.erp.size() > 0) rate += s.erp.cwiseProduct(s.phi.cwiseMin(0.0));
  return rate / dt;
}

std::string normal_softness_error(const ContactSystem& s) {
  const Index nc = s.num_contacts();
  if (s.compliance.size() != 0 && s.compliance.size() != nc) return "compliance: one entry per contact or none";
  if (s.erp.size() != 0 && s.erp.size() != nc) return "erp: one entry per contact or none";
  for (Index i = 0; i < std::max(s.compliance.size(), s.erp.size()); ++i) {
    std::string e = normal_softness_value_error(s.compliance.size() ? s.compliance(i) : 0.0, s.erp.size() ? s.erp(i) : 0.0);
    if (!e.empty()) return e;
  }
  return {};
}

}  // namespace lcprelax
