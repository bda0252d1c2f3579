#pragma once
// A generated family of degenerate LPs/QPs of the Maros–Meszaros kind, shared by the QP
// tests (qp_degenerate_lp_test, qp_polish_test):
//   min ½xᵀPx + qᵀx  s.t.  Gx ≥ l,  0 ≤ x ≤ U (= big),
// built around a vertex x0 with half of its variables at 0 and others at U (primal
// degenerate: 60% of the rows tight at x0 as well), and q = Gᵀw − z_b − P x0 from
// nonnegative multipliers w on half of the tight rows and z_b on 70% of the active bounds
// (dual degenerate: the optimal multiplier set is not a point), so x0 is optimal. Row
// entries span 10^spread (badly scaled). With `quadratic`, odd seeds get a diagonal P on
// every other variable (0.1…0.3); even seeds and quadratic = false are LPs.
#include <lcprelax/kkt/qp_problem.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace lcprelax::testing {

inline QpProblem make_degenerate_qp(unsigned seed, Index n, Index m, double big, double spread, bool quadratic) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const auto mag = [&]() { return std::pow(10.0, spread * (u01(rng) - 0.5)); };
  QpProblem p(n);
  std::vector<Triplet> t;
  for (Index i = 0; i < m; ++i)
    for (int k = 0; k < 4; ++k)
      t.emplace_back(i, (i * 7 + k * 13 + static_cast<Index>(u01(rng) * 5)) % n, (u01(rng) - 0.3) * mag());
  SparseMatrix G(m, n);
  G.setFromTriplets(t.begin(), t.end());
  Vector x0(n);
  for (Index j = 0; j < n; ++j) x0(j) = u01(rng) < 0.5 ? 0.0 : (u01(rng) < 0.3 ? big : big * u01(rng));
  const Vector g0 = G * x0;
  p.G = G;
  p.l = Vector(m);
  p.u = Vector::Constant(m, std::numeric_limits<double>::infinity());
  for (Index i = 0; i < m; ++i) p.l(i) = u01(rng) < 0.6 ? g0(i) : g0(i) - big * u01(rng);
  p.xl = Vector::Zero(n);
  p.xu = Vector::Constant(n, big);
  Vector w = Vector::Zero(m);
  for (Index i = 0; i < m; ++i)
    if (p.l(i) == g0(i) && u01(rng) < 0.5) w(i) = mag();
  Vector zb = Vector::Zero(n);
  for (Index j = 0; j < n; ++j) {
    if (x0(j) == 0.0 && u01(rng) < 0.7) zb(j) = -mag();
    if (x0(j) == big && u01(rng) < 0.7) zb(j) = mag();
  }
  if (quadratic && seed % 2) {
    std::vector<Triplet> d;
    for (Index j = 0; j < n; j += 2) d.emplace_back(j, j, 0.1 * (1 + j % 3));
    p.P.setFromTriplets(d.begin(), d.end());
  }
  // Stationarity at x0 with z = −w (lower sides) and z_b: x0 is optimal.
  p.q = G.transpose() * w - zb - p.P.selfadjointView<Eigen::Upper>() * x0;
  return p;
}

/// u z⁺ + l z⁻ as a double product (qpbenchmark's float64 definition of a support term).
inline double support_term(double z, double lo, double hi) {
  if (z > 0) return hi * z;
  if (z < 0) return lo * z;
  return 0.0;
}

}  // namespace lcprelax::testing
