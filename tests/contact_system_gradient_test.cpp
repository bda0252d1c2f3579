// accumulate_world_gradient (models/contact_system_gradient.hpp) against central finite
// differences. For a random cotangent ct per island, L(world) = Σ_islands ⟨ct, data(world)⟩
// over Jn, Jt (on their patterns), φ, μ, M⁻¹ and v*, with the contact list and its features
// held fixed (refresh_contacts at the perturbed world, then assemble_contact_system), is
// differentiated with respect to every primitive: the vertices of every body (static ones
// too), every dynamic body's mass and inertia, half-plane normals and offsets, segment end
// points and every contact's μ. Checked on a settled 20-body pile (≥ 60 contacts) and on
// small two-shape worlds covering every feature kind and side. The forward mode
// (contact_system_tangent) is checked on the pile made soft, where the per-contact normal
// compliance and erp enter the data, the tangent and the adjoint identity too.
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/contact/contact_features.hpp>
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/contact_system_gradient.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <set>
#include <string>

namespace lcprelax {
namespace {

using Kind = Contact::Feature::Kind;
constexpr double kPi = 3.14159265358979323846;

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
}

std::vector<ContactSystem> assemble_all(const World& world, const std::vector<Contact>& contacts,
                                        const std::vector<Island>& islands, double dt, const std::vector<Vec3>& applied) {
  std::vector<ContactSystem> s;
  for (const Island& island : islands) s.push_back(assemble_contact_system(world, contacts, island, dt, applied));
  return s;
}

// Σ ct·(plus − minus) entry by entry (no cancellation between large constant terms);
// plus and minus must share their sparsity patterns.
double inner_difference(const ContactSystemCotangent& ct, const ContactSystem& plus, const ContactSystem& minus) {
  double sum = 0.0;
  for (const auto* pair : {&plus.Jn, &plus.Jt}) {
    const SparseMatrix& p = *pair;
    const SparseMatrix& m = pair == &plus.Jn ? minus.Jn : minus.Jt;
    const SparseMatrix& c = pair == &plus.Jn ? ct.Jn : ct.Jt;
    EXPECT_EQ(p.nonZeros(), m.nonZeros());
    for (Index j = 0; j < p.outerSize(); ++j) {
      SparseMatrix::InnerIterator ip(p, j), im(m, j);
      for (; ip && im; ++ip, ++im) {
        EXPECT_EQ(ip.row(), im.row());
        sum += c.coeff(ip.row(), j) * (ip.value() - im.value());
      }
    }
  }
  sum += ct.phi.dot(plus.phi - minus.phi) + ct.mu.dot(plus.mu - minus.mu);
  sum += ct.minv.dot(plus.minv - minus.minv) + ct.v_star.dot(plus.v_star - minus.v_star);
  if (plus.compliance.size() > 0)  // soft islands only (rigid ones carry no softness vectors)
    sum += ct.compliance.dot(plus.compliance - minus.compliance) + ct.erp.dot(plus.erp - minus.erp);
  return sum;
}

ContactSystemCotangent random_cotangent(const ContactSystem& s, std::mt19937_64& rng) {
  ContactSystemCotangent ct;
  ct.set_zero(s);
  for (Index k = 0; k < ct.Jn.nonZeros(); ++k) ct.Jn.valuePtr()[k] = uniform(rng, -1.0, 1.0);
  for (Index k = 0; k < ct.Jt.nonZeros(); ++k) ct.Jt.valuePtr()[k] = uniform(rng, -1.0, 1.0);
  for (Vector* v : {&ct.phi, &ct.mu, &ct.minv, &ct.v_star, &ct.compliance, &ct.erp})
    for (Index k = 0; k < v->size(); ++k) (*v)(k) = uniform(rng, -1.0, 1.0);
  return ct;
}

struct Check {
  double max_error = 0.0;  // max over entries of |fd − an| / max(|an|, 1e-3·max|an| of the kind, 1e-9)
  int entries = 0;
  std::string worst;
};

// Checks every primitive's derivative against central differences; returns the report.
Check check_gradient(const World& world, const std::vector<Contact>& contacts, double dt, const std::vector<Vec3>& applied,
                     std::mt19937_64& rng) {
  const std::vector<Island> islands = find_islands(world, contacts);
  const std::vector<ContactSystem> systems = assemble_all(world, contacts, islands, dt, applied);
  std::vector<ContactSystemCotangent> cts;
  for (const ContactSystem& s : systems) cts.push_back(random_cotangent(s, rng));
  WorldGradient g;
  g.set_zero(world, contacts.size());
  for (std::size_t k = 0; k < systems.size(); ++k) accumulate_world_gradient(world, contacts, systems[k], dt, applied, cts[k], g);

  using Perturb = std::function<void(World&, std::vector<Contact>&, double)>;
  auto fd = [&](const Perturb& perturb, double h) {
    World wp = world, wm = world;
    std::vector<Contact> cp = contacts, cm = contacts;
    perturb(wp, cp, h);
    perturb(wm, cm, -h);
    refresh_contacts(wp, cp);
    refresh_contacts(wm, cm);
    const std::vector<ContactSystem> sp = assemble_all(wp, cp, islands, dt, applied);
    const std::vector<ContactSystem> sm = assemble_all(wm, cm, islands, dt, applied);
    double sum = 0.0;
    for (std::size_t k = 0; k < islands.size(); ++k) sum += inner_difference(cts[k], sp[k], sm[k]);
    return sum / (2.0 * h);
  };
  struct Entry {
    std::string name;
    double analytic, numeric;
  };
  std::vector<std::vector<Entry>> kinds(5);  // vertices, mass, inertia, static shapes, μ
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const RigidBody& body = world.bodies[b];
    double radius = 0.0;
    for (const Vec2& v : body.shape.vertices) radius = std::max(radius, v.norm());
    for (std::size_t k = 0; k < body.shape.vertices.size(); ++k)
      for (int d = 0; d < 2; ++d) {
        const double numeric = fd([&](World& w, std::vector<Contact>&, double h) { w.bodies[b].shape.vertices[k](d) += h; },
                                  1e-6 * radius);
        kinds[0].push_back({"body " + std::to_string(b) + " vertex " + std::to_string(k) + "." + std::to_string(d),
                            g.bodies[b].vertices[k](d), numeric});
      }
    if (body.is_static) continue;
    kinds[1].push_back({"body " + std::to_string(b) + " mass", g.bodies[b].mass,
                        fd([&](World& w, std::vector<Contact>&, double h) { w.bodies[b].mass += h; }, 1e-6 * body.mass)});
    kinds[2].push_back({"body " + std::to_string(b) + " inertia", g.bodies[b].inertia,
                        fd([&](World& w, std::vector<Contact>&, double h) { w.bodies[b].inertia += h; }, 1e-6 * body.inertia)});
  }
  for (std::size_t p = 0; p < world.half_planes.size(); ++p) {
    for (int d = 0; d < 2; ++d)
      kinds[3].push_back({"half-plane " + std::to_string(p) + " normal." + std::to_string(d), g.half_plane_normal[p](d),
                          fd([&](World& w, std::vector<Contact>&, double h) { w.half_planes[p].normal(d) += h; }, 1e-6)});
    kinds[3].push_back({"half-plane " + std::to_string(p) + " offset", g.half_plane_offset[p],
                        fd([&](World& w, std::vector<Contact>&, double h) { w.half_planes[p].offset += h; }, 1e-6)});
  }
  for (std::size_t s = 0; s < world.segments.size(); ++s)
    for (int e = 0; e < 2; ++e)
      for (int d = 0; d < 2; ++d)
        kinds[3].push_back({"segment " + std::to_string(s) + " end " + std::to_string(e) + "." + std::to_string(d),
                            g.segment_ends[s][e](d), fd([&](World& w, std::vector<Contact>&, double h) {
                              (e == 0 ? w.segments[s].a : w.segments[s].b)(d) += h;
                            }, 1e-6)});
  for (std::size_t c = 0; c < contacts.size(); ++c)
    if (contacts[c].mu > 0)
      kinds[4].push_back({"contact " + std::to_string(c) + " mu", g.contact_mu[c],
                          fd([&](World&, std::vector<Contact>& cs, double h) { cs[c].mu += h; }, 1e-6)});
  Check check;
  for (const std::vector<Entry>& entries : kinds) {
    double scale = 0.0;
    for (const Entry& e : entries) scale = std::max(scale, std::abs(e.analytic));
    for (const Entry& e : entries) {
      const double error = std::abs(e.numeric - e.analytic) / std::max({std::abs(e.analytic), 1e-3 * scale, 1e-9});
      ++check.entries;
      if (error > check.max_error)
        check.max_error = error,
        check.worst = e.name + ": analytic " + std::to_string(e.analytic) + ", numeric " + std::to_string(e.numeric);
    }
  }
  return check;
}

