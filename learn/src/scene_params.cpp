// The parameter map of a scene (scene_params.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/scene_params.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

namespace lcprelax::learn {
namespace {

double radius_of(const Polygon& p) {
  double r = 0.0;
  for (const Vec2& v : p.vertices) r = std::max(r, v.norm());
  return r;
}

bool same_class(const RigidBody& a, const RigidBody& b) {
  if (a.mass != b.mass || a.inertia != b.inertia || a.shape.vertices.size() != b.shape.vertices.size() ||
      a.gap_offset != b.gap_offset || a.velocity_residual != b.velocity_residual)
    return false;
  for (std::size_t i = 0; i < a.shape.vertices.size(); ++i)
    if (a.shape.vertices[i] != b.shape.vertices[i]) return false;
  return true;
}

std::pair<int, int> ordered(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

constexpr Index kResidualEntries = 12;  // W is 3×4, row-major in θ

// One parameter of World::lcp_block: B = Σ θ_k E_k, d = Σ θ_k e_k (scene_params.hpp).
struct LcpBlockDirection {
  std::string name;
  Eigen::Matrix4d E = Eigen::Matrix4d::Zero();
  Eigen::Vector4d e = Eigen::Vector4d::Zero();
};

// Free: the 16 entries of B and the 4 of d. Tied (the friction rows' antisymmetry imposed):
// a 2×2 correction of W in (n, t) spread with the LCP's signs, of the cone row's μ entry, and
// of (q_n, q_t) with q⁻ = −q⁺.
const std::vector<LcpBlockDirection>& lcp_block_directions(bool tied) {
  static const std::vector<LcpBlockDirection> free_dirs = [] {
    std::vector<LcpBlockDirection> d;
    for (int k = 0; k < 4; ++k)
      for (int l = 0; l < 4; ++l) {
        LcpBlockDirection x{"lcp_block.M" + std::to_string(k) + std::to_string(l)};
        x.E(k, l) = 1.0;
        d.push_back(x);
      }
    for (int k = 0; k < 4; ++k) {
      LcpBlockDirection x{"lcp_block.q" + std::to_string(k)};
      x.e(k) = 1.0;
      d.push_back(x);
    }
    return d;
  }();
  static const std::vector<LcpBlockDirection> tied_dirs = [] {
    const double sign[3] = {1.0, 1.0, -1.0};  // LCP index 0 (λn), 1 (β⁺), 2 (β⁻) → J row n, t, t with sign
    const int jrow[3] = {0, 1, 1};
    std::vector<LcpBlockDirection> d;
    const char* names[2][2] = {{"nn", "nt"}, {"tn", "tt"}};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        LcpBlockDirection x{std::string("lcp_block.W") + names[a][b]};
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l)
            if (jrow[k] == a && jrow[l] == b) x.E(k, l) = sign[k] * sign[l];
        d.push_back(x);
      }
    LcpBlockDirection mu{"lcp_block.mu"};
    mu.E(3, 0) = 1.0;
    d.push_back(mu);
    LcpBlockDirection qn{"lcp_block.qn"};
    qn.e(0) = 1.0;
    d.push_back(qn);
    LcpBlockDirection qt{"lcp_block.qt"};
    qt.e(1) = 1.0, qt.e(2) = -1.0;
    d.push_back(qt);
    return d;
  }();
  return tied ? tied_dirs : free_dirs;
}

}  // namespace

