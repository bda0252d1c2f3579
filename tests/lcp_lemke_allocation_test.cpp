// LemkeSolver::solve() on a warm solver (setup() done, one solve behind it) allocates
// nothing: a contact LCP (the bench_lemke pile, fc2d_to_lcp) is solved cold, q is then
// changed a little and the LCP solved again, warm-started from the first solve's final
// basis, with every heap allocation counted (tests/allocation_counter.hpp).
// - Dense basis (n = 32): the whole update_q + warm_start + solve() allocates nothing,
//   both when the warm basis stays feasible (0 pivots) and when q moves so far that it is
//   rejected and the solve pivots from the all-w basis.
// - Sparse basis (n = 120): the same, except that KLU's factorizations from scratch
//   (klu_analyze, klu_factor) allocate; they are excluded from the count through
//   LemkeSolver::set_refactorization_hook, everything else (pivots, Schur-complement
//   updates, ratio tests, tie-breaks, refinement, extraction) is counted. A warm basis
//   that is already factorized is not factorized again, so the 0-pivot warm solve is
//   counted without any exclusion.
#include "allocation_counter.hpp"

#include "../bench/lemke_problems.hpp"

#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <vector>

namespace lcprelax {
namespace {

struct Counted {
  long allocations = 0;
  long pivots = 0;
  long refactorizations = 0;
  bool warm_started = false;
  LcpStatus status = LcpStatus::unsolved;
  double complementarity = 0.0;
};

// While a refactorization from scratch runs, allocations are not counted.
void pause_counting(bool starting) { test::g_count_allocations.store(!starting); }

// Contact LCP with its q for the pile of nc contacts, the fc2d q scaled by `scale` and
// perturbed by `noise`·U(−1, 1) per entry (seeded).
Fc2dLcp pile_lcp(Index nc, double scale, double noise) {
  io::Fc2dData p = bench::make_pile(nc, 2024);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Vector q = scale * p.q;
  for (Index i = 0; i < q.size(); ++i) q(i) += noise * U(rng);
  return fc2d_to_lcp(p.W, q, p.mu);
}

// Independent complementarity max|min(z, Mz + q)|.
double complementarity(const SparseMatrix& M, const Vector& q, const Vector& z) {
  const Vector w = M * z + q;
  return z.cwiseMin(w).cwiseAbs().maxCoeff();
}

// Solves (M, q) cold, then (M, q2) warm-started from the final basis, counting the
// allocations of update_q + warm_start + solve (excluding refactorizations from scratch
// when exclude_refactorizations).
Counted warm_solve(LemkeMethod method, const SparseMatrix& M, const Vector& q, const Vector& q2,
                   bool exclude_refactorizations) {
  LemkeSettings settings;
  settings.method = method;
  LemkeSolver solver(settings);
  solver.setup(M, q);
  const LcpResult& cold = solver.solve();
  EXPECT_TRUE(has_solution(cold.info.status)) << cold.info.message;
  EXPECT_GT(cold.info.pivots, 0);
  const std::vector<bool> basis = cold.z_basic;
  if (exclude_refactorizations) solver.set_refactorization_hook(pause_counting);
  Counted c;
  {
    test::AllocationCounter counter;
    solver.update_q(q2);
    solver.warm_start(basis);
    const LcpResult& r = solver.solve();
    c.allocations = counter.stop();
    c.pivots = r.info.pivots;
    c.refactorizations = r.info.refactorizations;
    c.warm_started = r.info.warm_started;
    c.status = r.info.status;
    c.complementarity = r.info.complementarity;
  }
  solver.set_refactorization_hook(nullptr);
  EXPECT_EQ(solver.result().info.method, method);
  if (has_solution(c.status)) {
    EXPECT_LE(complementarity(M, q2, solver.result().z), 1e-9 * q2.lpNorm<Eigen::Infinity>());
  }
  std::printf("%s n = %ld: %ld allocations, %ld pivots, %ld refactorizations, warm_started %d\n", to_string(method),
              static_cast<long>(q.size()), c.allocations, c.pivots, c.refactorizations, c.warm_started ? 1 : 0);
  return c;
}

void expect_solved(const Counted& c, const Vector& q) {
  EXPECT_EQ(c.status, LcpStatus::solved);
  EXPECT_LE(c.complementarity, 1e-9 * q.lpNorm<Eigen::Infinity>());
}

TEST(LemkeAllocation, DenseWarmBasisStillFeasibleAllocatesNothing) {
  const Fc2dLcp a = pile_lcp(8, 1.0, 0.0), b = pile_lcp(8, 1.1, 0.0);
  ASSERT_EQ(a.q.size(), 32);
  const Counted c = warm_solve(LemkeMethod::dense, a.M, a.q, b.q, false);
  expect_solved(c, b.q);
  EXPECT_TRUE(c.warm_started);
  EXPECT_EQ(c.pivots, 0);
  EXPECT_EQ(c.allocations, 0);
}

TEST(LemkeAllocation, DensePivotingSolveAllocatesNothing) {
  const Fc2dLcp a = pile_lcp(8, 1.0, 0.0), b = pile_lcp(8, 1.0, 0.05);
  const Counted c = warm_solve(LemkeMethod::dense, a.M, a.q, b.q, false);
  expect_solved(c, b.q);
  EXPECT_FALSE(c.warm_started);
  EXPECT_GT(c.pivots, 0);
  EXPECT_EQ(c.allocations, 0);
}

TEST(LemkeAllocation, SparseWarmBasisStillFeasibleAllocatesNothing) {
  const Fc2dLcp a = pile_lcp(30, 1.0, 0.0), b = pile_lcp(30, 1.1, 0.0);
  ASSERT_EQ(a.q.size(), 120);
  const Counted c = warm_solve(LemkeMethod::sparse, a.M, a.q, b.q, false);
  expect_solved(c, b.q);
  EXPECT_TRUE(c.warm_started);
  EXPECT_EQ(c.pivots, 0);
  EXPECT_EQ(c.refactorizations, 0);  // the final basis of the cold solve is still factored
  EXPECT_EQ(c.allocations, 0);
}

TEST(LemkeAllocation, SparsePivotingSolveAllocatesOnlyInKluFactorizations) {
  const Fc2dLcp a = pile_lcp(30, 1.0, 0.0), b = pile_lcp(30, 1.0, 0.05);
  const Counted c = warm_solve(LemkeMethod::sparse, a.M, a.q, b.q, true);
  expect_solved(c, b.q);
  EXPECT_FALSE(c.warm_started);
  EXPECT_GT(c.pivots, 0);
  EXPECT_GE(c.refactorizations, 2);  // the rejected warm basis and the final basis at least
  EXPECT_EQ(c.allocations, 0);
  // For the record: with the factorizations counted too (KLU allocates in them).
  const Counted all = warm_solve(LemkeMethod::sparse, a.M, a.q, b.q, false);
  EXPECT_EQ(all.pivots, c.pivots);
  EXPECT_GT(all.allocations, 0);
}

}  // namespace
}  // namespace lcprelax