std::vector<Vec3> random_applied(const World& world, std::mt19937_64& rng) {
  std::vector<Vec3> u(world.bodies.size(), Vec3::Zero());
  for (std::size_t b = 0; b < u.size(); b += 2)
    u[b] = Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -0.1, 0.1)) * world.bodies[b].mass;
  return u;
}

// A 20-body pile settled for 250 steps of 10 ms (simulated once, shared by the tests), with
// one post-stabilization pass: the pile these tests were measured on (with the default 5
// it settles with 59 contacts, one short of the test's 60).
const Simulator& settled_pile() {
  static const Simulator sim = [] {
    PileOptions options;
    options.bodies = 20;
    options.seed = 1;
    Scene scene = make_pile_scene(options);
    scene.settings.post_stabilization_passes = 1;
    Simulator s = make_simulator(scene);
    for (int k = 0; k < 250; ++k) s.step();
    return s;
  }();
  return sim;
}

TEST(ContactSystemGradient, SettledPileMatchesCentralDifferences) {
  const Simulator& sim = settled_pile();
  std::mt19937_64 rng(7);
  const World& world = sim.world();
  const std::vector<Vec3> applied = random_applied(world, rng);
  const StepContacts step = find_step_contacts(world, sim.settings(), applied);
  std::set<int> kinds;
  int ground = 0, walls = 0;
  for (const Contact& c : step.contacts) {
    kinds.insert(static_cast<int>(c.feature.kind));
    ground += c.static_kind == Contact::StaticKind::half_plane;
    walls += c.static_kind == Contact::StaticKind::segment;
  }
  std::printf("pile: %zu contacts (%d ground, %d walls) in %zu islands, %zu feature kinds\n", step.contacts.size(), ground,
              walls, step.islands.size(), kinds.size());
  EXPECT_GT(ground, 0);
  ASSERT_GE(step.contacts.size(), 60u);
  const Check check = check_gradient(world, step.contacts, sim.settings().dt, applied, rng);
  std::printf("pile: %d derivatives, max relative error %.3g (%s)\n", check.entries, check.max_error, check.worst.c_str());
  EXPECT_LE(check.max_error, 1e-6) << check.worst;
}