SceneLearnFlags parse_scene_learn_flags(const std::string& list) {
  SceneLearnFlags f{false, false, false, false, false, false, false, false, false, false};
  std::stringstream ss(list);
  std::string item;
  int count = 0;
  while (std::getline(ss, item, ',')) {
    bool* target = item == "mu" ? &f.mu
                   : item == "mass" ? &f.mass
                   : item == "inertia" ? &f.inertia
                   : item == "vertices" ? &f.vertices
                   : item == "ground" ? &f.ground
                   : item == "gap" ? &f.gap
                   : item == "residual" ? &f.residual
                   : item == "block" ? &f.block
                   : item == "block_tied" ? &f.block_tied
                   : item == "softness" ? &f.softness
                                      : nullptr;
    if (!target)
      throw InputError("--learn: unknown parameter kind '" + item +
                       "' (expected mu, mass, inertia, vertices, ground, gap, residual, block, block_tied, softness)");
    if (*target) throw InputError("--learn: '" + item + "' given twice");
    *target = true;
    ++count;
  }
  if (count == 0) throw InputError("--learn: empty list");
  if (f.block && f.block_tied) throw InputError("--learn: block and block_tied are two forms of one correction, give one");
  return f;
}

std::vector<int> scene_shape_classes(const World& world) {
  std::vector<int> cls(world.bodies.size(), -1);
  std::vector<int> representative;  // body index of each class
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    if (world.bodies[b].is_static) continue;
    for (std::size_t c = 0; c < representative.size() && cls[b] < 0; ++c)
      if (same_class(world.bodies[b], world.bodies[static_cast<std::size_t>(representative[c])]))
        cls[b] = static_cast<int>(c);
    if (cls[b] < 0) {
      cls[b] = static_cast<int>(representative.size());
      representative.push_back(static_cast<int>(b));
    }
  }
  return cls;
}

SceneParameterMap::SceneParameterMap(const World& world, const SceneParameterSettings& settings)
    : settings_(settings), body_class_(scene_shape_classes(world)) {
  int classes = 0;
  for (int c : body_class_) classes = std::max(classes, c + 1);
  if (classes == 0) throw InputError("scene parameters: the world has no dynamic body");
  std::vector<double> radius(static_cast<std::size_t>(classes), 0.0);
  class_vertices_.assign(static_cast<std::size_t>(classes), -1);
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const int c = body_class_[b];
    if (c < 0) continue;
    const int nv = static_cast<int>(world.bodies[b].shape.vertices.size());
    if (class_vertices_[c] < 0) class_vertices_[c] = nv, radius[c] = radius_of(world.bodies[b].shape);
  }
  double mean_radius = 0.0;
  for (double r : radius) mean_radius += r / classes;

  auto push = [this](Kind k, double scale) {
    kind_.push_back(k);
    scale_.push_back(scale);
  };
  push(Kind::mu, 1.0);
  if (settings.mu_per_pair) {
    for (const FrictionTable::Pair& p : world.friction.pairs) {
      const auto key = ordered(p.material_a, p.material_b);
      if (std::find(pairs_.begin(), pairs_.end(), key) == pairs_.end()) pairs_.push_back(key), push(Kind::mu, 1.0);
    }
  }
  class_first_.resize(static_cast<std::size_t>(classes));
  for (int c = 0; c < classes; ++c) {
    class_first_[c] = static_cast<Index>(kind_.size());
    push(Kind::mass, 1.0);
    push(Kind::inertia, 1.0);
    for (int i = 0; i < 2 * class_vertices_[c]; ++i) push(Kind::vertex, radius[c]);
  }
  first_half_plane_ = static_cast<Index>(kind_.size());
  for (std::size_t h = 0; h < world.half_planes.size(); ++h) push(Kind::angle, 1.0), push(Kind::offset, mean_radius);
  first_segment_ = static_cast<Index>(kind_.size());
  for (std::size_t s = 0; s < 4 * world.segments.size(); ++s) push(Kind::segment_end, mean_radius);
  first_gap_ = static_cast<Index>(kind_.size());
  if (settings.learn.gap)
    for (int c = 0; c < classes; ++c) push(Kind::gap, radius[c]);
  first_residual_ = static_cast<Index>(kind_.size());
  if (settings.learn.residual)
    for (Index e = 0; e < kResidualEntries * classes; ++e) push(Kind::residual, 1.0);
  if (settings.learn.block && settings.learn.block_tied)
    throw InputError("scene parameters: learn.block and learn.block_tied exclude each other");
  first_block_ = static_cast<Index>(kind_.size());
  if (settings.learn.block || settings.learn.block_tied)
    for (std::size_t k = 0; k < lcp_block_directions(settings.learn.block_tied).size(); ++k) push(Kind::lcp_block, 1.0);
  first_softness_ = static_cast<Index>(kind_.size());
  if (settings.learn.softness) {
    // Compliance in units of the classes' mean 1/m (the size of a Delassus diagonal).
    double inverse_mass = 0.0;
    for (int c = 0; c < classes; ++c) {
      const auto it = std::find(body_class_.begin(), body_class_.end(), c);
      inverse_mass += 1.0 / world.bodies[static_cast<std::size_t>(it - body_class_.begin())].mass / classes;
    }
    for (std::size_t k = 0; k <= pairs_.size(); ++k) push(Kind::compliance, inverse_mass), push(Kind::erp, 1.0);
  }
  size_ = static_cast<Index>(kind_.size());
}

