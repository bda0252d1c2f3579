// Contacts recomputed from their recorded features (see contact/contact_features.hpp).
#include <lcprelax/contact/contact_features.hpp>
#include <lcprelax/contact/convex_shape.hpp>
#include <lcprelax/core/errors.hpp>

#include <sstream>

namespace lcprelax {
namespace {

int vertex_count(const World& world, const Contact& c) {
  if (c.static_kind == Contact::StaticKind::segment) return 2;
  return static_cast<int>(world.bodies[c.body_b].shape.vertices.size());
}

}  // namespace

std::string contact_feature_error(const World& world, const Contact& c) {
  using Kind = Contact::Feature::Kind;
  const Contact::Feature& f = c.feature;
  const int nbodies = static_cast<int>(world.bodies.size());
  if (c.body_a < 0 || c.body_a >= nbodies) return "body_a out of range";
  if (f.kind == Kind::none) return "feature: not recorded (kind none)";
  const int na = static_cast<int>(world.bodies[c.body_a].shape.vertices.size());
  if (c.static_kind == Contact::StaticKind::half_plane) {
    if (c.static_index < 0 || c.static_index >= static_cast<int>(world.half_planes.size()))
      return "static_index: no such half-plane";
    if (f.kind != Kind::plane_vertex) return "feature: a half-plane contact must be plane_vertex";
    if (f.vertex < 0 || f.vertex >= na) return "feature.vertex: out of range";
    return {};
  }
  if (c.static_kind == Contact::StaticKind::segment) {
    if (c.static_index < 0 || c.static_index >= static_cast<int>(world.segments.size()))
      return "static_index: no such segment";
  } else if (c.body_b < 0 || c.body_b >= nbodies || c.body_b == c.body_a) {
    return "body_b out of range";
  }
  if (f.kind == Kind::plane_vertex) return "feature: plane_vertex needs a half-plane";
  const int nb = vertex_count(world, c);
  const int nf = f.face_on_a ? na : nb, no = f.face_on_a ? nb : na;
  if (f.edge < 0 || f.edge >= nf) return "feature.edge: out of range";
  if (f.vertex < 0 || f.vertex >= no) return "feature.vertex: out of range";
  if (f.kind == Kind::clipped_edge && f.side != 0 && f.side != 1) return "feature.side: must be 0 or 1";
  if (f.kind == Kind::closest && (f.side < -1 || f.side > 1)) return "feature.side: must be -1, 0 or 1";
  return {};
}

std::string contact_features_error(const World& world, const std::vector<Contact>& contacts) {
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const std::string e = contact_feature_error(world, contacts[i]);
    if (!e.empty()) {
      std::ostringstream os;
      os << "contacts[" << i << "]: " << e;
      return os.str();
    }
  }
  return {};
}

void refresh_contacts(const World& world, std::vector<Contact>& contacts) {
  const std::string error = contact_features_error(world, contacts);
  if (!error.empty()) throw InputError("refresh_contacts: " + error);
  std::vector<ConvexShape> shapes(world.bodies.size());
  std::vector<bool> made(world.bodies.size(), false);
  auto shape_of = [&](int b) -> const ConvexShape& {
    if (!made[b]) shapes[b] = make_shape(world.bodies[b]), made[b] = true;
    return shapes[b];
  };
  for (Contact& c : contacts) {
    const ConvexShape& a = shape_of(c.body_a);
    FeatureGeometry<double> g;
    if (c.static_kind == Contact::StaticKind::half_plane) {
      const HalfPlane& hp = world.half_planes[c.static_index];
      g = feature_geometry<double>(c.feature, a.vertices.data(), hp.normal, hp.offset);
    } else {
      const ConvexShape b = c.static_kind == Contact::StaticKind::segment ? make_shape(world.segments[c.static_index])
                                                                          : shape_of(c.body_b);
      g = feature_geometry<double>(c.feature, a.vertices.data(), a.count, b.vertices.data(), b.count);
    }
    c.point = g.point;
    c.normal = g.normal;
    c.gap = g.gap;
  }
}

}  // namespace lcprelax