// Forward mode: contact_system_tangent against central differences along a random direction
// of every primitive at once, and against the reverse mode (⟨ct, T dir⟩ = ⟨g, dir⟩); the
// contacts are made soft (per-contact normal compliance and erp, which the tangent passes
// through and the adjoint accumulates per contact).
TEST(ContactSystemGradient, ForwardModeMatchesCentralDifferencesAndTheAdjoint) {
  const Simulator& sim = settled_pile();
  std::mt19937_64 rng(9);
  const World& world = sim.world();
  const double dt = sim.settings().dt;
  const std::vector<Vec3> applied = random_applied(world, rng);
  std::vector<Contact> contacts = find_step_contacts(world, sim.settings(), applied).contacts;
  for (Contact& c : contacts) c.compliance = uniform(rng, 0.01, 0.1), c.erp = uniform(rng, 0.1, 0.9);
  const std::vector<Island> islands = find_islands(world, contacts);
  WorldGradient dir;
  dir.set_zero(world, contacts.size());
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    for (Vec2& v : dir.bodies[b].vertices) v = Vec2(uniform(rng, -0.1, 0.1), uniform(rng, -0.1, 0.1));
    if (world.bodies[b].is_static) continue;
    dir.bodies[b].mass = uniform(rng, -1, 1) * world.bodies[b].mass;
    dir.bodies[b].inertia = uniform(rng, -1, 1) * world.bodies[b].inertia;
  }
  for (std::size_t p = 0; p < world.half_planes.size(); ++p)
    dir.half_plane_normal[p] = Vec2(uniform(rng, -1, 1), uniform(rng, -1, 1)), dir.half_plane_offset[p] = uniform(rng, -1, 1);
  for (auto& ends : dir.segment_ends)
    for (Vec2& e : ends) e = Vec2(uniform(rng, -1, 1), uniform(rng, -1, 1));
  for (double& m : dir.contact_mu) m = uniform(rng, -1, 1);
  for (double& c : dir.contact_compliance) c = uniform(rng, -0.01, 0.01);
  for (double& e : dir.contact_erp) e = uniform(rng, -0.1, 0.1);

  auto moved = [&](double h, World& w, std::vector<Contact>& cs) {
    w = world, cs = contacts;
    for (std::size_t b = 0; b < w.bodies.size(); ++b) {
      for (std::size_t k = 0; k < w.bodies[b].shape.vertices.size(); ++k) w.bodies[b].shape.vertices[k] += h * dir.bodies[b].vertices[k];
      w.bodies[b].mass += h * dir.bodies[b].mass;
      w.bodies[b].inertia += h * dir.bodies[b].inertia;
    }
    for (std::size_t p = 0; p < w.half_planes.size(); ++p)
      w.half_planes[p].normal += h * dir.half_plane_normal[p], w.half_planes[p].offset += h * dir.half_plane_offset[p];
    for (std::size_t k = 0; k < w.segments.size(); ++k)
      w.segments[k].a += h * dir.segment_ends[k][0], w.segments[k].b += h * dir.segment_ends[k][1];
    for (std::size_t c = 0; c < cs.size(); ++c) {
      cs[c].mu += h * dir.contact_mu[c];
      cs[c].compliance += h * dir.contact_compliance[c];
      cs[c].erp += h * dir.contact_erp[c];
    }
    refresh_contacts(w, cs);
  };
  const double h = 1e-6;
  World wp, wm;
  std::vector<Contact> cp, cm;
  moved(h, wp, cp);
  moved(-h, wm, cm);
  double worst = 0.0, adjoint_worst = 0.0;
  for (const Island& island : islands) {
    const ContactSystem s = assemble_contact_system(world, contacts, island, dt, applied);
    const ContactSystem t = contact_system_tangent(world, contacts, s, dt, applied, dir);
    const ContactSystem sp = assemble_contact_system(wp, cp, island, dt, applied);
    const ContactSystem sm = assemble_contact_system(wm, cm, island, dt, applied);
    auto compare = [&](const double* tangent, const double* plus, const double* minus, Index n) {
      double scale = 0.0;
      for (Index k = 0; k < n; ++k) scale = std::max(scale, std::abs(tangent[k]));
      for (Index k = 0; k < n; ++k)
        worst = std::max(worst, std::abs((plus[k] - minus[k]) / (2 * h) - tangent[k]) / std::max(1e-3 * scale, std::abs(tangent[k]) + 1e-300));
    };
    ASSERT_EQ(t.Jn.nonZeros(), s.Jn.nonZeros());
    compare(t.Jn.valuePtr(), sp.Jn.valuePtr(), sm.Jn.valuePtr(), t.Jn.nonZeros());
    compare(t.Jt.valuePtr(), sp.Jt.valuePtr(), sm.Jt.valuePtr(), t.Jt.nonZeros());
    ASSERT_EQ(s.compliance.size(), s.num_contacts());  // soft: the vectors exist
    for (const auto member : {&ContactSystem::phi, &ContactSystem::mu, &ContactSystem::minv, &ContactSystem::v_star,
                              &ContactSystem::compliance, &ContactSystem::erp})
      compare((t.*member).data(), (sp.*member).data(), (sm.*member).data(), (t.*member).size());

    const ContactSystemCotangent ct = random_cotangent(s, rng);
    WorldGradient g;
    g.set_zero(world, contacts.size());
    accumulate_world_gradient(world, contacts, s, dt, applied, ct, g);
    ContactSystem zero = t;
    zero.Jn.coeffs().setZero(), zero.Jt.coeffs().setZero();
    for (const auto member : {&ContactSystem::phi, &ContactSystem::mu, &ContactSystem::minv, &ContactSystem::v_star,
                              &ContactSystem::compliance, &ContactSystem::erp})
      (zero.*member).setZero();
    const double forward = inner_difference(ct, t, zero);
    double reverse = 0.0;
    for (std::size_t b = 0; b < world.bodies.size(); ++b) {
      for (std::size_t k = 0; k < g.bodies[b].vertices.size(); ++k) reverse += g.bodies[b].vertices[k].dot(dir.bodies[b].vertices[k]);
      reverse += g.bodies[b].mass * dir.bodies[b].mass + g.bodies[b].inertia * dir.bodies[b].inertia;
    }
    for (std::size_t p = 0; p < world.half_planes.size(); ++p)
      reverse += g.half_plane_normal[p].dot(dir.half_plane_normal[p]) + g.half_plane_offset[p] * dir.half_plane_offset[p];
    for (std::size_t k = 0; k < world.segments.size(); ++k)
      reverse += g.segment_ends[k][0].dot(dir.segment_ends[k][0]) + g.segment_ends[k][1].dot(dir.segment_ends[k][1]);
    for (std::size_t c = 0; c < contacts.size(); ++c)
      reverse += g.contact_mu[c] * dir.contact_mu[c] + g.contact_compliance[c] * dir.contact_compliance[c] +
                 g.contact_erp[c] * dir.contact_erp[c];
    adjoint_worst = std::max(adjoint_worst, std::abs(forward - reverse) / std::max(std::abs(forward), 1e-300));
  }
  std::printf("forward mode: max relative error against central differences %.3g, |fwd - rev|/|fwd| %.3g\n", worst,
              adjoint_worst);
  EXPECT_LE(worst, 1e-6);
  EXPECT_LE(adjoint_worst, 1e-12);
}