ParameterSet SceneParameterMap::parameters(const World& world) const {
  if (world.bodies.size() != body_class_.size() || world.half_planes.size() * 2 != static_cast<std::size_t>(first_segment_ - first_half_plane_) ||
      world.segments.size() * 4 != static_cast<std::size_t>(first_gap_ - first_segment_))
    throw InputError("scene parameters: the world does not have the scene's bodies and static shapes");
  const SceneLearnFlags& f = settings_.learn;
  auto scaled = [this](Parameter p, Index k) {  // ξ in units of the parameter's length scale
    if (kind_[static_cast<std::size_t>(k)] != Kind::angle) p.scale = length_scale(k);
    return p;
  };
  auto positive = [](std::string name, double value, bool learn) {
    Parameter p{std::move(name), value, Transform::log};
    p.learn = learn;
    return p;
  };
  auto representative = [&](std::size_t c) -> const RigidBody& {
    const auto it = std::find(body_class_.begin(), body_class_.end(), static_cast<int>(c));
    return world.bodies[static_cast<std::size_t>(it - body_class_.begin())];
  };
  ParameterSet theta;
  theta.add(positive("mu", world.friction.default_mu, f.mu));
  for (const auto& [a, b] : pairs_)
    theta.add(positive("mu[" + std::to_string(a) + "," + std::to_string(b) + "]", world.friction.mu(a, b), f.mu));
  for (std::size_t c = 0; c < class_first_.size(); ++c) {
    const RigidBody& body = representative(c);
    const std::string prefix = "class" + std::to_string(c) + ".";
    theta.add(positive(prefix + "mass", body.mass, f.mass));
    theta.add(positive(prefix + "inertia", body.inertia, f.inertia));
    for (std::size_t i = 0; i < body.shape.vertices.size(); ++i) {
      const std::string v = prefix + "vertex" + std::to_string(i);
      Parameter px{v + ".x", body.shape.vertices[i].x()}, py{v + ".y", body.shape.vertices[i].y()};
      px.learn = py.learn = f.vertices;
      theta.add(scaled(px, theta.size())), theta.add(scaled(py, theta.size()));
    }
  }
  for (std::size_t h = 0; h < world.half_planes.size(); ++h) {
    const HalfPlane& hp = world.half_planes[h];
    const std::string prefix = "half_plane" + std::to_string(h) + ".";
    Parameter angle{prefix + "angle", std::atan2(hp.normal.y(), hp.normal.x())}, offset{prefix + "offset", hp.offset};
    angle.learn = offset.learn = f.ground;
    theta.add(angle), theta.add(scaled(offset, theta.size()));
  }
  for (std::size_t s = 0; s < world.segments.size(); ++s) {
    const Segment& seg = world.segments[s];
    const std::string prefix = "segment" + std::to_string(s) + ".";
    const double values[4] = {seg.a.x(), seg.a.y(), seg.b.x(), seg.b.y()};
    const char* names[4] = {"a.x", "a.y", "b.x", "b.y"};
    for (int k = 0; k < 4; ++k) {
      Parameter p{prefix + names[k], values[k]};
      p.learn = f.ground;
      theta.add(scaled(p, theta.size()));
    }
  }
  if (f.gap)
    for (std::size_t c = 0; c < class_first_.size(); ++c)
      theta.add(scaled(Parameter{"class" + std::to_string(c) + ".gap", representative(c).gap_offset}, theta.size()));
  if (f.residual)
    for (std::size_t c = 0; c < class_first_.size(); ++c)
      for (Index r = 0; r < 3; ++r)
        for (Index j = 0; j < 4; ++j)
          theta.add(Parameter{"class" + std::to_string(c) + ".residual" + std::to_string(r) + std::to_string(j),
                              representative(c).velocity_residual(r, j)});
  if (f.block || f.block_tied)
    for (const LcpBlockDirection& d : lcp_block_directions(f.block_tied)) {
      // The entry each direction owns (its first nonzero): B_kl, or d_k.
      double value = 0.0;
      Index i = 0, j = 0;
      if (d.E.cwiseAbs().maxCoeff(&i, &j) > 0.0) value = world.lcp_block.M(i, j) * d.E(i, j);
      else if (d.e.cwiseAbs().maxCoeff(&i) > 0.0) value = world.lcp_block.q(i) * d.e(i);
      theta.add(Parameter{d.name, value});
    }
  if (f.softness) {
    auto add_softness = [&](const std::string& suffix, double compliance, double erp) {
      Parameter c{"compliance" + suffix, compliance, Transform::identity, 0.0};
      Parameter e{"erp" + suffix, erp, Transform::identity, 0.0, 1.0};
      theta.add(scaled(c, theta.size())), theta.add(scaled(e, theta.size()));
    };
    add_softness("", world.friction.default_compliance, world.friction.default_erp);
    for (const auto& [a, b] : pairs_)
      add_softness("[" + std::to_string(a) + "," + std::to_string(b) + "]", world.friction.compliance(a, b),
                   world.friction.erp(a, b));
  }
  return theta;
}

