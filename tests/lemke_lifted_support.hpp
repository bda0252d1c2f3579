#pragma once
// Test helpers for Lemke's lifted form (LcpLiftedForm): the Stewart–Trinkle LCP of a
// dropping pile's largest island with its lifted form, and random LCPs of that layout.
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace lcprelax::test {

struct PileLcp {
  StewartTrinkleLcp lcp;
  LcpLiftedForm lifted;
};

// The LCP of the largest island of a 40-body pile dropped for `steps` steps.
inline PileLcp pile_lcp(int steps) {
  Simulator sim = pile_simulator(40, 2, ContactModel::lcp);
  for (int k = 0; k < steps; ++k) sim.step();
  const ContactSystem s = largest_island_system(sim);
  EXPECT_GT(s.num_contacts(), 0);
  const double dt = sim.settings().dt;
  return {stewart_trinkle_lcp(s, delassus(s), dt), stewart_trinkle_lifted_form(s, dt)};
}

inline LemkeSettings sparse_settings(bool lifted) {
  LemkeSettings st;
  st.method = LemkeMethod::sparse;
  st.lifted_basis = lifted;
  st.refactor_interval = 20;  // several refactorizations of K per solve
  return st;
}

// A vector of n entries uniform in [-1, 1) from seed.
inline Vector random_vector(Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector g(n);
  for (Index i = 0; i < n; ++i) g(i) = u(rng);
  return g;
}

inline double relative_difference(const Vector& a, const Vector& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1e-300, a.lpNorm<Eigen::Infinity>());
}

// M = J diag(d) Jᵀ + H on nc "contacts" of one normal, two friction and one slack row each
// (the Stewart–Trinkle layout [λn, β⁺, β⁻, γ]), m = 3·bodies velocities; J's rows touch two
// random bodies. q = w* − M z* for a strictly complementary pair (z*, w*) ≥ 0: a solution
// exists and, nondegenerate, stays basic under small changes of q.
inline PileLcp random_lcp(std::mt19937& rng, Index nc, Index bodies, bool friction_coupling = true) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.1, 1.0);
  std::uniform_int_distribution<Index> body(0, bodies - 1);
  const Index n = 4 * nc, m = 3 * bodies;
  std::vector<Triplet> tj, th;
  for (Index c = 0; c < nc; ++c) {
    const Index a = body(rng);
    Index b = body(rng);
    if (b == a) b = (a + 1) % bodies;
    for (int k = 0; k < 3; ++k) {
      tj.emplace_back(c, 3 * a + k, u(rng));
      tj.emplace_back(c, 3 * b + k, u(rng));
      const double t0 = u(rng), t1 = u(rng);
      tj.emplace_back(nc + c, 3 * a + k, t0);
      tj.emplace_back(nc + c, 3 * b + k, t1);
      tj.emplace_back(2 * nc + c, 3 * a + k, -t0);
      tj.emplace_back(2 * nc + c, 3 * b + k, -t1);
    }
    th.emplace_back(c, c, 1e-3 * pos(rng));  // compliance
    if (!friction_coupling) {  // a positive diagonal instead: M positive definite
      for (Index r : {nc + c, 2 * nc + c, 3 * nc + c}) th.emplace_back(r, r, pos(rng));
      continue;
    }
    th.emplace_back(3 * nc + c, c, 0.5 * pos(rng));  // μ
    for (Index f : {nc + c, 2 * nc + c}) {
      th.emplace_back(f, 3 * nc + c, 1.0);
      th.emplace_back(3 * nc + c, f, -1.0);
    }
  }
  PileLcp p;
  p.lifted.J.resize(n, m);
  p.lifted.J.setFromTriplets(tj.begin(), tj.end());
  p.lifted.H.resize(n, n);
  p.lifted.H.setFromTriplets(th.begin(), th.end());
  p.lifted.d.resize(m);
  for (Index k = 0; k < m; ++k) p.lifted.d(k) = pos(rng);
  const SparseMatrix D = SparseMatrix(p.lifted.d.asDiagonal());
  p.lcp.M = SparseMatrix(p.lifted.J * D * p.lifted.J.transpose()) + p.lifted.H;
  Vector z = Vector::Zero(n), w = Vector::Zero(n);
  for (Index i = 0; i < n; ++i) (u(rng) > 0 ? z(i) : w(i)) = pos(rng);
  p.lcp.q = w - p.lcp.M * z;
  return p;
}

}  // namespace lcprelax::test
