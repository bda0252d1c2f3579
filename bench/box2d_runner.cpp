// Box2D 2.4 side of the peer comparison: an lcprelax Scene converted to a b2World
// (conventions and units in box2d_runner.hpp).
#include "box2d_runner.hpp"

#include <lcprelax/core/errors.hpp>

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace lcprelax::bench {
namespace {

/// The polygon moved inwards by r (each edge along its inward normal), or empty when an
/// edge would vanish, flip or become shorter than `min_edge` (vertices counter-clockwise).
std::vector<Vec2> offset_inwards(const std::vector<Vec2>& v, double r, double min_edge) {
  const std::size_t n = v.size();
  std::vector<Vec2> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    // vertex i is shared by edge (i−1 → i) and edge (i → i+1)
    const Vec2& p0 = v[(i + n - 1) % n];
    const Vec2& p1 = v[i];
    const Vec2& p2 = v[(i + 1) % n];
    const Vec2 e0 = (p1 - p0).normalized(), e1 = (p2 - p1).normalized();
    const Vec2 in0(-e0.y(), e0.x()), in1(-e1.y(), e1.x());  // inward normals (CCW polygon)
    // solve p1 + r·in0 + s·e0 = p1 + r·in1 + t·e1 for the corner of the two offset lines
    const double cross = e0.x() * e1.y() - e0.y() * e1.x();
    if (cross <= 1e-12) return {};
    const Vec2 d = r * (in1 - in0);
    const double s = (d.x() * e1.y() - d.y() * e1.x()) / cross;
    out[i] = p1 + r * in0 + s * e0;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 old_edge = v[(i + 1) % n] - v[i], new_edge = out[(i + 1) % n] - out[i];
    if (new_edge.dot(old_edge) <= 0 || new_edge.norm() < min_edge) return {};
  }
  return out;
}

}  // namespace

struct Box2dWorld::Impl {
  Scene scene;
  Box2dSettings settings;
  b2World world{b2Vec2(0.0f, -9.81f)};
  std::vector<b2Body*> bodies;  // same order as scene.world.bodies
  int unshrunk = 0;
};

Box2dWorld::Box2dWorld(const Scene& scene, Box2dSettings settings) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.scene = scene;
  m.settings = settings;
  const World& w = scene.world;
  if (!w.friction.pairs.empty()) throw InputError("Box2dWorld: friction tables with material pairs are not supported");
  const float mu = static_cast<float>(w.friction.default_mu);
  m.world.SetGravity(b2Vec2(static_cast<float>(w.gravity.x()), static_cast<float>(w.gravity.y())));
  m.world.SetAllowSleeping(settings.allow_sleep);

  // scene extent, for the length of the half-plane edges
  Vec2 lo(0, 0), hi(0, 0);
  for (const RigidBody& b : w.bodies) lo = lo.cwiseMin(b.pose.head<2>()), hi = hi.cwiseMax(b.pose.head<2>());
  for (const Segment& s : w.segments) lo = lo.cwiseMin(s.a).cwiseMin(s.b), hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  const Vec2 centre = 0.5 * (lo + hi);
  const double half_length = 10.0 * ((hi - lo).norm() + 10.0);
  const double skin = b2_polygonRadius;

  b2BodyDef ground_def;
  b2Body* ground = m.world.CreateBody(&ground_def);
  auto add_edge = [&](const Vec2& a, const Vec2& b) {
    b2EdgeShape edge;
    edge.SetTwoSided(b2Vec2(static_cast<float>(a.x()), static_cast<float>(a.y())),
                     b2Vec2(static_cast<float>(b.x()), static_cast<float>(b.y())));
    b2FixtureDef f;
    f.shape = &edge;
    f.friction = mu;
    f.restitution = 0.0f;
    ground->CreateFixture(&f);
  };
  for (const HalfPlane& h : w.half_planes) {
    const Vec2 n = h.normal.normalized(), t(n.y(), -n.x());
    const double c = h.offset - (settings.shrink_by_skin ? skin : 0.0);
    const Vec2 foot = centre + (c - n.dot(centre)) * n;  // the point of the line nearest the scene
    add_edge(foot - half_length * t, foot + half_length * t);
  }
  for (const Segment& s : w.segments) add_edge(s.a, s.b);

  for (const RigidBody& rb : w.bodies) {
    const std::size_t nv = rb.shape.vertices.size();
    if (nv > static_cast<std::size_t>(b2_maxPolygonVertices))
      throw InputError("Box2dWorld: a polygon has " + std::to_string(nv) + " vertices, Box2D allows at most " +
                       std::to_string(b2_maxPolygonVertices));
    std::vector<Vec2> verts = rb.shape.vertices;
    if (settings.shrink_by_skin) {
      std::vector<Vec2> shrunk = offset_inwards(verts, skin, 0.003);
      if (shrunk.empty())
        ++m.unshrunk;
      else
        verts = std::move(shrunk);
    }
    std::vector<b2Vec2> pts;
    for (const Vec2& p : verts) pts.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    b2PolygonShape shape;
    shape.Set(pts.data(), static_cast<int32>(pts.size()));

    b2BodyDef def;
    def.type = rb.is_static ? b2_staticBody : b2_dynamicBody;
    def.position.Set(static_cast<float>(rb.pose.x()), static_cast<float>(rb.pose.y()));
    def.angle = static_cast<float>(rb.pose.z());
    def.linearVelocity.Set(static_cast<float>(rb.velocity.x()), static_cast<float>(rb.velocity.y()));
    def.angularVelocity = static_cast<float>(rb.velocity.z());
    b2Body* body = m.world.CreateBody(&def);
    b2FixtureDef f;
    f.shape = &shape;
    f.density = 1.0f;  // replaced by SetMassData below
    f.friction = mu;
    f.restitution = 0.0f;
    body->CreateFixture(&f);
    if (!rb.is_static) {
      b2MassData md;
      md.mass = static_cast<float>(rb.mass);
      md.center.SetZero();
      md.I = static_cast<float>(rb.inertia);
      body->SetMassData(&md);
    }
    m.bodies.push_back(body);
  }
}

Box2dWorld::~Box2dWorld() = default;

void Box2dWorld::step() {
  impl_->world.Step(static_cast<float>(impl_->scene.settings.dt), impl_->settings.velocity_iterations,
                    impl_->settings.position_iterations);
}

World Box2dWorld::world() const {
  World w = impl_->scene.world;
  for (std::size_t i = 0; i < impl_->bodies.size(); ++i) {
    const b2Body* b = impl_->bodies[i];
    w.bodies[i].pose = Vec3(b->GetPosition().x, b->GetPosition().y, b->GetAngle());
    w.bodies[i].velocity = Vec3(b->GetLinearVelocity().x, b->GetLinearVelocity().y, b->GetAngularVelocity());
  }
  return w;
}

double Box2dWorld::max_penetration() const {
  double p = 0.0;
  for (const b2Contact* c = impl_->world.GetContactList(); c; c = c->GetNext()) {
    if (!c->IsTouching() || !c->IsEnabled()) continue;
    b2WorldManifold wm;
    c->GetWorldManifold(&wm);
    for (int k = 0; k < c->GetManifold()->pointCount; ++k) p = std::max(p, -static_cast<double>(wm.separations[k]));
  }
  return p;
}

int Box2dWorld::contact_points() const {
  int n = 0;
  for (const b2Contact* c = impl_->world.GetContactList(); c; c = c->GetNext())
    if (c->IsTouching()) n += c->GetManifold()->pointCount;
  return n;
}

int Box2dWorld::unshrunk_polygons() const { return impl_->unshrunk; }

}  // namespace lcprelax::bench