void SceneParameterMap::apply(const ParameterSet& theta, World& world) const {
  if (theta.size() != size_ || world.bodies.size() != body_class_.size())
    throw InputError("scene parameters: θ or the world does not have the scene's layout");
  world.friction.default_mu = theta[0].value;
  if (settings_.learn.softness) {
    world.friction.default_compliance = theta[first_softness_].value;
    world.friction.default_erp = theta[first_softness_ + 1].value;
  }
  for (FrictionTable::Pair& p : world.friction.pairs) {
    const auto it = std::find(pairs_.begin(), pairs_.end(), ordered(p.material_a, p.material_b));
    const Index k = it == pairs_.end() ? 0 : 1 + static_cast<Index>(it - pairs_.begin());
    p.mu = theta[k].value;
    if (settings_.learn.softness) {
      p.compliance = theta[first_softness_ + 2 * k].value;
      p.erp = theta[first_softness_ + 2 * k + 1].value;
    }
  }
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const int c = body_class_[b];
    if (c < 0) continue;
    RigidBody& body = world.bodies[b];
    const Index k = class_first_[c];
    body.mass = theta[k].value;
    body.inertia = theta[k + 1].value;
    for (std::size_t i = 0; i < body.shape.vertices.size(); ++i)
      body.shape.vertices[i] = Vec2(theta[k + 2 + 2 * static_cast<Index>(i)].value, theta[k + 3 + 2 * static_cast<Index>(i)].value);
    if (settings_.learn.gap) body.gap_offset = theta[first_gap_ + c].value;
    if (settings_.learn.residual)
      for (Index e = 0; e < kResidualEntries; ++e)
        body.velocity_residual(e / 4, e % 4) = theta[first_residual_ + kResidualEntries * c + e].value;
  }
  for (std::size_t h = 0; h < world.half_planes.size(); ++h) {
    const double psi = theta[first_half_plane_ + 2 * static_cast<Index>(h)].value;
    world.half_planes[h].normal = Vec2(std::cos(psi), std::sin(psi));
    world.half_planes[h].offset = theta[first_half_plane_ + 2 * static_cast<Index>(h) + 1].value;
  }
  for (std::size_t s = 0; s < world.segments.size(); ++s) {
    const Index k = first_segment_ + 4 * static_cast<Index>(s);
    world.segments[s].a = Vec2(theta[k].value, theta[k + 1].value);
    world.segments[s].b = Vec2(theta[k + 2].value, theta[k + 3].value);
  }
  if (settings_.learn.block || settings_.learn.block_tied) {
    world.lcp_block.enabled = true;
    world.lcp_block.M.setZero();
    world.lcp_block.q.setZero();
    const std::vector<LcpBlockDirection>& dirs = lcp_block_directions(settings_.learn.block_tied);
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      const double v = theta[first_block_ + static_cast<Index>(k)].value;
      world.lcp_block.M += v * dirs[k].E;
      world.lcp_block.q += v * dirs[k].e;
    }
  }
}

