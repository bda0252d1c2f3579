// LemkeSharedFactorization (lcp/lemke.hpp): solvers that factorize their bases in one shared
// KLU object reuse its symbolic analysis and pivot order while the basis pattern repeats,
// with results equal bit for bit to a solver with a factorization of its own (the values
// here move so little that partial pivoting would pick the same pivots). Sequence: the largest island of a
// 60-body LCP pile dropped for 300 steps (at rest), solved cold; then its LCP with q scaled
// by 1 + 1e-9·k (k = 1..4, the same pattern, slightly different values: the next steps of a
// pile at rest) solved from that basis with one shared factorization: one analysis for the
// warm basis' pattern and none after it, pivots reused from the second solve on, each z
// equal bit for bit to a fresh solver's. And
// solve_lcp_model, which the simulator calls with each island's shared factorization: on
// every island of that pile solved by the sparse method, the same impulses and velocities
// bit for bit with and without one, with one analysis for three solves.
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

namespace lcprelax {
namespace {

bool same_bits(const Vector& a, const Vector& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

Simulator pile_at_rest() {
  Simulator sim = test::pile_simulator(60, 1, ContactModel::lcp);
  for (int k = 0; k < 300; ++k) sim.step();
  return sim;
}

TEST(LemkeSharedFactorization, ReusesTheAnalysisOfARepeatedBasisWithTheSameResult) {
  const Simulator sim = pile_at_rest();
  const double dt = sim.settings().dt;
  const ContactSystem s = test::largest_island_system(sim);
  ASSERT_GT(s.num_contacts(), 100);
  const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), dt);
  const ContactSolution cold = solve_lcp_model(s, dt, LemkeSettings{});
  ASSERT_EQ(cold.status, ContactStatus::solved) << cold.message;

  const std::shared_ptr<LemkeSharedFactorization> shared = make_lemke_shared_factorization();
  for (int k = 1; k <= 4; ++k) {
    const Vector q = lcp.q * (1.0 + 1e-9 * k);
    LemkeSettings sparse;
    sparse.method = LemkeMethod::sparse;
    LemkeSolver own(sparse), with_shared(sparse);
    with_shared.share_factorization(shared);
    for (LemkeSolver* solver : {&own, &with_shared}) {
      solver->setup(lcp.M, q);
      solver->warm_start(cold.z_basic);
    }
    const LcpResult& a = own.solve();
    const LcpResult& b = with_shared.solve();
    ASSERT_EQ(a.info.status, LcpStatus::solved) << a.info.message;
    EXPECT_EQ(b.info.status, LcpStatus::solved);
    EXPECT_TRUE(b.info.warm_started);
    EXPECT_EQ(b.info.pivots, 0);
    EXPECT_TRUE(same_bits(a.z, b.z)) << "solve " << k;
    EXPECT_TRUE(same_bits(a.w, b.w)) << "solve " << k;
    EXPECT_EQ(shared->analyses, 1) << "solve " << k;  // the first solve's, reused after it
    EXPECT_EQ(shared->factorizations, k);
    EXPECT_EQ(shared->reused_pivots, k - 1);  // the first solve's pivots, kept after it
  }
}

TEST(LemkeSharedFactorization, ANewPatternIsAnalysedAgain) {
  // Two different LCPs in turn: each factorization after the first needs its own analysis.
  SparseMatrix A(2, 2), B(3, 3);
  A.insert(0, 0) = 2.0;
  A.insert(1, 1) = 3.0;
  A.insert(0, 1) = 1.0;
  B.insert(0, 0) = 2.0;
  B.insert(1, 1) = 2.0;
  B.insert(2, 2) = 2.0;
  A.makeCompressed();
  B.makeCompressed();
  const std::shared_ptr<LemkeSharedFactorization> shared = make_lemke_shared_factorization();
  for (const SparseMatrix* M : {&A, &B, &A}) {
    LemkeSettings settings;
    settings.method = LemkeMethod::sparse;
    LemkeSolver solver(settings);
    solver.share_factorization(shared);
    solver.setup(*M, -Vector::Ones(M->rows()));
    solver.warm_start(std::vector<bool>(static_cast<std::size_t>(M->rows()), true));
    const LcpResult& r = solver.solve();
    ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
    EXPECT_EQ(r.info.pivots, 0);
  }
  EXPECT_EQ(shared->factorizations, 3);
  EXPECT_EQ(shared->analyses, 3);
}

TEST(LemkeSharedFactorization, SolveLcpModelAnswersAreUnchanged) {
  // The simulator passes each island's shared factorization to solve_lcp_model; without
  // one (the reference) the impulses and velocities must be the same bit for bit.
  const Simulator sim = pile_at_rest();
  const double dt = sim.settings().dt;
  const World& world = sim.world();
  const std::vector<Contact> contacts = find_contacts(world, CollisionSettings{});
  int checked = 0;
  for (const Island& island : find_islands(world, contacts)) {
    const ContactSystem s = assemble_contact_system(world, contacts, island, dt);
    if (4 * s.num_contacts() <= LemkeSettings{}.dense_max_n) continue;  // the dense method shares nothing
    const ContactSolution cold = solve_lcp_model(s, dt, LemkeSettings{});
    ASSERT_EQ(cold.status, ContactStatus::solved) << cold.message;
    ++checked;
    const std::shared_ptr<LemkeSharedFactorization> shared = make_lemke_shared_factorization();
    for (int k = 0; k < 3; ++k) {
      const ContactSolution a = solve_lcp_model(s, dt, LemkeSettings{}, cold.z_basic);
      const ContactSolution b = solve_lcp_model(s, dt, LemkeSettings{}, cold.z_basic, shared);
      ASSERT_EQ(b.status, ContactStatus::solved) << b.message;
      EXPECT_TRUE(b.warm_started);
      EXPECT_TRUE(same_bits(a.lambda_n, b.lambda_n));
      EXPECT_TRUE(same_bits(a.lambda_t, b.lambda_t));
      EXPECT_TRUE(same_bits(a.v_next, b.v_next));
    }
    EXPECT_EQ(shared->analyses, 1);
    EXPECT_EQ(shared->factorizations, 3);
    EXPECT_EQ(shared->reused_pivots, 2);
  }
  EXPECT_GE(checked, 1);
}

}  // namespace
}  // namespace lcprelax
