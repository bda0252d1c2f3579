#pragma once
// Shared pieces of the Lemke crash-start tests (lcp_crash_start_test, lcp_crash_flip_test,
// lcp_lemke_purify_test): a P-matrix LCP with a perturbed right-hand side to take a crash
// basis from, the central-difference check of ∂(wᵀz)/∂q, and Siconos' fc2d error of an LCP
// solution on the problem scaled to ‖q‖₂ = 1.
#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace lcprelax::test {

/// M = AᵀA + I (A with a third of its entries standard normal, seed `seed`): a P-matrix, so
/// the LCP has one solution, nondegenerate for a random q. q standard normal, q_guess = q
/// plus 0.5 × standard normal noise (the LCP whose basis seeds a crash start), w the
/// weights of the loss ℓ = wᵀz.
struct PMatrixLcp {
  SparseMatrix M;
  Vector q, q_guess, w;
};

inline PMatrixLcp p_matrix_lcp(Index n, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  DenseMatrix A(n, n);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j) A(i, j) = (i + j) % 3 == 0 ? normal(gen) : 0.0;
  PMatrixLcp p;
  p.M = DenseMatrix(A.transpose() * A + DenseMatrix::Identity(n, n)).sparseView();
  p.q.resize(n);
  p.q_guess.resize(n);
  p.w.resize(n);
  for (Index i = 0; i < n; ++i) {
    p.q(i) = normal(gen);
    p.q_guess(i) = p.q(i) + 0.5 * normal(gen);
    p.w(i) = 1.0 + 0.1 * (i % 5);
  }
  return p;
}

/// Expects grad = ∂(wᵀz)/∂q at every entry of q, against central differences of cold Lemke
/// solves (h = 1e-6, tolerance 1e-6 relative).
inline void expect_q_gradient_matches_central_differences(const PMatrixLcp& p, const Vector& grad) {
  const double h = 1e-6;
  for (Index k = 0; k < p.q.size(); ++k) {
    Vector qp = p.q, qm = p.q;
    qp(k) += h;
    qm(k) -= h;
    LemkeSolver sp, sm;
    sp.setup(p.M, qp);
    sm.setup(p.M, qm);
    const LcpResult& a = sp.solve();
    const LcpResult& b = sm.solve();
    ASSERT_TRUE(a.info.status == LcpStatus::solved && b.info.status == LcpStatus::solved);
    const double fd = (p.w.dot(a.z) - p.w.dot(b.z)) / (2 * h);
    EXPECT_NEAR(grad(k), fd, 1e-6 * (1.0 + std::abs(fd))) << "q entry " << k;
  }
}

/// Siconos' fc2d error of the LCP solution z (fc2d_to_lcp's layout) on the problem scaled to
/// ‖q‖₂ = 1 (tiny-q problems are otherwise absolute).
inline double scaled_fc2d_error(const io::Fc2dData& d, const Vector& z) {
  Vector r, u;
  fc2d_from_lcp(z, d.W, d.q, r, u);
  io::Fc2dData s = d;
  const double norm = d.q.norm() > 0 ? d.q.norm() : 1.0;
  s.q /= norm;
  return io::fc2d_error(s, r / norm);
}

}  // namespace lcprelax::test
