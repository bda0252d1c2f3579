// The lifted basis of the sparse Lemke method (LcpLiftedForm, LemkeSettings::lifted_basis;
// lcp/src/lemke_basis.hpp): the basis factorization holds the momentum equations instead of
// the Delassus products, and everything else reads M, so
// - on the Stewart–Trinkle LCPs of a dropping polygon pile (stewart_trinkle_lifted_form),
//   a solver accepts the form and Lemke with it solves where the plain basis does, with the
//   LCP's residual within tolerance. These LCPs are degenerate (redundant contacts), so
//   roundoff may break ties differently and the two paths end at different solutions;
//   the plain basis started from the lifted one's final basis confirms it in 0 pivots
//   with the same z (1e-9 relative), and so does a lifted solver;
// - backward() (a transposed solve through K) gives the plain basis' ∂ℓ/∂q at the same
//   basis, and central differences of ℓ(q) = Σ z confirm it on a random positive definite
//   LCP of that form with a strictly complementary solution (the basis holds under the
//   perturbation);
// - on random LCPs M = J diag(d) Jᵀ + H with H of the Stewart–Trinkle kind (μ, ±1 slack
//   couplings, a diagonal compliance) and a known solution, sizes 12–300, lifted and plain
//   take the same path (same status and pivots) to the same z;
// - a regularized retry (M + εI: the basis adds ε to H's diagonal) solves with the lifted
//   basis as with the plain one;
// - the iterative refinement after each refactorization computes q − B x_B from the lifted
//   form (J (d ∘ Jᵀz) + (H + εI) z), so the checks above of the final residual on M, with K
//   refactorized every 20 or 3 pivots, also pin that residual;
// - both LU column orderings (LemkeSettings::lu_ordering) solve regularized pile LCPs
//   (M + εI, the LCP model's ε) to the same solution;
// - forms that do not describe M get an InputError naming the problem.
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/sparse/klu_lu.hpp>

