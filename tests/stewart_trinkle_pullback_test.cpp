// stewart_trinkle_pullback (learn/stewart_trinkle_pullback.hpp) as the exact gradient of a
// linear functional of the island's LCP data: for random dM (on and off M_lcp's pattern),
// dq, dP, dp,
//     L(s) = Σ dM ∘ M_lcp(s) + dq·q(s) + Σ dP ∘ P(s) + dp·p(s),
// M_lcp, q from stewart_trinkle_lcp(s, delassus(s), Δt) and P, p from
// stewart_trinkle_prediction(s), the pullback's cotangent must equal L's partials in every
// field of the ContactSystem: Jn, Jt (on their patterns), φ, μ, M⁻¹, v* and the normal
// softness c (compliance) and e (erp) — checked by central differences along a random
// direction in each field (h = 1e-6 relative; agreement to 1e-7 relative) on a pile island
// made soft (c ∈ [0.01, 0.1] 1/kg, e ∈ [0.1, 0.9]) and on the same island rigid (where c
// and e still have partials, the data's dependence at c = e = 0, checked by forward
// differences into c, e ≥ 0: L is linear in both).
#include <lcprelax/learn/stewart_trinkle_pullback.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>

namespace lcprelax::learn {
namespace {

ContactSystem pile_island() {
  PileOptions o;
  o.bodies = 12;
  o.seed = 3;
  const Scene scene = make_pile_scene(o);
  Simulator sim(scene.world, scene.settings);
  for (int k = 0; k < 60; ++k) sim.step();
  const StepContacts found = find_step_contacts(sim.world(), sim.settings());
  std::size_t big = 0;
  for (std::size_t i = 0; i < found.islands.size(); ++i)
    if (found.islands[i].contacts.size() > found.islands[big].contacts.size()) big = i;
  return assemble_contact_system(sim.world(), found.contacts, found.islands[big], sim.settings().dt);
}

SparseMatrix random_like(const SparseMatrix& pattern, std::mt19937_64& rng, int extra) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Triplet> t;
  for (Index j = 0; j < pattern.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(pattern, j); it; ++it) t.emplace_back(it.row(), j, u(rng));
  std::uniform_int_distribution<Index> row(0, pattern.rows() - 1), col(0, pattern.cols() - 1);
  for (int k = 0; k < extra; ++k) t.emplace_back(row(rng), col(rng), u(rng));  // off the pattern too
  SparseMatrix m(pattern.rows(), pattern.cols());
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

double frobenius(const SparseMatrix& a, const SparseMatrix& b) {
  double sum = 0.0;
  for (Index j = 0; j < a.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(a, j); it; ++it) sum += it.value() * b.coeff(it.row(), j);
  return sum;
}

struct Functional {
  SparseMatrix dM, dP;
  Vector dq, dp;
  double dt;
  double operator()(const ContactSystem& s) const {
    const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), dt);
    const StewartTrinklePrediction pred = stewart_trinkle_prediction(s);
    return frobenius(dM, lcp.M) + dq.dot(lcp.q) + frobenius(dP, pred.P) + dp.dot(pred.p);
  }
};

// ⟨cotangent field, direction⟩ against (L(s + h·dir) − L(s − h·dir)) / 2h for one field.
// One-sided (forward) where the field cannot go below 0: L is linear in c and e, so the
// forward difference is exact up to roundoff there.
void check_field(const std::string& name, const ContactSystem& s, const Functional& L,
                 const std::function<double(ContactSystem&, double)>& move, bool one_sided = false) {
  ContactSystem plus = s, minus = s, probe = s;
  const double h = 1e-6;
  const double predicted = move(probe, 0.0);  // the directional derivative from the cotangent
  move(plus, h);
  if (!one_sided) move(minus, -h);
  const double fd = (L(plus) - L(minus)) / ((one_sided ? 1.0 : 2.0) * h);
  EXPECT_NEAR(predicted, fd, 1e-7 * std::max(1.0, std::abs(fd))) << name;
}

