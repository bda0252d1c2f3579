#pragma once
// LISWET-like convex data fits (Li & Swetits' problems of the Maros–Meszaros collection) for
// the QP tests: min ½‖x − c‖² subject to x_i − 2x_{i+1} + x_{i+2} ≥ 0 (i < n − 2), x free,
// c_j = data(t_j, j) at t_j = j/(n − 1); and the check that a result is solved, with the
// residuals of qp_settings.hpp recomputed from the data (A is empty, x is free, l = 0).
#include <lcprelax/kkt/qp_solver.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace lcprelax::testing_support {

template <class Data>
QpProblem make_liswet_fit(Index n, Data data) {
  const double inf = std::numeric_limits<double>::infinity();
  QpProblem p;
  const Index m = n - 2;
  std::vector<Triplet> tp, tg;
  for (Index j = 0; j < n; ++j) tp.emplace_back(j, j, 1.0);
  p.P.resize(n, n);
  p.P.setFromTriplets(tp.begin(), tp.end());
  p.q.resize(n);
  for (Index j = 0; j < n; ++j) p.q(j) = -data(static_cast<double>(j) / static_cast<double>(n - 1), j);
  for (Index i = 0; i < m; ++i) {
    tg.emplace_back(i, i, 1.0);
    tg.emplace_back(i, i + 1, -2.0);
    tg.emplace_back(i, i + 2, 1.0);
  }
  p.A.resize(0, n);
  p.b.resize(0);
  p.G.resize(m, n);
  p.G.setFromTriplets(tg.begin(), tg.end());
  p.l = Vector::Zero(m);
  p.u = Vector::Constant(m, inf);
  p.xl = Vector::Constant(n, -inf);
  p.xu = Vector::Constant(n, inf);
  return p;
}

inline void expect_liswet_solved(const QpProblem& p, const QpResult& r) {
  ASSERT_EQ(r.info.status, QpStatus::solved) << r.info.message;
  const Vector Gx = p.G * r.x, Px = p.P.selfadjointView<Eigen::Upper>() * r.x;
  EXPECT_LE(std::max(0.0, (p.l - Gx).maxCoeff()), 2e-9);
  EXPECT_LE((Px + p.q + p.G.transpose() * r.z + r.z_bounds).lpNorm<Eigen::Infinity>(), 2e-9);
  const long double gap = static_cast<long double>(r.x.dot(Px)) + static_cast<long double>(p.q.dot(r.x));
  EXPECT_LE(std::fabs(static_cast<double>(gap)), 2e-9);  // l = 0: the support terms vanish
  EXPECT_LE(r.z.maxCoeff(), 2e-9) << "lower sides only: z <= 0";
}

}  // namespace lcprelax::testing_support
