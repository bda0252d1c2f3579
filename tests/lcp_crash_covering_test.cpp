// A crash path with the settings' covering vector instead of B·1
// (LemkeSettings::crash_covering_from_basis = false, lemke_crash.cpp and lemke_pivot.cpp):
// from the basis that solves q + δu, the path with covering vector u is the homotopy from
// q + θu (θ ≤ δ) back to q (the lcp contact model's second polish, models/contact_step.hpp).
// Expected:
// - a P-matrix LCP (M = AᵀA + I, n = 60, unique solution): from the solution basis of
//   q + δu (δ = 0.5, so that the basis changes on the way), the path along u solves q to a complementarity residual ≤ 1e-9, ends
//   at the cold start's solution (1e-10 relative) in fewer pivots than the cold start, and
//   backward() with its basis equals central differences at every entry of q;
// - a start basis whose negative basic value the covering vector does not raise ((B⁻¹d)_i
//   ≤ 0) is refused with numerical_error and a message, or, with the cold fallback,
//   solved by the cold start;
// - with the default (B·1) the same warm basis is a valid crash start.
#include <lcprelax/lcp/lemke.hpp>

#include "lemke_test_support.hpp"

#include <gtest/gtest.h>

#include <string>

namespace lcprelax {
namespace {

TEST(LemkeCrashCovering, HomotopyAlongThePerturbationReachesTheSolution) {
  const test::PMatrixLcp p = test::p_matrix_lcp(60, 4);
  const Index n = p.q.size();
  Vector u(n);
  for (Index i = 0; i < n; ++i) u(i) = 0.5 + 0.5 * ((i * 37) % 11) / 11.0;
  LemkeSolver perturbed;
  perturbed.setup(p.M, p.q + 0.5 * u);
  const LcpResult& rp = perturbed.solve();
  ASSERT_EQ(rp.info.status, LcpStatus::solved);

  LemkeSolver cold;
  cold.setup(p.M, p.q);
  const LcpResult& rc = cold.solve();
  ASSERT_EQ(rc.info.status, LcpStatus::solved);

  LemkeSettings along;
  along.crash_flip_rounds = 0;  // Lemke's path alone, as in the lcp contact model
  along.crash_start = true;
  along.crash_cold_fallback = false;
  along.crash_covering_from_basis = false;
  along.covering = u;
  LemkeSolver homotopy(along);
  homotopy.setup(p.M, p.q);
  homotopy.warm_start(rp.z_basic);
  const LcpResult& rh = homotopy.solve();
  ASSERT_EQ(rh.info.status, LcpStatus::solved) << rh.info.message;
  const Vector w = p.M * rh.z + p.q;
  EXPECT_LE(rh.z.cwiseMin(w).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE((rh.z - rc.z).lpNorm<Eigen::Infinity>(), 1e-10 * (1.0 + rc.z.lpNorm<Eigen::Infinity>()));
  std::printf("[ measured ] cold %ld pivots, along u from the perturbed basis %ld\n", rc.info.pivots, rh.info.pivots);
  EXPECT_GT(rh.info.pivots, 0);
  EXPECT_LT(rh.info.pivots, rc.info.pivots);
  test::expect_q_gradient_matches_central_differences(p, homotopy.backward(p.w).dq);
}

// M = [[2, 1], [1, 2]], q = (1, −1), warm basis {z₁, w₂}: B = [−M_:1, e₂], x_B = B⁻¹q =
// (−½, −3/2) and B⁻¹(1, 1) = (−½, ½): z₀ cannot raise x_B,1.
TEST(LemkeCrashCovering, UncoveredStartIsRefused) {
  SparseMatrix M(2, 2);
  M.insert(0, 0) = 2.0, M.insert(0, 1) = 1.0, M.insert(1, 0) = 1.0, M.insert(1, 1) = 2.0;
  const Vector q = (Vector(2) << 1.0, -1.0).finished();
  const std::vector<bool> warm = {true, false};
  LemkeSettings s;
  s.crash_flip_rounds = 0;  // the flips would repair this basis before any crash path
  s.covering_retries = 0;   // and Lemke's retries would solve it from other starts
  s.regularization_retries = 0;
  s.crash_start = true;
  auto from_warm = [&](bool covering_from_basis, bool cold_fallback) {
    LemkeSettings t = s;
    t.crash_covering_from_basis = covering_from_basis;
    t.crash_cold_fallback = cold_fallback;
    LemkeSolver solver(t);
    solver.setup(M, q);
    solver.warm_start(warm);
    return solver.solve();  // a copy: the solver goes out of scope
  };
  const LcpResult refused = from_warm(false, false);
  EXPECT_EQ(refused.info.status, LcpStatus::numerical_error) << refused.info.message;
  EXPECT_NE(refused.info.message.find("covering vector does not cover"), std::string::npos) << refused.info.message;

  const LcpResult cold = from_warm(false, true);
  ASSERT_EQ(cold.info.status, LcpStatus::solved) << cold.info.message;
  EXPECT_NEAR(cold.z(0), 0.0, 1e-14);  // z = (0, ½), w = (3/2, 0)
  EXPECT_NEAR(cold.z(1), 0.5, 1e-14);

  const LcpResult crash = from_warm(true, false);
  ASSERT_EQ(crash.info.status, LcpStatus::solved) << crash.info.message;
  EXPECT_NEAR(crash.z(1), 0.5, 1e-14);
}

}  // namespace
}  // namespace lcprelax