void check_all(ContactSystem s, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Index nc = s.num_contacts(), nf = s.num_friction(), n = nc + 3 * nf, nd = s.num_dofs();
  const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), 0.01);
  const StewartTrinklePrediction pred = stewart_trinkle_prediction(s);
  Functional L{random_like(lcp.M, rng, 3 * static_cast<int>(n)), random_like(pred.P, rng, static_cast<int>(n)),
               Vector::NullaryExpr(n, [&](Index) { return u(rng); }),
               Vector::NullaryExpr(nd, [&](Index) { return u(rng); }), 0.01};
  const ContactSystemCotangent ct = stewart_trinkle_pullback(s, L.dt, L.dM, L.dq, L.dP, L.dp);

  auto random_vector = [&](Index size) { return Vector(Vector::NullaryExpr(size, [&](Index) { return u(rng); })); };
  auto sparse_move = [&](SparseMatrix ContactSystem::*field, const SparseMatrix& cot) {
    const SparseMatrix dir = random_like(s.*field, rng, 0);
    return [dir, field, &cot](ContactSystem& x, double h) {
      if (h == 0.0) return frobenius(dir, cot);
      x.*field += h * dir;
      return 0.0;
    };
  };
  auto vector_move = [&](Vector ContactSystem::*field, const Vector& cot, bool nonnegative) {
    const Vector r = random_vector((s.*field).size());
    const Vector dir = nonnegative ? Vector(r.cwiseAbs()) : r;
    return [dir, field, &cot](ContactSystem& x, double h) {
      if (h == 0.0) return dir.dot(cot);
      x.*field += h * dir;
      return 0.0;
    };
  };
  check_field("Jn", s, L, sparse_move(&ContactSystem::Jn, ct.Jn));
  check_field("Jt", s, L, sparse_move(&ContactSystem::Jt, ct.Jt));
  check_field("phi", s, L, vector_move(&ContactSystem::phi, ct.phi, false));
  check_field("mu", s, L, vector_move(&ContactSystem::mu, ct.mu, false));
  check_field("minv", s, L, vector_move(&ContactSystem::minv, ct.minv, false));
  check_field("v_star", s, L, vector_move(&ContactSystem::v_star, ct.v_star, false));
  ASSERT_EQ(ct.compliance.size(), nc);
  ASSERT_EQ(ct.erp.size(), nc);
  const bool rigid = s.compliance.size() == 0;
  if (rigid) {  // the partials at c = e = 0 (the vectors made explicit), forward differences
    s.compliance = Vector::Zero(nc);
    s.erp = Vector::Zero(nc);
  }
  check_field("compliance", s, L, vector_move(&ContactSystem::compliance, ct.compliance, rigid), rigid);
  check_field("erp", s, L, vector_move(&ContactSystem::erp, ct.erp, rigid), rigid);
}

TEST(StewartTrinklePullback, IsTheGradientOfALinearFunctionalOnASoftIsland) {
  ContactSystem s = pile_island();
  ASSERT_GE(s.num_contacts(), 8);
  ASSERT_GT(s.num_friction(), 0);
  // φ away from the kinks at 0 (φ⁺ and e·min(φ, 0)) by more than the differencing step.
  for (Index c = 0; c < s.num_contacts(); ++c)
    if (std::abs(s.phi(c)) < 1e-4) s.phi(c) = c % 2 ? 2e-4 : -2e-4;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uc(0.01, 0.1), ue(0.1, 0.9);
  s.compliance = Vector::NullaryExpr(s.num_contacts(), [&](Index) { return uc(rng); });
  s.erp = Vector::NullaryExpr(s.num_contacts(), [&](Index) { return ue(rng); });
  check_all(s, 11);
}

TEST(StewartTrinklePullback, IsTheGradientOfALinearFunctionalOnARigidIsland) {
  ContactSystem s = pile_island();
  for (Index c = 0; c < s.num_contacts(); ++c)
    if (std::abs(s.phi(c)) < 1e-4) s.phi(c) = c % 2 ? 2e-4 : -2e-4;
  ASSERT_EQ(s.compliance.size(), 0);  // a rigid island carries no softness vectors
  check_all(s, 13);
}

}  // namespace
}  // namespace lcprelax::learn
