#pragma once
// Seeded random feasible sparse convex QPs shared by the QP tests: P = upper(BᵀB) + 0.1·I,
// n/6 equality rows with b = A·x0, n/2 rows of G with l ≤ G·x0 ≤ u (some one-sided, and
// with equality_rows some l = u = G_i·x0), and box bounds around x0 on some variables.
#include <lcprelax/kkt/qp_problem.hpp>

#include <limits>
#include <random>
#include <vector>

namespace lcprelax::testing_support {

inline SparseMatrix random_sparse(std::mt19937& rng, Index rows, Index cols, int per_row) {
  std::uniform_int_distribution<Index> col(0, cols - 1);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::vector<Triplet> t;
  for (Index i = 0; i < rows; ++i)
    for (int k = 0; k < per_row; ++k) t.emplace_back(i, col(rng), val(rng));
  SparseMatrix M(rows, cols);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

inline QpProblem make_random_qp(unsigned seed, Index n, bool equality_rows) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> sym(-1.0, 1.0), pos(0.1, 1.0);
  std::uniform_int_distribution<int> kind(0, equality_rows ? 3 : 2);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  QpProblem p(n);
  const Vector x0 = Vector::NullaryExpr(n, [&](Index) { return sym(rng); });
  const SparseMatrix B = random_sparse(rng, n, n, 3);
  SparseMatrix I(n, n);
  I.setIdentity();
  const SparseMatrix full = SparseMatrix(SparseMatrix(B.transpose()) * B) + 0.1 * I;
  p.P = full.triangularView<Eigen::Upper>();
  p.q = Vector::NullaryExpr(n, [&](Index) { return 3 * sym(rng); });
  p.A = random_sparse(rng, n / 6, n, 4);
  p.b = p.A * x0;
  p.G = random_sparse(rng, n / 2, n, 4);
  const Vector gx = p.G * x0;
  p.l = gx - Vector::NullaryExpr(gx.size(), [&](Index) { return pos(rng); });
  p.u = gx + Vector::NullaryExpr(gx.size(), [&](Index) { return pos(rng); });
  for (Index i = 0; i < gx.size(); ++i) {
    const int k = kind(rng);
    if (k == 1) p.l(i) = -kInf;
    if (k == 2) p.u(i) = kInf;
    if (k == 3 && i % 2) p.l(i) = p.u(i) = gx(i);  // some equality rows
  }
  for (Index j = 0; j < n; ++j) {
    const int k = kind(rng);
    if (k >= 1) p.xl(j) = x0(j) - pos(rng);
    if (k >= 2) p.xu(j) = x0(j) + pos(rng);
  }
  return p;
}

}  // namespace lcprelax::testing_support
