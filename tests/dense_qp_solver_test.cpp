// DenseQpSolver against QpSolver (same solution, multipliers and gradients on random
// convex QPs with equality rows, two-sided/one-sided/equality rows of G, bounds and fixed
// variables), against central finite differences, and its hand-over to QpSolver on a
// problem it cannot solve (an infeasible one: QpSolver's certificate comes back).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/kkt/dense_qp_solver.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include "random_qp_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>
#include <limits>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double max_abs_diff(const Vector& a, const Vector& b) { return a.size() == 0 ? 0.0 : (a - b).cwiseAbs().maxCoeff(); }

QpProblem small_problem(unsigned seed) {
  QpProblem p = testing_support::make_random_qp(seed, 12, /*equality_rows=*/true);
  p.xl(3) = p.xu(3) = 0.25;  // a fixed variable
  return p;
}

class DenseQpMethods : public ::testing::TestWithParam<DenseQpMethod> {};

const char* method_message(DenseQpMethod m) {
  return m == DenseQpMethod::active_set_first ? "solved by the dense active-set method" : "solved by the dense interior point";
}

TEST_P(DenseQpMethods, SameSolutionAsQpSolver) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const QpProblem p = small_problem(seed);
    ASSERT_TRUE(DenseQpSolver::suits(p));
    DenseQpSolver dense(QpSettings{}, GetParam());
    dense.setup(p);
    const QpResult& rd = dense.solve();
    QpSolver ref;
    ref.setup(p);
    const QpResult& rr = ref.solve();
    if (rr.info.status == QpStatus::primal_infeasible) {  // the fixed variable can make it so
      EXPECT_EQ(rd.info.status, QpStatus::primal_infeasible) << "seed " << seed;
      EXPECT_TRUE(dense.used_fallback());
      continue;
    }
    ASSERT_EQ(rr.info.status, QpStatus::solved) << "seed " << seed;
    ASSERT_EQ(rd.info.status, QpStatus::solved) << "seed " << seed << ": " << rd.info.message;
    EXPECT_FALSE(dense.used_fallback()) << "seed " << seed << ": " << rd.info.message;
    EXPECT_EQ(rd.info.message, method_message(GetParam())) << "seed " << seed;
    EXPECT_LE(rd.info.primal_residual, 1e-9);
    EXPECT_LE(rd.info.dual_residual, 1e-9);
    EXPECT_LE(rd.info.duality_gap, 1e-9);
    EXPECT_LT(max_abs_diff(rd.x, rr.x), 1e-7) << "seed " << seed;
    EXPECT_LT(max_abs_diff(rd.y, rr.y), 1e-6) << "seed " << seed;
    EXPECT_LT(max_abs_diff(rd.z, rr.z), 1e-6) << "seed " << seed;
    EXPECT_LT(max_abs_diff(rd.z_bounds, rr.z_bounds), 1e-6) << "seed " << seed;
    EXPECT_NEAR(rd.info.objective, rr.info.objective, 1e-8 * (1 + std::abs(rr.info.objective)));
  }
}

// Strict complementarity: every finite side of a row or bound is either clearly inactive or
// has a clearly nonzero multiplier (else the derivative does not exist and each interior
// point reports its own interpolation between the one-sided ones).
bool strictly_complementary(const QpProblem& p, const QpResult& r, double tol) {
  const Vector gx = p.G * r.x;
  for (Index i = 0; i < gx.size(); ++i)
    if (p.l(i) != p.u(i) && std::min(gx(i) - p.l(i), p.u(i) - gx(i)) < tol && std::abs(r.z(i)) < tol) return false;
  for (Index j = 0; j < r.x.size(); ++j)
    if (p.xl(j) != p.xu(j) && std::min(r.x(j) - p.xl(j), p.xu(j) - r.x(j)) < tol && std::abs(r.z_bounds(j)) < tol)
      return false;
  return true;
}