int SceneParameterMap::material_of_b(const World& world, const Contact& c) {
  if (c.body_b >= 0) return world.bodies[static_cast<std::size_t>(c.body_b)].material;
  if (c.static_kind == Contact::StaticKind::half_plane) return world.half_planes[static_cast<std::size_t>(c.static_index)].material;
  return world.segments[static_cast<std::size_t>(c.static_index)].material;
}

Index SceneParameterMap::mu_index(const World& /*world*/, int material_a, int material_b) const {
  const auto it = std::find(pairs_.begin(), pairs_.end(), ordered(material_a, material_b));
  return it == pairs_.end() ? 0 : 1 + static_cast<Index>(it - pairs_.begin());
}

Vector SceneParameterMap::gradient(const World& world, const std::vector<Contact>& contacts, const WorldGradient& g) const {
  if (g.bodies.size() != world.bodies.size() || g.contact_mu.size() != contacts.size())
    throw InputError("scene parameters: the world gradient does not match the world or its contacts");
  Vector grad = Vector::Zero(size_);
  if (settings_.learn.softness && (g.contact_compliance.size() != contacts.size() || g.contact_erp.size() != contacts.size()))
    throw InputError("scene parameters: the world gradient has no compliance/erp entry per contact");
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const int ma = world.bodies[static_cast<std::size_t>(contacts[c].body_a)].material;
    const Index k = mu_index(world, ma, material_of_b(world, contacts[c]));
    grad(k) += g.contact_mu[c];
    if (settings_.learn.softness) {
      grad(first_softness_ + 2 * k) += g.contact_compliance[c];
      grad(first_softness_ + 2 * k + 1) += g.contact_erp[c];
    }
  }
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const int c = body_class_[b];
    if (c < 0) continue;
    const Index k = class_first_[c];
    grad(k) += g.bodies[b].mass;
    grad(k + 1) += g.bodies[b].inertia;
    for (std::size_t i = 0; i < g.bodies[b].vertices.size(); ++i) {
      grad(k + 2 + 2 * static_cast<Index>(i)) += g.bodies[b].vertices[i].x();
      grad(k + 3 + 2 * static_cast<Index>(i)) += g.bodies[b].vertices[i].y();
    }
    if (settings_.learn.gap) grad(first_gap_ + c) += g.bodies[b].gap_offset;
    if (settings_.learn.residual)
      for (Index e = 0; e < kResidualEntries; ++e)
        grad(first_residual_ + kResidualEntries * c + e) += g.bodies[b].velocity_residual(e / 4, e % 4);
  }
  for (std::size_t h = 0; h < world.half_planes.size(); ++h) {
    const Vec2& n = world.half_planes[h].normal;  // (cos ψ, sin ψ): dn/dψ = (−sin ψ, cos ψ)
    const Index k = first_half_plane_ + 2 * static_cast<Index>(h);
    grad(k) += g.half_plane_normal[h].dot(Vec2(-n.y(), n.x()));
    grad(k + 1) += g.half_plane_offset[h];
  }
  for (std::size_t s = 0; s < world.segments.size(); ++s) {
    const Index k = first_segment_ + 4 * static_cast<Index>(s);
    grad(k) += g.segment_ends[s][0].x(), grad(k + 1) += g.segment_ends[s][0].y();
    grad(k + 2) += g.segment_ends[s][1].x(), grad(k + 3) += g.segment_ends[s][1].y();
  }
  if (settings_.learn.block || settings_.learn.block_tied) {
    const std::vector<LcpBlockDirection>& dirs = lcp_block_directions(settings_.learn.block_tied);
    for (std::size_t k = 0; k < dirs.size(); ++k)
      grad(first_block_ + static_cast<Index>(k)) +=
          (dirs[k].E.array() * g.lcp_block_M.array()).sum() + dirs[k].e.dot(Eigen::Vector4d(g.lcp_block_q));
  }
  return grad;
}