// A two-shape world: two polygons (b static or not), a polygon and a half-plane, or a
// polygon and a segment, placed so that they are close (scenario as in contact_features_test).
World small_world(std::mt19937_64& rng, int scenario) {
  auto polygon = [&](double r) {
    Polygon p;
    const int n = 3 + static_cast<int>(rng() % 10);
    const double phase = uniform(rng, 0.0, 2.0 * kPi);
    for (int k = 0; k < n; ++k) {
      const double a = phase + 2.0 * kPi * (k + uniform(rng, -0.3, 0.3)) / n;
      p.vertices.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    return p;
  };
  World world;
  const double ra = uniform(rng, 0.2, 0.6), rb = uniform(rng, 0.2, 0.6);
  const double dir = uniform(rng, 0.0, 2.0 * kPi);
  world.bodies.push_back(make_body(polygon(ra), 1000.0, Vec3(0.0, 0.0, uniform(rng, -kPi, kPi))));
  world.bodies[0].velocity = Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
  if (scenario <= 1) {
    const double dist = (ra + rb) * uniform(rng, 0.55, 1.02);
    world.bodies.push_back(make_body(polygon(rb), 1000.0, Vec3(dist * std::cos(dir), dist * std::sin(dir), 0.3)));
    world.bodies[1].is_static = scenario == 1;
  } else if (scenario == 2) {
    HalfPlane hp;
    const double tilt = uniform(rng, -1.0, 1.0);
    hp.normal = Vec2(-std::sin(tilt), std::cos(tilt));
    hp.offset = -ra * uniform(rng, 0.6, 1.1);
    world.half_planes.push_back(hp);
  } else {
    Segment s;
    const double half = scenario == 3 ? uniform(rng, 0.5, 2.0) : uniform(rng, 0.05, 0.4);
    const Vec2 centre = (ra + (scenario == 3 ? 0.0 : half) + uniform(rng, -0.1, 0.05)) * Vec2(std::cos(dir), std::sin(dir));
    const double along = scenario == 3 ? dir + kPi / 2 + uniform(rng, -0.5, 0.5) : dir + uniform(rng, -0.7, 0.7);
    s.a = centre - half * Vec2(std::cos(along), std::sin(along));
    s.b = centre + half * Vec2(std::cos(along), std::sin(along));
    world.segments.push_back(s);
  }
  return world;
}

TEST(ContactSystemGradient, EveryFeatureKindMatchesCentralDifferences) {
  // Cases: (kind, side, face on a, what b is) until each has been checked once.
  std::set<std::string> seen;
  std::mt19937_64 rng(11);
  double worst = 0.0;
  int checked = 0;
  for (int trial = 0; trial < 4000 && seen.size() < 40; ++trial) {
    const int scenario = trial % 5;
    const World world = small_world(rng, scenario);
    const std::vector<Contact> contacts = find_contacts(world, CollisionSettings{0.05});
    bool fresh = false;
    for (const Contact& c : contacts) {
      const std::string key = std::to_string(static_cast<int>(c.feature.kind)) + "/" + std::to_string(c.feature.side) + "/" +
                              std::to_string(c.feature.face_on_a) + "/" + std::to_string(scenario);
      fresh = seen.insert(key).second || fresh;
    }
    if (!fresh) continue;
    const std::vector<Vec3> applied = random_applied(world, rng);
    const Check check = check_gradient(world, contacts, 0.01, applied, rng);
    ++checked;
    worst = std::max(worst, check.max_error);
    EXPECT_LE(check.max_error, 1e-6) << "trial " << trial << ": " << check.worst;
  }
  std::printf("%d small worlds, %zu (kind, side, face, scenario) cases, max relative error %.3g\n", checked, seen.size(), worst);
  // deepest_vertex: HandMadeDeepestVertexAndInteriorClosestPoint.
  for (const Kind k : {Kind::incident_vertex, Kind::clipped_edge, Kind::closest, Kind::plane_vertex}) {
    bool found = false;
    for (const std::string& key : seen) found = found || key.rfind(std::to_string(static_cast<int>(k)) + "/", 0) == 0;
    EXPECT_TRUE(found) << "kind " << static_cast<int>(k);
  }
}

// deepest_vertex and an interior closest point need near-ties in the narrow phase (see
// contact_features_test): their features set by hand.
TEST(ContactSystemGradient, HandMadeDeepestVertexAndInteriorClosestPoint) {
  World world;
  Polygon box, tri;
  box.vertices = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
  tri.vertices = {{0.0, -0.1}, {0.2, 0.1}, {-0.2, 0.1}};
  world.bodies.push_back(make_body(box, 1000.0, Vec3(0.0, 0.0, 0.1)));
  world.bodies.push_back(make_body(tri, 1000.0, Vec3(0.2, 0.66, -0.2)));
  world.bodies[0].velocity = Vec3(0.3, -0.2, 0.5);
  std::mt19937_64 rng(5);
  for (const Kind kind : {Kind::closest, Kind::deepest_vertex}) {
    Contact c;
    c.body_a = 0;
    c.body_b = 1;
    c.mu = 0.4;
    c.feature.kind = kind;
    c.feature.face_on_a = true;
    c.feature.edge = 2;
    c.feature.vertex = 0;
    c.feature.side = -1;
    std::vector<Contact> contacts{c};
    refresh_contacts(world, contacts);
    const Check check = check_gradient(world, contacts, 0.01, random_applied(world, rng), rng);
    std::printf("hand-made kind %d: %d derivatives, max relative error %.3g (%s)\n", static_cast<int>(kind),
                check.entries, check.max_error, check.worst.c_str());
    EXPECT_LE(check.max_error, 1e-6) << check.worst;
  }
}

TEST(ContactSystemGradient, BadShapesAreRejected) {
  World world;
  Polygon box;
  box.vertices = {{-0.5, -0.25}, {0.5, -0.25}, {0.5, 0.25}, {-0.5, 0.25}};
  world.bodies.push_back(make_body(box, 1000.0, Vec3(0.0, 0.249, 0.0)));
  world.half_planes.push_back(HalfPlane{});
  const std::vector<Contact> contacts = find_contacts(world);
  const std::vector<Island> islands = find_islands(world, contacts);
  ASSERT_EQ(islands.size(), 1u);
  const ContactSystem s = assemble_contact_system(world, contacts, islands[0], 0.01);
  ContactSystemCotangent ct;
  ct.set_zero(s);
  EXPECT_EQ(ct.Jn.nonZeros(), s.Jn.nonZeros());
  WorldGradient g;
  g.set_zero(world, contacts.size());
  EXPECT_NO_THROW(accumulate_world_gradient(world, contacts, s, 0.01, {}, ct, g));
  EXPECT_EQ(g.bodies[0].mass, 0.0);
  WorldGradient wrong;
  wrong.set_zero(world, contacts.size() + 1);
  EXPECT_THROW(accumulate_world_gradient(world, contacts, s, 0.01, {}, ct, wrong), InputError);
  ContactSystemCotangent short_ct = ct;
  short_ct.phi.resize(0);
  EXPECT_THROW(accumulate_world_gradient(world, contacts, s, 0.01, {}, short_ct, g), InputError);
  std::vector<Contact> unrecorded = contacts;
  unrecorded[0].feature = Contact::Feature{};
  EXPECT_THROW(accumulate_world_gradient(world, unrecorded, s, 0.01, {}, ct, g), InputError);
  EXPECT_THROW(accumulate_world_gradient(world, contacts, s, 0.0, {}, ct, g), InputError);
}

}  // namespace
}  // namespace lcprelax