#include "lemke_lifted_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace lcprelax {
namespace {
using test::PileLcp;
using test::pile_lcp;
using test::random_lcp;
using test::relative_difference;
using test::sparse_settings;

TEST(LemkeLiftedBasis, PileLcpsTakeThePlainPathToTheSameSolution) {
  int solved = 0;
  for (int steps : {60, 90, 120}) {
    const PileLcp p = pile_lcp(steps);
    const Index n = p.lcp.M.rows();
    ASSERT_GT(n, 100);
    LemkeSolver plain(sparse_settings(false)), lifted(sparse_settings(true));
    plain.setup(p.lcp.M, p.lcp.q);
    lifted.setup(p.lcp.M, p.lcp.q, p.lifted);
    const LcpResult& a = plain.solve();
    const LcpResult& b = lifted.solve();
    if (a.info.status != LcpStatus::solved) continue;
    ASSERT_EQ(b.info.status, LcpStatus::solved) << "steps " << steps << ": " << b.info.message;
    ++solved;
    EXPECT_GT(b.info.refactorizations, 1);
    const double tol = 1e-9 * std::max(1.0, p.lcp.q.lpNorm<Eigen::Infinity>());
    EXPECT_LE(b.info.complementarity, tol);
    const Vector w = p.lcp.M * b.z + p.lcp.q;
    EXPECT_GE(w.minCoeff(), -tol);
    EXPECT_GE(b.z.minCoeff(), 0.0);
    for (bool lifted_again : {false, true}) {
      LemkeSolver again(sparse_settings(lifted_again));
      if (lifted_again) again.setup(p.lcp.M, p.lcp.q, p.lifted);
      else again.setup(p.lcp.M, p.lcp.q);
      again.warm_start(b.z_basic);
      const LcpResult& c = again.solve();
      EXPECT_EQ(c.info.status, LcpStatus::solved);
      EXPECT_EQ(c.info.pivots, 0);
      EXPECT_LE(relative_difference(b.z, c.z), 1e-9) << "steps " << steps << " lifted " << lifted_again;
    }
  }
  EXPECT_GE(solved, 2);
}

TEST(LemkeLiftedBasis, BackwardMatchesThePlainBasisOnAPile) {
  const PileLcp p = pile_lcp(90);
  LemkeSolver first(sparse_settings(true));
  first.setup(p.lcp.M, p.lcp.q, p.lifted);
  const LcpResult& r = first.solve();
  ASSERT_EQ(r.info.status, LcpStatus::solved);
  // Both from the same (final) basis: the derivative is that basis' (lemke.hpp).
  LemkeSolver plain(sparse_settings(false)), lifted(sparse_settings(true));
  plain.setup(p.lcp.M, p.lcp.q);
  lifted.setup(p.lcp.M, p.lcp.q, p.lifted);
  plain.warm_start(r.z_basic);
  lifted.warm_start(r.z_basic);
  ASSERT_EQ(plain.solve().info.pivots, 0);
  ASSERT_EQ(lifted.solve().info.pivots, 0);
  const Vector g = test::random_vector(p.lcp.M.rows(), 7);
  const LcpGradient ga = plain.backward(g), gb = lifted.backward(g);
  EXPECT_LE(relative_difference(ga.dq, gb.dq), 1e-8);
  SparseMatrix diff = ga.dM - gb.dM;
  double dmax = 0, amax = 0;
  for (Index k = 0; k < diff.nonZeros(); ++k) dmax = std::max(dmax, std::abs(diff.valuePtr()[k]));
  for (Index k = 0; k < ga.dM.nonZeros(); ++k) amax = std::max(amax, std::abs(ga.dM.valuePtr()[k]));
  EXPECT_LE(dmax, 1e-8 * amax);
}

TEST(LemkeLiftedBasis, BackwardAgreesWithFiniteDifferences) {
  // M positive definite (H diagonal): a unique, strictly complementary solution.
  std::mt19937 rng(13);
  const PileLcp p = random_lcp(rng, 30, 12, /*friction_coupling=*/false);
  LemkeSolver lifted(sparse_settings(true));
  lifted.setup(p.lcp.M, p.lcp.q, p.lifted);
  const LcpResult& r = lifted.solve();
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  const Index n = p.lcp.M.rows();
  const LcpGradient gb = lifted.backward(Vector::Ones(n));
  // ℓ(q) = Σ z: central differences along a few directions, each solve warm-started from
  // the final basis (the derivative is the one of that basis).
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = 1e-7 * std::max(1.0, p.lcp.q.lpNorm<Eigen::Infinity>());
  for (int k = 0; k < 3; ++k) {
    Vector dir(n);
    for (Index i = 0; i < n; ++i) dir(i) = u(rng);
    double sum[2];
    for (int side = 0; side < 2; ++side) {
      LemkeSolver s(sparse_settings(true));
      s.setup(p.lcp.M, p.lcp.q + (side == 0 ? h : -h) * dir, p.lifted);
      s.warm_start(r.z_basic);
      const LcpResult& rs = s.solve();
      ASSERT_EQ(rs.info.status, LcpStatus::solved);
      ASSERT_EQ(rs.info.pivots, 0);  // the same basis
      sum[side] = rs.z.sum();
    }
    const double fd = (sum[0] - sum[1]) / (2 * h), an = gb.dq.dot(dir);
    EXPECT_NEAR(fd, an, 1e-6 * std::max(1.0, std::abs(an))) << "direction " << k;
  }
}

TEST(LemkeLiftedBasis, RandomContactLcpsEndAlike) {
  std::mt19937 rng(11);
  int solved = 0, cases = 0;
  for (Index nc : {3, 10, 30, 75}) {
    for (Index bodies : {nc / 3 + 1, nc + 2}) {
      const PileLcp p = random_lcp(rng, nc, bodies);
      LemkeSolver plain(sparse_settings(false)), lifted(sparse_settings(true));
      plain.setup(p.lcp.M, p.lcp.q);
      lifted.setup(p.lcp.M, p.lcp.q, p.lifted);
      const LcpResult& a = plain.solve();
      const LcpResult& b = lifted.solve();
      ++cases;
      ASSERT_EQ(a.info.status, b.info.status) << "nc " << nc << " bodies " << bodies;
      EXPECT_EQ(a.info.pivots, b.info.pivots) << "nc " << nc << " bodies " << bodies;
      if (a.info.status != LcpStatus::solved) continue;
      ++solved;
      EXPECT_LE(relative_difference(a.z, b.z), 1e-8) << "nc " << nc << " bodies " << bodies;
      EXPECT_LE(b.info.complementarity, 1e-9 * std::max(1.0, p.lcp.q.lpNorm<Eigen::Infinity>()));
    }
  }
  EXPECT_GE(solved, cases / 2);  // the others end on a ray both ways (copositive, not copositive-plus M)
}

TEST(LemkeLiftedBasis, RegularizedRetryShiftsTheLiftedH) {
  // M shifted by −1e-3·I: Lemke's first path ends on a ray on most of these; the retries on
  // M + εI (ε 5% of ‖M‖∞, K refactorized every 3 pivots) run with the shift in K. Lifted
  // and plain agree in status, message and pivots (without the shift in K they do not:
  // 53 against 78 pivots on the first case), and in z when a retry solves.
  std::mt19937 rng(3);
  int retried = 0;
  for (int k = 0; k < 6; ++k) {
    PileLcp p = random_lcp(rng, 6, 3);
    SparseMatrix I(p.lcp.M.rows(), p.lcp.M.rows());
    I.setIdentity();
    p.lifted.H = SparseMatrix(p.lifted.H - 1e-3 * I);
    p.lcp.M = SparseMatrix(p.lcp.M - 1e-3 * I);
    LemkeSettings st = sparse_settings(false);
    st.covering_retries = 0;
    st.regularization_retries = 2;
    st.regularization = 0.05;
    st.refactor_interval = 3;  // K factorized (with its shift) every 3 pivots
    LemkeSolver plain(st);
    st.lifted_basis = true;
    LemkeSolver lifted(st);
    plain.setup(p.lcp.M, p.lcp.q);
    lifted.setup(p.lcp.M, p.lcp.q, p.lifted);
    const LcpResult& a = plain.solve();
    const LcpResult& b = lifted.solve();
    EXPECT_EQ(a.info.status, b.info.status);
    EXPECT_EQ(a.info.message, b.info.message);
    EXPECT_EQ(a.info.pivots, b.info.pivots);
    if (a.info.message.find("retr") != std::string::npos) ++retried;
    if (a.info.status == LcpStatus::solved) {
      EXPECT_LE(relative_difference(a.z, b.z), 1e-8);
    }
  }
  EXPECT_GT(retried, 0);
}

// LemkeSettings::lu_ordering on the lifted bases of regularized pile LCPs (M + εI with the
// LCP model's ε = 1e-8·‖M‖∞, εI added to the lifted H, as models/contact_step.hpp step 4
// builds them): K's tiny diagonal ε beside entries of J ~ 1 makes true partial pivoting
// leave the diagonal, the case COLAMD orders for. M + εI is positive definite, so its LCP
// has one solution: both orderings reach it (1e-6 relative, the conditioning of ε), with
// residuals within tolerance, and COLAMD's factors of the final basis are the smaller
// (here 4,602 against 5,311 and 7,919 against 10,782 entries; on 1,000-body piles about
// half, bench/results/lemke_lu_ordering.txt).
TEST(LemkeLiftedBasis, LuOrderingsSolveRegularizedPileLcpsAlike) {
  for (int steps : {60, 120}) {
    PileLcp p = pile_lcp(steps);
    const Index n = p.lcp.M.rows();
    SparseMatrix I(n, n);
    I.setIdentity();
    const double eps = 1e-8 * std::max(1.0, Vector(p.lcp.M.cwiseAbs() * Vector::Ones(n)).maxCoeff());
    p.lcp.M = SparseMatrix(p.lcp.M + eps * I);
    p.lifted.H = SparseMatrix(p.lifted.H + eps * I);
    Vector z[2];
    Index factor_entries[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      LemkeSettings st = sparse_settings(true);
      st.lu_ordering = k ? LuOrdering::amd : LuOrdering::colamd;
      auto lu = make_lemke_shared_factorization();
      LemkeSolver solver(st);
      solver.share_factorization(lu);
      solver.setup(p.lcp.M, p.lcp.q, p.lifted);
      const LcpResult& r = solver.solve();
      ASSERT_EQ(r.info.status, LcpStatus::solved) << "steps " << steps << " " << to_string(st.lu_ordering);
      EXPECT_LE(r.info.complementarity, 1e-9 * std::max(1.0, p.lcp.q.lpNorm<Eigen::Infinity>()));
      EXPECT_EQ(lu->klu.ordering(), k ? sparse::KluLu::Ordering::amd : sparse::KluLu::Ordering::colamd);
      Index l = 0, u = 0, off = 0;
      lu->klu.factor_counts(l, u, off);
      std::printf("steps %d n %ld %s: pivots %ld, final basis L+U %ld\n", steps, static_cast<long>(n),
                  to_string(st.lu_ordering), r.info.pivots, static_cast<long>(l + u));
      z[k] = r.z;
      factor_entries[k] = l + u;
    }
    EXPECT_LE(relative_difference(z[0], z[1]), 1e-6) << "steps " << steps;
    EXPECT_LT(factor_entries[0], factor_entries[1]) << "steps " << steps;
  }
}

TEST(LemkeLiftedBasis, FormsThatDoNotDescribeMAreRejected) {
  std::mt19937 rng(5);
  const PileLcp p = random_lcp(rng, 4, 3);
  LemkeSolver s(sparse_settings(true));
  auto message = [&](const LcpLiftedForm& f) {
    try {
      s.setup(p.lcp.M, p.lcp.q, f);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(p.lifted), "no error");
  LcpLiftedForm wrong = p.lifted;
  wrong.H.coeffRef(0, 0) += 1.0;
  EXPECT_NE(message(wrong).find("differs from M"), std::string::npos);
  wrong = p.lifted;
  wrong.d(0) = -1.0;
  EXPECT_NE(message(wrong).find("d > 0"), std::string::npos);
  wrong = p.lifted;
  wrong.d(1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(wrong).find("NaN"), std::string::npos);
  wrong = p.lifted;
  wrong.d.conservativeResize(wrong.d.size() - 1);
  EXPECT_NE(message(wrong).find("lifted form has J"), std::string::npos);
  wrong = p.lifted;
  wrong.H.conservativeResize(3, 3);
  EXPECT_NE(message(wrong).find("lifted form has J"), std::string::npos);
  // After a rejected form the solver is not set up; a valid setup works again.
  EXPECT_THROW(s.solve(), std::logic_error);
  EXPECT_EQ(message(p.lifted), "no error");
  EXPECT_NE(s.solve().info.status, LcpStatus::unsolved);
}

}  // namespace
}  // namespace lcprelax
