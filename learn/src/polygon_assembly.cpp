// Contact data of a polygon sample and its derivatives with respect to θ (polygon_assembly.hpp).
#include <lcprelax/contact/convex_shape.hpp>
#include <lcprelax/contact/narrow_phase.hpp>
#include <lcprelax/learn/polygon_assembly.hpp>
#include <lcprelax/core/errors.hpp>

#include <algorithm>
#include <cmath>

namespace lcprelax::learn {
namespace {

double cross(const Vec2& a, const Vec2& c) { return a.x() * c.y() - a.y() * c.x(); }

Vec3 free_velocity(const PolygonModel& m, const PolygonTransition& s, const PolygonDataset& d) {
  return s.v + d.dt * Vec3(d.gravity.x() + s.u.x() / m.mass, d.gravity.y() + s.u.y() / m.mass, s.u.z() / m.inertia);
}

}  // namespace

void PolygonContactData::set_zero(Index nc) {
  Jn.setZero(nc, 3);
  Jt.setZero(nc, 3);
  phi.setZero(nc);
  mu.setZero(nc);
  minv.setZero(3);
  v_star.setZero(3);
}

double polygon_speculative_margin(const PolygonModel& model, const PolygonTransition& sample,
                                  const PolygonDataset& data) {
  const double r = polygon_radius(model.shape);
  double fastest = 0.0;
  for (const Vec3& v : {sample.v, free_velocity(model, sample, data)})
    fastest = std::max(fastest, v.head<2>().norm() + std::abs(v(2)) * r);
  return data.margin + 2.0 * fastest * data.dt;
}

std::vector<int> polygon_active_vertices(const PolygonModel& model, const PolygonTransition& sample,
                                         const PolygonDataset& data, double extra_margin) {
  RigidBody body;
  body.shape = model.shape;
  body.pose = sample.q;
  const ConvexShape shape = make_shape(body);
  const HalfPlane ground = ground_half_plane(model.ground_height, model.ground_angle);
  const Manifold m = collide(shape, ground, polygon_speculative_margin(model, sample, data));
  std::vector<int> vertices;
  for (int k = 0; k < m.count; ++k) {
    // The point is vertex − ½φn: find the vertex it came from.
    int best = -1;
    double best_distance = INFINITY;
    for (int i = 0; i < shape.count; ++i) {
      const Vec2 w = shape.vertices[static_cast<std::size_t>(i)];
      const double g = ground.normal.dot(w) - ground.offset;
      const double distance = (w - 0.5 * g * ground.normal - m.points[static_cast<std::size_t>(k)].point).norm();
      if (distance < best_distance) best = i, best_distance = distance;
    }
    if (std::find(vertices.begin(), vertices.end(), best) == vertices.end()) vertices.push_back(best);
  }
  if (extra_margin > 0.0) {
    const double limit = polygon_speculative_margin(model, sample, data) + extra_margin;
    for (int i = 0; i < shape.count; ++i) {
      const double g = ground.normal.dot(shape.vertices[static_cast<std::size_t>(i)]) - ground.offset;
      if (g <= limit && std::find(vertices.begin(), vertices.end(), i) == vertices.end()) vertices.push_back(i);
    }
  }
  std::sort(vertices.begin(), vertices.end());
  return vertices;
}

void assemble_polygon(const PolygonModel& model, const std::vector<int>& vertices, const PolygonTransition& sample,
                      const PolygonDataset& data, PolygonAssembly& out) {
  const Index nc = static_cast<Index>(vertices.size());
  const Index nv = static_cast<Index>(model.shape.vertices.size());
  const PolygonLayout layout{nv};
  out.vertices = vertices;
  out.value.set_zero(nc);
  out.tangent.resize(static_cast<std::size_t>(layout.size()));
  for (PolygonContactData& t : out.tangent) t.set_zero(nc);

  // Mass, inertia and the free velocity.
  const double m = model.mass, I = model.inertia, dt = data.dt;
  PolygonContactData& v = out.value;
  v.minv << 1.0 / m, 1.0 / m, 1.0 / I;
  v.v_star = free_velocity(model, sample, data);
  PolygonContactData& tm = out.tangent[PolygonLayout::kMass];
  tm.minv << -1.0 / (m * m), -1.0 / (m * m), 0.0;
  tm.v_star << -dt * sample.u.x() / (m * m), -dt * sample.u.y() / (m * m), 0.0;
  PolygonContactData& ti = out.tangent[PolygonLayout::kInertia];
  ti.minv << 0.0, 0.0, -1.0 / (I * I);
  ti.v_star << 0.0, 0.0, -dt * sample.u.z() / (I * I);

  // Contacts.
  const double alpha = model.ground_angle, h = model.ground_height;
  const Vec2 n(-std::sin(alpha), std::cos(alpha)), t(-n.y(), n.x());
  const double offset = h * std::cos(alpha);
  const double c = std::cos(sample.q.z()), s = std::sin(sample.q.z());
  const Vec2 x = sample.q.head<2>();
  PolygonContactData& tmu = out.tangent[PolygonLayout::kMu];
  PolygonContactData& th = out.tangent[static_cast<std::size_t>(layout.ground_height())];
  PolygonContactData& ta = out.tangent[static_cast<std::size_t>(layout.ground_angle())];
  for (Index k = 0; k < nc; ++k) {
    const int i = vertices[static_cast<std::size_t>(k)];
    if (i < 0 || i >= nv) throw InputError("assemble_polygon: active vertex index out of range");
    const Vec2 b = model.shape.vertices[static_cast<std::size_t>(i)];
    const Vec2 rb(c * b.x() - s * b.y(), s * b.x() + c * b.y());  // R b
    const double phi = n.dot(x + rb) - offset;
    v.phi(k) = phi;
    v.mu(k) = model.mu;
    v.Jn.row(k) << n.x(), n.y(), cross(rb, n);
    v.Jt.row(k) << t.x(), t.y(), cross(rb, t) - 0.5 * phi;
    tmu.mu(k) = 1.0;
    // Vertex coordinates: d(Rb)/db_x = (c, s), d(Rb)/db_y = (−s, c).
    const Vec2 dr[2] = {Vec2(c, s), Vec2(-s, c)};
    const Index idx[2] = {layout.vertex_x(i), layout.vertex_y(i)};
    for (int a = 0; a < 2; ++a) {
      PolygonContactData& tv = out.tangent[static_cast<std::size_t>(idx[a])];
      const double dphi = n.dot(dr[a]);
      tv.phi(k) = dphi;
      tv.Jn(k, 2) = cross(dr[a], n);
      tv.Jt(k, 2) = cross(dr[a], t) - 0.5 * dphi;
    }
    // Ground height.
    const double dphi_h = -std::cos(alpha);
    th.phi(k) = dphi_h;
    th.Jt(k, 2) = -0.5 * dphi_h;
    // Ground angle.
    const double dphi_a = t.dot(x + rb) + h * std::sin(alpha);
    ta.phi(k) = dphi_a;
    ta.Jn.row(k) << t.x(), t.y(), cross(rb, t);
    ta.Jt.row(k) << -n.x(), -n.y(), -cross(rb, n) - 0.5 * dphi_a;
  }
}

ContactSystem to_contact_system(const PolygonContactData& d) {
  ContactSystem s;
  const Index nc = d.num_contacts();
  s.bodies = {0};
  s.contacts.resize(static_cast<std::size_t>(nc));
  s.friction_rows.resize(static_cast<std::size_t>(nc));
  for (Index k = 0; k < nc; ++k) s.contacts[static_cast<std::size_t>(k)] = s.friction_rows[static_cast<std::size_t>(k)] = static_cast<int>(k);
  s.minv = d.minv;
  s.Jn = d.Jn.sparseView();
  s.Jt = d.Jt.sparseView();
  s.Jn.makeCompressed();
  s.Jt.makeCompressed();
  s.phi = d.phi;
  s.mu = d.mu;
  s.v_star = d.v_star;
  return s;
}

}  // namespace lcprelax::learn