// ℓ = w_xᵀx* + w_yᵀy* + w_zᵀz* by central differences on every vector datum and on three
// stored values of each of P, A and G, on the strictly complementary seeds.
TEST_P(DenseQpMethods, GradientsMatchFiniteDifferences) {
  QpSettings tight;
  tight.eps_abs = 1e-12;  // the differences of solutions divided by 2h stay below 1e-6
  int compared = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const QpProblem p0 = small_problem(seed);
    DenseQpSolver s(tight, GetParam());
    s.setup(p0);
    if (s.solve().info.status != QpStatus::solved || !strictly_complementary(p0, s.result(), 1e-3)) continue;
    ++compared;
    const Vector wx = Vector::LinSpaced(p0.num_variables(), 1.0, -0.5);
    const Vector wy = Vector::Constant(p0.num_equalities(), 0.3);
    const Vector wz = Vector::LinSpaced(p0.num_inequalities(), 0.5, -0.5);
    const QpGradient g = s.backward(wx, wy, wz);
    EXPECT_LT(g.adjoint_residual, 1e-12) << "seed " << seed;
    auto loss = [&](const QpProblem& p) {
      DenseQpSolver t(tight, GetParam());
      t.setup(p);
      const QpResult& r = t.solve();
      EXPECT_EQ(r.info.status, QpStatus::solved);
      return wx.dot(r.x) + wy.dot(r.y) + wz.dot(r.z);
    };
    const double h = 1e-5;
    auto check = [&](double analytic, const std::function<void(QpProblem&, double)>& perturb, const char* what,
                     Index k) {
      QpProblem a = p0, b = p0;
      perturb(a, h), perturb(b, -h);
      const double fd = (loss(a) - loss(b)) / (2 * h);
      EXPECT_NEAR(analytic, fd, 1e-5 * (1 + std::abs(fd))) << "seed " << seed << " " << what << "[" << k << "]";
    };
    for (Index j = 0; j < p0.num_variables(); ++j) {
      check(g.dq(j), [j](QpProblem& p, double e) { p.q(j) += e; }, "q", j);
      if (p0.xl(j) == p0.xu(j)) continue;
      if (std::isfinite(p0.xl(j))) check(g.dxl(j), [j](QpProblem& p, double e) { p.xl(j) += e; }, "xl", j);
      if (std::isfinite(p0.xu(j))) check(g.dxu(j), [j](QpProblem& p, double e) { p.xu(j) += e; }, "xu", j);
    }
    for (Index i = 0; i < p0.num_equalities(); ++i) check(g.db(i), [i](QpProblem& p, double e) { p.b(i) += e; }, "b", i);
    for (Index i = 0; i < p0.num_inequalities(); ++i) {
      if (p0.l(i) == p0.u(i)) continue;
      if (std::isfinite(p0.l(i))) check(g.dl(i), [i](QpProblem& p, double e) { p.l(i) += e; }, "l", i);
      if (std::isfinite(p0.u(i))) check(g.du(i), [i](QpProblem& p, double e) { p.u(i) += e; }, "u", i);
    }
    for (Index k : {Index(0), Index(2), Index(5)}) {
      if (k < p0.P.nonZeros()) check(g.dP.valuePtr()[k], [k](QpProblem& p, double e) { p.P.valuePtr()[k] += e; }, "P", k);
      if (k < p0.A.nonZeros()) check(g.dA.valuePtr()[k], [k](QpProblem& p, double e) { p.A.valuePtr()[k] += e; }, "A", k);
      if (k < p0.G.nonZeros()) check(g.dG.valuePtr()[k], [k](QpProblem& p, double e) { p.G.valuePtr()[k] += e; }, "G", k);
    }
  }
  EXPECT_GE(compared, 8);
}

INSTANTIATE_TEST_SUITE_P(BothMethods, DenseQpMethods,
                         ::testing::Values(DenseQpMethod::active_set_first, DenseQpMethod::interior_point));

// A positive semidefinite P (a free direction bounded only by constraints): the active-set
// method needs strict convexity, so the interior point solves it.
TEST(DenseQpSolver, SemidefiniteProblemGoesToTheInteriorPoint) {
  QpProblem p(2);
  p.P.insert(0, 0) = 1.0;  // x1 has no curvature
  p.q << -1.0, -1.0;
  p.xu = Vector::Constant(2, 2.0);
  DenseQpSolver s;
  s.setup(p);
  const QpResult& r = s.solve();
  EXPECT_EQ(r.info.status, QpStatus::solved);
  EXPECT_EQ(r.info.message, "solved by the dense interior point");
  EXPECT_NEAR(r.x(0), 1.0, 1e-8);
  EXPECT_NEAR(r.x(1), 2.0, 1e-8);
}

// min ½·a·x0² + ½·x1² + h·x0 − 3·x1 s.t. x0 ≥ 0, x1 ≤ 2 (a row) at h = 0: x0 = 0 is both the
// unconstrained minimizer and on its bound (multiplier 0: weakly active). dx0/dh is −1/a
// from above and 0 from below; backward() reports their mean −1/(2a), as central
// differences and the interior point's limit do; the strictly active row keeps its exact
// derivative (dx1/du = 1).
TEST(DenseQpSolver, WeaklyActiveSideGetsTheMeanOfTheOneSidedDerivatives) {
  const double a = 4.0;
  QpProblem p(2);
  p.P.insert(0, 0) = a;
  p.P.insert(1, 1) = 1.0;
  p.q << 0.0, -3.0;
  p.G = SparseMatrix(1, 2);
  p.G.insert(0, 1) = 1.0;
  p.l = Vector::Constant(1, -kInf);
  p.u = Vector::Constant(1, 2.0);
  p.xl(0) = 0.0;
  for (const DenseQpMethod method : {DenseQpMethod::active_set_first, DenseQpMethod::interior_point}) {
    QpSettings st;
    st.eps_abs = 1e-12;
    DenseQpSolver s(st, method);
    s.setup(p);
    const QpResult& r = s.solve();
    ASSERT_EQ(r.info.status, QpStatus::solved) << r.info.message;
    EXPECT_NEAR(r.x(0), 0.0, 1e-6);  // the interior point: ~√eps_abs at a weakly active side
    EXPECT_NEAR(r.x(1), 2.0, 1e-9);
    const QpGradient g0 = s.backward(Vector::Unit(2, 0));
    EXPECT_NEAR(g0.dq(0), -1.0 / (2 * a), 1e-4) << r.info.message;
    const QpGradient g1 = s.backward(Vector::Unit(2, 1));
    EXPECT_NEAR(g1.du(0), 1.0, 1e-6) << r.info.message;
  }
}

