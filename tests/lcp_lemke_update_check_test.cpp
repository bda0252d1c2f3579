// The sparse Lemke basis' ill-conditioned updates (lemke_basis_sparse.cpp): an update whose
// Schur complement has a condition estimate beyond 1e12 is kept while the updated basic
// values still solve B x_B = q to 1e-10 (relative, normalized units), and the basis is
// refactorized only when they do not (LcpInfo::update_checks, update_refactorizations).
//
// Problems: M = G Gᵀ + εI with G of size n × n/3 (a third of its entries standard normal)
// and ε = 1e-11·‖G Gᵀ‖∞: positive definite, so each LCP has one solution, but with a
// condition number near 1e11, as the M + εI of a jammed pile (more contacts than degrees of
// freedom); q standard normal. (At ε = 1e-12·‖G Gᵀ‖∞, n = 240, seed 1 ends with its final
// residual above tolerance with and without the checks alike: the limit of the method, not
// of the checks.) Expected, for several sizes and seeds:
// - the sparse method solves each (status solved: the final basis refactorized and its
//   residual within tolerance) with the dense method's z to 1e-6 relative (the condition
//   number amplifies roundoff);
// - ill-conditioned updates occur and are checked (update_checks > 0 over the problems),
//   and most pass (update_refactorizations < update_checks): fewer refactorizations than
//   checks plus the count at the fixed interval.
#include <lcprelax/lcp/lemke.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

namespace lcprelax {
namespace {

struct NearSingular {
  SparseMatrix M;
  Vector q;
};

NearSingular near_singular_lcp(Index n, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  const Index k = n / 3;
  DenseMatrix G = DenseMatrix::Zero(n, k);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < k; ++j)
      if ((i * 7 + j * 3 + seed) % 3 == 0) G(i, j) = normal(gen);
  DenseMatrix M = G * G.transpose();
  const double eps = 1e-11 * M.cwiseAbs().rowwise().sum().maxCoeff();
  M += eps * DenseMatrix::Identity(n, n);
  NearSingular p;
  p.M = M.sparseView();
  p.q.resize(n);
  for (Index i = 0; i < n; ++i) p.q(i) = normal(gen);
  return p;
}

TEST(LemkeUpdateCheck, IllConditionedUpdatesAreKeptWhileTheirResidualHolds) {
  long checks = 0, failed_checks = 0, refactorizations = 0, pivots = 0;
  for (const Index n : {60, 120, 240}) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      SCOPED_TRACE(testing::Message() << "n " << n << " seed " << seed);
      const NearSingular p = near_singular_lcp(n, seed);
      LemkeSettings sparse;
      sparse.method = LemkeMethod::sparse;
      LemkeSolver s(sparse);
      s.setup(p.M, p.q);
      const LcpResult& r = s.solve();
      ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
      LemkeSettings dense;
      dense.method = LemkeMethod::dense;
      LemkeSolver d(dense);
      d.setup(p.M, p.q);
      const LcpResult& rd = d.solve();
      ASSERT_EQ(rd.info.status, LcpStatus::solved) << rd.info.message;
      EXPECT_LE((r.z - rd.z).lpNorm<Eigen::Infinity>(), 1e-6 * std::max(1.0, rd.z.lpNorm<Eigen::Infinity>()));
      const Vector w = p.M * r.z + p.q;
      EXPECT_LE(r.z.cwiseMin(w).cwiseAbs().maxCoeff(), 1e-9 * p.q.lpNorm<Eigen::Infinity>());
      EXPECT_LE(r.info.update_refactorizations, r.info.update_checks);
      checks += r.info.update_checks;
      failed_checks += r.info.update_refactorizations;
      refactorizations += r.info.refactorizations;
      pivots += r.info.pivots;
    }
  }
  std::printf("[ measured ] %ld pivots, %ld refactorizations, %ld checked updates (%ld failed)\n", pivots,
              refactorizations, checks, failed_checks);
  EXPECT_GT(checks, 0) << "the problems must exercise the ill-conditioned updates";
  EXPECT_LT(failed_checks, checks);
}

}  // namespace
}  // namespace lcprelax