ParameterSet perturb_scene_parameters(const ParameterSet& truth, const SceneParameterMap& map, double fraction,
                                      std::uint64_t seed) {
  if (!(std::isfinite(fraction) && fraction >= 0 && fraction < 1))
    throw InputError("perturbation fraction: must be in [0, 1)");
  if (truth.size() != map.size()) throw InputError("perturb_scene_parameters: θ does not have the map's layout");
  std::mt19937_64 rng(seed);
  ParameterSet out = truth;
  Vector theta = truth.values();
  for (Index k = 0; k < truth.size(); ++k) {
    const double sign = (rng() >> 63) ? 1.0 : -1.0;  // drawn for every parameter (layout order)
    if (!truth[k].learn) continue;
    switch (map.kind(k)) {
      case SceneParameterMap::Kind::mu:
      case SceneParameterMap::Kind::mass:
      case SceneParameterMap::Kind::inertia: theta(k) *= 1.0 + sign * fraction; break;
      case SceneParameterMap::Kind::angle:
      case SceneParameterMap::Kind::residual: theta(k) += sign * 0.1 * fraction; break;
      case SceneParameterMap::Kind::lcp_block:  // kept: no scale-free size (entries in 1/kg, kg, m/s)
      case SceneParameterMap::Kind::compliance:
      case SceneParameterMap::Kind::erp: break;  // kept: the rigid truth (0) is on the bound
      default: theta(k) += sign * 0.5 * fraction * map.length_scale(k); break;
    }
  }
  out.set_values(theta);
  return out;
}

double scene_relative_error(const ParameterSet& estimate, const ParameterSet& truth, const SceneParameterMap& map,
                            Index k) {
  if (estimate.size() != truth.size() || truth.size() != map.size() || k < 0 || k >= truth.size())
    throw InputError("scene_relative_error: parameter sets of different layouts or index out of range");
  const double d = std::abs(estimate[k].value - truth[k].value);
  switch (map.kind(k)) {
    case SceneParameterMap::Kind::mu:
    case SceneParameterMap::Kind::mass:
    case SceneParameterMap::Kind::inertia: return d / std::abs(truth[k].value);
    case SceneParameterMap::Kind::angle:
    case SceneParameterMap::Kind::residual:
    case SceneParameterMap::Kind::lcp_block:
    case SceneParameterMap::Kind::erp: return d;
    default: return d / map.length_scale(k);  // vertices, gaps, offsets, segment ends, compliance
  }
}

}  // namespace lcprelax::learn
