// LemkeSolver::setup(lifted, q): M given by its lifted form J diag(d) Jᵀ + H alone, formed
// only when a solve needs its columns (lemke.hpp). Pinned:
// - a warm basis that solves the LCP (a pile island's final basis) is confirmed in zero
//   pivots without forming M (LcpInfo::matrix_formed false), with the z of a solver given M
//   (1e-12 relative) and w = M z + q (checked against the M formed outside);
// - a cold solve forms M and takes the path of a solver given M on random contact LCPs
//   (same status and pivots, z to 1e-8);
// - backward() after a lifted-only warm start (M formed then) equals the backward of a
//   solver given M at the same basis, dq and dM, and agrees with central differences of
//   ℓ(q) = Σ z (every solve lifted-only) on a random positive definite LCP;
// - the dense method forms M at setup and solves as with M;
// - a form of the wrong size, with a NaN or with d ≤ 0, and a q with a NaN or of another
//   size than the form, get an InputError naming the problem.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include "lemke_lifted_support.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>

namespace lcprelax {
namespace {
using test::PileLcp;
using test::relative_difference;
using test::sparse_settings;

TEST(LemkeLiftedOnly, AWarmBasisThatSolvesNeverFormsM) {
  for (int steps : {60, 120}) {
    const PileLcp p = test::pile_lcp(steps);
    LemkeSolver with_m(sparse_settings(true));
    with_m.setup(p.lcp.M, p.lcp.q, p.lifted);
    const LcpResult& a = with_m.solve();
    if (a.info.status != LcpStatus::solved) continue;
    LemkeSolver lifted_only(sparse_settings(true));
    lifted_only.setup(p.lifted, p.lcp.q);
    lifted_only.warm_start(a.z_basic);
    const LcpResult& b = lifted_only.solve();
    ASSERT_EQ(b.info.status, LcpStatus::solved) << "steps " << steps << ": " << b.info.message;
    EXPECT_EQ(b.info.pivots, 0);
    EXPECT_TRUE(b.info.warm_started);
    EXPECT_FALSE(b.info.matrix_formed);
    EXPECT_TRUE(a.info.matrix_formed);
    EXPECT_LE(relative_difference(a.z, b.z), 1e-12) << "steps " << steps;
    const Vector w = p.lcp.M * b.z + p.lcp.q;
    EXPECT_LE((w - b.w).lpNorm<Eigen::Infinity>(), 1e-12 * std::max(1.0, p.lcp.q.lpNorm<Eigen::Infinity>()));
    EXPECT_LE(b.info.complementarity, 1e-9 * std::max(1.0, p.lcp.q.lpNorm<Eigen::Infinity>()));
    return;
  }
  FAIL() << "no pile LCP solved cold";
}

TEST(LemkeLiftedOnly, ColdSolvesFormMAndTakeThePathOfM) {
  std::mt19937 rng(17);
  int solved = 0, cases = 0;
  for (Index nc : {3, 10, 30, 75}) {
    for (Index bodies : {nc / 3 + 1, nc + 2}) {
      const PileLcp p = test::random_lcp(rng, nc, bodies);
      LemkeSolver with_m(sparse_settings(true)), lifted_only(sparse_settings(true));
      with_m.setup(p.lcp.M, p.lcp.q, p.lifted);
      lifted_only.setup(p.lifted, p.lcp.q);
      const LcpResult& a = with_m.solve();
      const LcpResult& b = lifted_only.solve();
      ++cases;
      ASSERT_EQ(a.info.status, b.info.status) << "nc " << nc << " bodies " << bodies;
      EXPECT_EQ(a.info.pivots, b.info.pivots) << "nc " << nc << " bodies " << bodies;
      EXPECT_TRUE(b.info.matrix_formed);  // z columns entered
      if (a.info.status != LcpStatus::solved) continue;
      ++solved;
      EXPECT_LE(relative_difference(a.z, b.z), 1e-8) << "nc " << nc << " bodies " << bodies;
    }
  }
  EXPECT_GE(solved, cases / 2);
}

TEST(LemkeLiftedOnly, BackwardEqualsTheSolverGivenM) {
  const PileLcp p = test::pile_lcp(90);
  LemkeSolver first(sparse_settings(true));
  first.setup(p.lcp.M, p.lcp.q, p.lifted);
  const LcpResult& r = first.solve();
  ASSERT_EQ(r.info.status, LcpStatus::solved);
  LemkeSolver with_m(sparse_settings(true)), lifted_only(sparse_settings(true));
  with_m.setup(p.lcp.M, p.lcp.q, p.lifted);
  lifted_only.setup(p.lifted, p.lcp.q);
  with_m.warm_start(r.z_basic);
  lifted_only.warm_start(r.z_basic);
  ASSERT_EQ(with_m.solve().info.pivots, 0);
  ASSERT_EQ(lifted_only.solve().info.pivots, 0);
  const Vector g = test::random_vector(p.lcp.M.rows(), 9);
  const LcpGradient ga = with_m.backward(g), gb = lifted_only.backward(g);
  EXPECT_LE(relative_difference(ga.dq, gb.dq), 1e-12);
  // dM_ij = dq_i z_j on M's pattern: compare as dense matrices (the formed M may store
  // entries that cancel to zero where M's assembly stores none).
  const DenseMatrix da(ga.dM), db(gb.dM);
  EXPECT_LE((da - db).cwiseAbs().maxCoeff(), 1e-12 * std::max(1.0, da.cwiseAbs().maxCoeff()));
}

TEST(LemkeLiftedOnly, BackwardAgreesWithFiniteDifferences) {
  // M positive definite (H diagonal): a unique, strictly complementary solution, so the
  // final basis holds under small changes of q. Every solve is lifted-only.
  std::mt19937 rng(19);
  const PileLcp p = test::random_lcp(rng, 30, 12, /*friction_coupling=*/false);
  LemkeSolver solver(sparse_settings(true));
  solver.setup(p.lifted, p.lcp.q);
  const LcpResult& r = solver.solve();
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  const Index n = p.lcp.q.size();
  const LcpGradient an = solver.backward(Vector::Ones(n));  // ℓ(q) = Σ z
  const double h = 1e-7 * std::max(1.0, p.lcp.q.lpNorm<Eigen::Infinity>());
  for (unsigned k = 0; k < 3; ++k) {
    const Vector dir = test::random_vector(n, 100 + k);
    double sum[2];
    for (int side = 0; side < 2; ++side) {
      LemkeSolver s(sparse_settings(true));
      s.setup(p.lifted, p.lcp.q + (side == 0 ? h : -h) * dir);
      s.warm_start(r.z_basic);
      const LcpResult& rs = s.solve();
      ASSERT_EQ(rs.info.status, LcpStatus::solved);
      ASSERT_EQ(rs.info.pivots, 0);  // the same basis
      EXPECT_FALSE(rs.info.matrix_formed);
      sum[side] = rs.z.sum();
    }
    const double fd = (sum[0] - sum[1]) / (2 * h), analytic = an.dq.dot(dir);
    EXPECT_NEAR(fd, analytic, 1e-6 * std::max(1.0, std::abs(analytic))) << "direction " << k;
  }
}

TEST(LemkeLiftedOnly, TheDenseMethodFormsMAtSetup) {
  std::mt19937 rng(23);
  const PileLcp p = test::random_lcp(rng, 10, 5);
  LemkeSettings st;
  st.method = LemkeMethod::dense;
  LemkeSolver with_m(st), lifted_only(st);
  with_m.setup(p.lcp.M, p.lcp.q);
  lifted_only.setup(p.lifted, p.lcp.q);
  const LcpResult& a = with_m.solve();
  const LcpResult& b = lifted_only.solve();
  EXPECT_EQ(a.info.status, b.info.status);
  EXPECT_EQ(a.info.pivots, b.info.pivots);
  EXPECT_TRUE(b.info.matrix_formed);
  if (a.info.status == LcpStatus::solved) EXPECT_LE(relative_difference(a.z, b.z), 1e-8);
}

TEST(LemkeLiftedOnly, BadFormsAndRightHandSidesAreRejected) {
  std::mt19937 rng(5);
  const PileLcp p = test::random_lcp(rng, 4, 3);
  LemkeSolver s(sparse_settings(true));
  auto message = [&](const LcpLiftedForm& f, const Vector& q) {
    try {
      s.setup(f, q);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(p.lifted, p.lcp.q), "no error");
  LcpLiftedForm wrong = p.lifted;
  wrong.d(0) = 0.0;
  EXPECT_NE(message(wrong, p.lcp.q).find("d > 0"), std::string::npos);
  wrong = p.lifted;
  wrong.H.coeffRef(1, 1) = std::numeric_limits<double>::infinity();
  EXPECT_NE(message(wrong, p.lcp.q).find("NaN or infinite"), std::string::npos);
  wrong = p.lifted;
  wrong.d.conservativeResize(wrong.d.size() + 1);
  EXPECT_NE(message(wrong, p.lcp.q).find("lifted form has J"), std::string::npos);
  EXPECT_NE(message(p.lifted, Vector::Zero(p.lcp.q.size() - 1)).find("lifted form has J"), std::string::npos);
  Vector bad_q = p.lcp.q;
  bad_q(2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(p.lifted, bad_q).find("q has a NaN"), std::string::npos);
  // After a refused setup the solver is not set up; a valid one works again.
  EXPECT_THROW(s.solve(), std::logic_error);
  EXPECT_EQ(message(p.lifted, p.lcp.q), "no error");
  EXPECT_NE(s.solve().info.status, LcpStatus::unsolved);
}

}  // namespace
}  // namespace lcprelax
