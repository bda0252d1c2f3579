// find_contacts: broad phase, narrow phase, canonical ordering (see contact/collision.hpp).
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/contact/broad_phase.hpp>
#include <lcprelax/contact/convex_shape.hpp>
#include <lcprelax/contact/narrow_phase.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

namespace lcprelax {

std::string CollisionSettings::validation_error() const {
  if (!(margin >= 0.0) || !std::isfinite(margin)) {
    std::ostringstream os;
    os << "margin = " << margin << " must be finite and >= 0";
    return os.str();
  }
  return {};
}

bool contact_less(const Contact& l, const Contact& r) {
  return std::make_tuple(l.body_a, l.body_b, static_cast<int>(l.static_kind), l.static_index, l.point.x(),
                         l.point.y()) < std::make_tuple(r.body_a, r.body_b, static_cast<int>(r.static_kind),
                                                        r.static_index, r.point.x(), r.point.y());
}

std::vector<Contact> find_contacts(const World& world, const CollisionSettings& settings) {
  const std::string error = settings.validation_error();
  if (!error.empty()) throw InputError("CollisionSettings: " + error);
  const double margin = settings.margin;

  const BroadPhasePairs pairs = broad_phase(world, margin);

  const int n = static_cast<int>(world.bodies.size());
  std::vector<ConvexShape> shapes(n);
  for (int i = 0; i < n; ++i) shapes[i] = make_shape(world.bodies[i]);
  std::vector<ConvexShape> segments;
  segments.reserve(world.segments.size());
  for (const Segment& s : world.segments) segments.push_back(make_shape(s));

  std::vector<Contact> contacts;
  contacts.reserve(2 * (pairs.body_pairs.size() + pairs.shape_pairs.size()));
  auto emit = [&](const Manifold& m, int a, int b, Contact::StaticKind kind, int index, int material_b) {
    for (int k = 0; k < m.count; ++k) {
      Contact c;
      c.body_a = a;
      c.body_b = b;
      c.static_kind = kind;
      c.static_index = index;
      c.point = m.points[k].point;
      c.normal = m.normal;
      c.gap = m.points[k].gap;
      const int material_a = world.bodies[a].material;
      c.mu = world.friction.mu(material_a, material_b);
      c.compliance = world.friction.compliance(material_a, material_b);
      c.erp = world.friction.erp(material_a, material_b);
      c.feature = m.points[k].feature;
      contacts.push_back(c);
    }
  };

  for (const BodyPair& p : pairs.body_pairs) {
    // a is dynamic: the lower index unless that one is static.
    const int a = world.bodies[p.a].is_static ? p.b : p.a;
    const int b = a == p.a ? p.b : p.a;
    emit(collide(shapes[a], shapes[b], margin), a, b, Contact::StaticKind::none, -1, world.bodies[b].material);
  }
  for (const ShapePair& p : pairs.shape_pairs) {
    if (p.kind == Contact::StaticKind::half_plane) {
      const HalfPlane& hp = world.half_planes[p.index];
      emit(collide(shapes[p.body], hp, margin), p.body, -1, p.kind, p.index, hp.material);
    } else {
      emit(collide(shapes[p.body], segments[p.index], margin), p.body, -1, p.kind, p.index,
           world.segments[p.index].material);
    }
  }
  std::stable_sort(contacts.begin(), contacts.end(), contact_less);
  return contacts;
}

}  // namespace lcprelax
