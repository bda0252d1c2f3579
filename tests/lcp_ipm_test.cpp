// LCPs through the interior-point QP (lcp/lcp_ipm.hpp): on monotone P-matrix LCPs
// (M = BBᵀ + I + S, S skew; unique solution) it agrees with Lemke; a non-monotone LCP
// (M + Mᵀ indefinite) is refused with InputError "M is not monotone" before any solve.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lcp_ipm.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace lcprelax {
namespace {

TEST(LcpIpm, AgreesWithLemkeOnMonotoneLcps) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> N(0.0, 1.0);
    const Index n = 15;
    const DenseMatrix B = DenseMatrix::NullaryExpr(n, n, [&] { return N(rng); });
    DenseMatrix S = DenseMatrix::NullaryExpr(n, n, [&] { return N(rng); });
    S = 0.5 * (S - S.transpose()).eval();
    const DenseMatrix M = B * B.transpose() + DenseMatrix::Identity(n, n) + S;
    const Vector q = Vector::NullaryExpr(n, [&] { return N(rng); });
    const SparseMatrix Ms = M.sparseView();
    const LcpResult ipm = solve_lcp_ipm(Ms, q);
    ASSERT_EQ(ipm.info.status, LcpStatus::solved) << ipm.info.message << " seed " << seed;
    LemkeSolver lemke;
    lemke.setup(Ms, q);
    const LcpResult& lr = lemke.solve();
    ASSERT_EQ(lr.info.status, LcpStatus::solved);
    EXPECT_LE((ipm.z - lr.z).lpNorm<Eigen::Infinity>(), 1e-6) << "seed " << seed;
    EXPECT_LE(ipm.info.complementarity, 1e-9 * std::max(1.0, q.lpNorm<Eigen::Infinity>()));
  }
}

// M = [[0, 1], [−3, 0]] + diag(−1, 0): M + Mᵀ = [[−2, −2], [−2, 0]] is indefinite.
// M + Mᵀ with a negative diagonal entry cannot be monotone: InputError, no solve.
TEST(LcpIpm, NegativeDiagonalOfTheSymmetricPartThrows) {
  const DenseMatrix M = (DenseMatrix(2, 2) << -1, 1, -3, 0).finished();
  const Vector q = (Vector(2) << -1, 2).finished();
  EXPECT_THROW(solve_lcp_ipm(M.sparseView(), q), InputError);
}

TEST(LcpIpm, NonMonotoneIsRefusedInTheLcpsTerms) {
  // M + Mᵀ = [0 −2; −2 0] is indefinite: the QP would be nonconvex. Refused before any
  // solve (issue 19: it used to run, and a non-monotone M with positive diagonal could end
  // `solved` or exit 1), with a message about M, not about the QP's P.
  for (const DenseMatrix& M : {DenseMatrix((DenseMatrix(2, 2) << 0, 1, -3, 0).finished()),
                               DenseMatrix((DenseMatrix(2, 2) << 1, 3, 3, 1).finished())}) {
    const Vector q = (Vector(2) << -1, 2).finished();
    try {
      const LcpResult r = solve_lcp_ipm(M.sparseView(), q);
      ADD_FAILURE() << "accepted a non-monotone M; status " << to_string(r.info.status);
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("M is not monotone"), std::string::npos) << m;
      EXPECT_EQ(m.find("QP"), std::string::npos) << m;
    }
  }
}

}  // namespace
}  // namespace lcprelax
