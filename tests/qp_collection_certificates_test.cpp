// Infeasibility certificates on problems of the Maros–Meszaros collection's style: real
// collection problems (tests/data/maros_meszaros) made infeasible or unbounded by one
// change, as a modelling error would, and solved with the default QpSettings.
// - Primal infeasible: a copy of one row of the problem whose bounds contradict the
//   original's (l' = u + 1 for a row with finite u, or u' = l − 1), on QAFIRO (LP rows,
//   diagonal P), CVXQP1_S, HS118, QSCAGR7, QSHARE1B, DUALC1 and PRIMAL1. Certificate (qp_result.hpp): z, z_bounds with
//   ‖·‖∞ = 1, ‖Gᵀz + z_bounds‖∞ ≤ 1e-6 and Σ u_i z_i⁺ + l_i z_i⁻ + (bounds) ≤ −1e-6, with
//   no infinite bound paired with a nonzero multiplier of its sign.
// - Dual infeasible: two new variables t1, t2 ≥ 0 (costs −1 and 0, no quadratic term)
//   entering the first row as t1 − t2, so that t1 = t2 → ∞ keeps every row feasible and
//   lowers the objective without bound.
//   Certificate: x with ‖x‖∞ = 1, ‖Px‖∞ ≤ 1e-6, Gx in the recession cone of [l, u] and
//   of the bounds (to 1e-6), qᵀx ≤ −1e-6.
#include <lcprelax/io/qps_reader.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

QpProblem load(const std::string& name) {
  return io::read_qps(std::string(LCPRELAX_TEST_DATA_DIR) + "/maros_meszaros/" + name + ".qps").problem;
}

SparseMatrix with_rows(const SparseMatrix& G, const std::vector<Triplet>& extra, Index rows, Index cols) {
  std::vector<Triplet> t(extra);
  for (Index j = 0; j < G.outerSize(); ++j)
    for (SparseMatrix::InnerIterator e(G, j); e; ++e) t.emplace_back(e.row(), e.col(), e.value());
  SparseMatrix out(rows, cols);
  out.setFromTriplets(t.begin(), t.end());
  out.makeCompressed();
  return out;
}

// The first row with a finite side gets a contradicting copy appended.
QpProblem contradicting_row(QpProblem p) {
  const Index m = p.num_inequalities(), n = p.num_variables();
  Index row = -1;
  for (Index i = 0; i < m && row < 0; ++i)
    if (std::isfinite(p.u(i)) || std::isfinite(p.l(i))) row = i;
  EXPECT_GE(row, 0);
  const SparseMatrix Gr = SparseMatrix(p.G.row(row));
  std::vector<Triplet> extra;
  for (Index j = 0; j < Gr.outerSize(); ++j)
    for (SparseMatrix::InnerIterator e(Gr, j); e; ++e) extra.emplace_back(m, e.col(), e.value());
  p.G = with_rows(p.G, extra, m + 1, n);
  p.l.conservativeResize(m + 1);
  p.u.conservativeResize(m + 1);
  if (std::isfinite(p.u(row))) {
    p.l(m) = p.u(row) + 1.0;
    p.u(m) = kInf;
  } else {
    p.l(m) = -kInf;
    p.u(m) = p.l(row) - 1.0;
  }
  return p;
}

// Two new variables t1, t2 ≥ 0 with costs −1 and 0 and P = 0 on them, entering the first
// row as t1 − t2: the direction t1 = t2 = 1 keeps every row and bound feasible and lowers
// the objective without bound.
QpProblem unbounded_columns(QpProblem p) {
  const Index m = p.num_inequalities(), n = p.num_variables();
  EXPECT_GT(m, 0);
  SparseMatrix G(m, n + 2);
  std::vector<Triplet> t{Triplet(0, n, 1.0), Triplet(0, n + 1, -1.0)};
  for (Index j = 0; j < p.G.outerSize(); ++j)
    for (SparseMatrix::InnerIterator e(p.G, j); e; ++e) t.emplace_back(e.row(), e.col(), e.value());
  G.setFromTriplets(t.begin(), t.end());
  G.makeCompressed();
  p.G = G;
  p.A.resize(0, n + 2);
  p.P.conservativeResize(n + 2, n + 2);
  p.P.makeCompressed();
  p.q.conservativeResize(n + 2);
  p.q(n) = -1.0;
  p.q(n + 1) = 0.0;
  p.xl.conservativeResize(n + 2);
  p.xu.conservativeResize(n + 2);
  p.xl.tail(2).setZero();
  p.xu.tail(2).setConstant(kInf);
  return p;
}

