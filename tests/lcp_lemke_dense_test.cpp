// Dense lexicographic Lemke: closed-form and classic LCPs, warm start, ray termination,
// and the backward pass against central finite differences.
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace lcprelax {
namespace {

SparseMatrix sparse(const DenseMatrix& D) { return D.sparseView(); }

// Independent check of a returned solution: z ≥ 0, w = Mz + q ≥ 0, z ⊥ w.
void expect_lcp_solution(const DenseMatrix& M, const Vector& q, const LcpResult& r, double tol = 1e-9) {
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  const Vector w = M * r.z + q;
  EXPECT_GE(r.z.minCoeff(), 0.0);
  EXPECT_GE(w.minCoeff(), -tol);
  EXPECT_LE(r.z.cwiseProduct(w).cwiseAbs().maxCoeff(), tol);
  EXPECT_LE(r.info.complementarity, tol);
}

// The seeds' 1-D frictional block: z = (λ+, λ−, γ), M = [[1,-1,1],[-1,1,1],[-1,-1,0]],
// q = [v+u, −v−u, mgμ]. Next velocity v' = v + u + λ+ − λ−. Closed form: the block
// sticks (v' = 0) iff |v+u| ≤ mgμ, else it slides with friction −sign(v+u)·mgμ.
TEST(LemkeDense, FrictionalBlockSticksAndSlides) {
  const DenseMatrix M = (DenseMatrix(3, 3) << 1, -1, 1, -1, 1, 1, -1, -1, 0).finished();
  const double mg = 1.0, mu = 0.5;
  for (double vu : {-2.0, -0.7, -0.3, 0.0, 0.2, 0.49, 0.8, 3.0}) {
    const Vector q = (Vector(3) << vu, -vu, mg * mu).finished();
    LemkeSolver solver;
    solver.setup(sparse(M), q);
    const LcpResult& r = solver.solve();
    expect_lcp_solution(M, q, r);
    const double friction = r.z(0) - r.z(1);
    const double v_next = vu + friction;
    if (std::abs(vu) <= mg * mu) {
      EXPECT_NEAR(v_next, 0.0, 1e-12) << "v+u = " << vu;
    } else {
      EXPECT_NEAR(friction, -std::copysign(mg * mu, vu), 1e-12) << "v+u = " << vu;
    }
  }
}

// Cycles without lexicographic rules: M = [[1,2,0],[0,1,2],[2,0,1]], q = −1 → z = 1/3.
TEST(LemkeDense, DegenerateCyclingExample) {
  const DenseMatrix M = (DenseMatrix(3, 3) << 1, 2, 0, 0, 1, 2, 2, 0, 1).finished();
  const Vector q = -Vector::Ones(3);
  LemkeSolver solver;
  solver.setup(sparse(M), q);
  const LcpResult& r = solver.solve();
  expect_lcp_solution(M, q, r);
  for (Index i = 0; i < 3; ++i) EXPECT_NEAR(r.z(i), 1.0 / 3.0, 1e-12);
}

// Murty's example (Murty 1988, ch. 6): M lower triangular, 1 on the diagonal and 2 below,
// q = −1; solution z = e₁. Lemke with covering vector e needs exponentially many pivots.
TEST(LemkeDense, MurtyExponentialExample) {
  for (Index n : {6, 16}) {
    DenseMatrix M = DenseMatrix::Zero(n, n);
    for (Index i = 0; i < n; ++i)
      for (Index j = 0; j <= i; ++j) M(i, j) = i == j ? 1.0 : 2.0;
    const Vector q = -Vector::Ones(n);
    LemkeSolver solver;
    solver.setup(sparse(M), q);
    const LcpResult& r = solver.solve();
    expect_lcp_solution(M, q, r);
    EXPECT_NEAR(r.z(0), 1.0, 1e-12);
    EXPECT_NEAR(r.z.tail(n - 1).norm(), 0.0, 1e-12);
    RecordProperty("pivots_n" + std::to_string(n), std::to_string(r.info.pivots));
    std::printf("Murty n = %d: %ld pivots\n", n, r.info.pivots);
    EXPECT_GE(r.info.pivots, n);
  }
}

// w = −z − 1 ≥ 0 has no solution with z ≥ 0: Lemke must end in ray termination.
TEST(LemkeDense, InfeasibleEndsInRayTermination) {
  const DenseMatrix M = (DenseMatrix(2, 2) << -1, 0, 0, 1).finished();
  const Vector q = (Vector(2) << -1, 1).finished();
  LemkeSolver solver;
  solver.setup(sparse(M), q);
  EXPECT_EQ(solver.solve().info.status, LcpStatus::ray_termination);
}

TEST(LemkeDense, EmptyAndTrivialProblems) {
  LemkeSolver solver;
  solver.setup(SparseMatrix(0, 0), Vector(0));
  EXPECT_EQ(solver.solve().info.status, LcpStatus::solved);
  solver.setup(sparse(DenseMatrix::Identity(2, 2)), Vector::Ones(2));  // q ≥ 0 → z = 0
  const LcpResult& r = solver.solve();
  EXPECT_EQ(r.info.status, LcpStatus::solved);
  EXPECT_EQ(r.info.pivots, 0);
  EXPECT_EQ(r.z.norm(), 0.0);
}

TEST(LemkeDense, BadInputThrows) {
  LemkeSolver solver;
  EXPECT_THROW(solver.setup(SparseMatrix(2, 3), Vector::Zero(2)), InputError);
  EXPECT_THROW(solver.setup(sparse(DenseMatrix::Identity(2, 2)), Vector::Zero(3)), InputError);
  Vector q = Vector::Zero(2);
  q(1) = std::nan("");
  EXPECT_THROW(solver.setup(sparse(DenseMatrix::Identity(2, 2)), q), InputError);
  LemkeSettings s;
  s.covering = -Vector::Ones(2);
  EXPECT_THROW(LemkeSolver{s}, InputError);
}

// Random P-matrix (M = BBᵀ + I + S, S skew) and PSD (M = BBᵀ + S, B rank-deficient) LCPs.
DenseMatrix random_matrix(std::mt19937& rng, Index n, bool p_matrix) {
  std::normal_distribution<double> N(0.0, 1.0);
  DenseMatrix B = DenseMatrix::NullaryExpr(n, p_matrix ? n : n / 2, [&] { return N(rng); });
  DenseMatrix S = DenseMatrix::NullaryExpr(n, n, [&] { return N(rng); });
  S = 0.5 * (S - S.transpose()).eval();
  DenseMatrix M = B * B.transpose() + S;
  if (p_matrix) M += DenseMatrix::Identity(n, n);
  return M;
}

TEST(LemkeDense, WarmStartFromTheRightBasisTakesZeroPivots) {
  std::mt19937 rng(3);
  std::normal_distribution<double> N(0.0, 1.0);
  const DenseMatrix M = random_matrix(rng, 12, true);
  const Vector q = Vector::NullaryExpr(12, [&] { return N(rng); });
  LemkeSolver solver;
  solver.setup(sparse(M), q);
  const std::vector<bool> basis = solver.solve().z_basic;
  const Vector z = solver.result().z;
  EXPECT_GT(solver.result().info.pivots, 0);
  solver.warm_start(basis);
  const LcpResult& r = solver.solve();
  expect_lcp_solution(M, q, r);
  EXPECT_EQ(r.info.pivots, 0);
  EXPECT_TRUE(r.info.warm_started);
  EXPECT_LE((r.z - z).norm(), 1e-12);
}

// ℓ(z) = gᵀz: ∂ℓ/∂q and ∂ℓ/∂M_ij against central differences at non-degenerate solutions.
TEST(LemkeDense, BackwardMatchesCentralDifferences) {
  int checked = 0;
  for (bool p_matrix : {true, false}) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      std::mt19937 rng(seed + (p_matrix ? 0 : 100));
      std::normal_distribution<double> N(0.0, 1.0);
      const Index n = 8;
      const DenseMatrix M = random_matrix(rng, n, p_matrix);
      const Vector q = Vector::NullaryExpr(n, [&] { return N(rng); });
      const Vector g = Vector::NullaryExpr(n, [&] { return N(rng); });
      LemkeSolver solver;
      solver.setup(sparse(M), q);
      const LcpResult& r = solver.solve();
      if (r.info.status != LcpStatus::solved) continue;  // PSD LCPs may be infeasible
      bool degenerate = false;
      for (Index i = 0; i < n; ++i) degenerate |= std::max(r.z(i), r.w(i)) < 1e-6;
      if (degenerate) continue;
      ++checked;
      const LcpGradient grad = solver.backward(g);
      auto loss = [&](const DenseMatrix& Mp, const Vector& qp) {
        LemkeSolver s;
        s.setup(sparse(Mp), qp);
        const LcpResult& rp = s.solve();
        EXPECT_EQ(rp.info.status, LcpStatus::solved);
        return g.dot(rp.z);
      };
      const double h = 1e-6;
      for (Index i = 0; i < n; ++i) {
        Vector qp = q, qm = q;
        qp(i) += h;
        qm(i) -= h;
        EXPECT_NEAR((loss(M, qp) - loss(M, qm)) / (2 * h), grad.dq(i), 1e-6) << "dq " << i;
      }
      const DenseMatrix dM = grad.dM;
      for (Index i = 0; i < n; ++i)
        for (Index j = 0; j < n; ++j) {
          if (M(i, j) == 0.0) continue;
          DenseMatrix Mp = M, Mm = M;
          Mp(i, j) += h;
          Mm(i, j) -= h;
          EXPECT_NEAR((loss(Mp, q) - loss(Mm, q)) / (2 * h), dM(i, j), 1e-6) << "dM " << i << "," << j;
        }
    }
  }
  EXPECT_GE(checked, 4) << "too few non-degenerate cases were checked";
}

}  // namespace
}  // namespace lcprelax