// Degenerate families: every row of G duplicated (dependent active rows), and P scaled to
// 1e-3 (a flat direction next to stiff ones). The objective equals QpSolver's; backward()
// gives finite gradients with a small adjoint residual.
TEST(DenseQpSolver, DuplicatedRowsAndSmallCurvatureSolve) {
  int solved = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    for (int variant = 0; variant < 2; ++variant) {
      QpProblem p = testing_support::make_random_qp(seed, 8, false);
      if (variant == 0) {
        const Index m = p.G.rows();
        SparseMatrix G2(2 * m, p.G.cols());
        std::vector<Triplet> t;
        for (Index j = 0; j < p.G.outerSize(); ++j)
          for (SparseMatrix::InnerIterator it(p.G, j); it; ++it) {
            t.emplace_back(it.row(), j, it.value());
            t.emplace_back(it.row() + m, j, it.value());
          }
        G2.setFromTriplets(t.begin(), t.end());
        p.G = G2;
        p.l = Vector(p.l.replicate(2, 1));
        p.u = Vector(p.u.replicate(2, 1));
      } else {
        p.P *= 1e-3;
      }
      QpSolver ref;
      ref.setup(p);
      const QpResult& rr = ref.solve();
      DenseQpSolver dense;
      dense.setup(p);
      const QpResult& rd = dense.solve();
      if (rr.info.status != QpStatus::solved) continue;
      ++solved;
      ASSERT_EQ(rd.info.status, QpStatus::solved) << "seed " << seed << " variant " << variant << ": " << rd.info.message;
      EXPECT_NEAR(rd.info.objective, rr.info.objective, 1e-7 * (1 + std::abs(rr.info.objective)))
          << "seed " << seed << " variant " << variant;
      const QpGradient g = dense.backward(Vector::Ones(p.num_variables()));
      EXPECT_TRUE(g.dq.allFinite());
      EXPECT_LT(g.adjoint_residual, 1e-6) << "seed " << seed << " variant " << variant << ": " << rd.info.message;
    }
  }
  EXPECT_GE(solved, 15);
}

TEST(DenseQpSolver, UpdateEqualsFreshSetup) {
  const QpProblem p1 = small_problem(3), p2 = small_problem(4);
  QpProblem p2_on_1 = p1;  // p1's pattern and classes, other values
  p2_on_1.q = p2.q;
  p2_on_1.l = p1.l.array() - 0.05;
  p2_on_1.l = p2_on_1.l.cwiseMax(p1.l);  // keeps −∞ and l = u rows as they are
  DenseQpSolver a, b;
  a.setup(p1);
  a.solve();
  a.update(p2_on_1);
  const Vector xa = a.solve().x;
  b.setup(p2_on_1);
  const Vector xb = b.solve().x;
  EXPECT_EQ(xa, xb);
  // A new P (the cached factor of the active-set method must not be reused).
  QpProblem p3 = p2_on_1;
  p3.P *= 2.0;
  a.update(p3);
  const Vector xa3 = a.solve().x;
  DenseQpSolver c;
  c.setup(p3);
  EXPECT_EQ(xa3, c.solve().x);
  QpProblem other = testing_support::make_random_qp(3, 13, true);
  EXPECT_THROW(a.update(other), InputError);
}

TEST(DenseQpSolver, InfeasibleProblemGetsQpSolversCertificate) {
  QpProblem p(2);
  SparseMatrix I(2, 2);
  I.setIdentity();
  p.P = I;
  p.G = SparseMatrix(1, 2);
  p.G.insert(0, 0) = 1.0;
  p.G.insert(0, 1) = 1.0;
  p.l = Vector::Constant(1, 3.0);
  p.u = Vector::Constant(1, kInf);
  p.xu = Vector::Constant(2, 1.0);  // x0 + x1 ≥ 3 with x ≤ 1
  DenseQpSolver s;
  s.setup(p);
  const QpResult& r = s.solve();
  EXPECT_TRUE(s.used_fallback());
  EXPECT_EQ(r.info.status, QpStatus::primal_infeasible) << r.info.message;
  EXPECT_NE(r.info.message.find("QpSolver"), std::string::npos);
  EXPECT_THROW(s.backward(Vector::Ones(2)), std::logic_error);
}

TEST(DenseQpSolver, BadInputThrows) {
  QpProblem p = small_problem(1);
  p.q(0) = std::nan("");
  DenseQpSolver s;
  EXPECT_THROW(s.setup(p), InputError);
  EXPECT_THROW(s.solve(), InputError);
}

}  // namespace
}  // namespace lcprelax