// u z⁺ + l z⁻; an infinite side with a multiplier of its sign makes the certificate invalid.
double support(double z, double lo, double hi) {
  if (z > 0) return std::isfinite(hi) ? hi * z : kInf;
  if (z < 0) return std::isfinite(lo) ? lo * z : kInf;
  return 0.0;
}

void expect_primal_certificate(const QpProblem& p, const QpResult& r) {
  ASSERT_EQ(r.z.size(), p.num_inequalities());
  ASSERT_EQ(r.z_bounds.size(), p.num_variables());
  const double norm = std::max(r.z.lpNorm<Eigen::Infinity>(), r.z_bounds.lpNorm<Eigen::Infinity>());
  EXPECT_NEAR(norm, 1.0, 1e-9);
  const Vector stationarity = p.G.transpose() * r.z + r.z_bounds;
  EXPECT_LE(stationarity.lpNorm<Eigen::Infinity>(), 1e-6);
  double s = 0.0;
  for (Index i = 0; i < r.z.size(); ++i) s += support(r.z(i), p.l(i), p.u(i));
  for (Index j = 0; j < r.z_bounds.size(); ++j) s += support(r.z_bounds(j), p.xl(j), p.xu(j));
  EXPECT_LE(s, -1e-6);
}

void expect_dual_certificate(const QpProblem& p, const QpResult& r) {
  ASSERT_EQ(r.x.size(), p.num_variables());
  const Vector& d = r.x;
  EXPECT_NEAR(d.lpNorm<Eigen::Infinity>(), 1.0, 1e-9);
  const Vector Pd = p.P.selfadjointView<Eigen::Upper>() * d;
  EXPECT_LE(Pd.lpNorm<Eigen::Infinity>(), 1e-6);
  const Vector Gd = p.G * d;
  for (Index i = 0; i < Gd.size(); ++i) {
    if (std::isfinite(p.u(i))) {
      EXPECT_LE(Gd(i), 1e-6) << "row " << i;
    }
    if (std::isfinite(p.l(i))) {
      EXPECT_GE(Gd(i), -1e-6) << "row " << i;
    }
  }
  for (Index j = 0; j < d.size(); ++j) {
    if (std::isfinite(p.xu(j))) {
      EXPECT_LE(d(j), 1e-6) << "variable " << j;
    }
    if (std::isfinite(p.xl(j))) {
      EXPECT_GE(d(j), -1e-6) << "variable " << j;
    }
  }
  EXPECT_LE(p.q.dot(d), -1e-6);
}

class CollectionCertificates : public ::testing::TestWithParam<std::string> {};

TEST_P(CollectionCertificates, ContradictingRowIsPrimalInfeasible) {
  const QpProblem p = contradicting_row(load(GetParam()));
  ASSERT_EQ(p.validation_error(), "");
  QpSolver solver;
  solver.setup(p);
  const QpResult& r = solver.solve();
  ASSERT_EQ(r.info.status, QpStatus::primal_infeasible) << r.info.message;
  expect_primal_certificate(p, r);
}

TEST_P(CollectionCertificates, UnboundedColumnIsDualInfeasible) {
  const QpProblem p = unbounded_columns(load(GetParam()));
  ASSERT_EQ(p.validation_error(), "");
  QpSolver solver;
  solver.setup(p);
  const QpResult& r = solver.solve();
  ASSERT_EQ(r.info.status, QpStatus::dual_infeasible) << r.info.message;
  expect_dual_certificate(p, r);
}

INSTANTIATE_TEST_SUITE_P(MarosMeszaros, CollectionCertificates, ::testing::Values("QAFIRO", "CVXQP1_S", "HS118", "QSCAGR7", "QSHARE1B", "DUALC1", "PRIMAL1"));

}  // namespace
}  // namespace lcprelax
