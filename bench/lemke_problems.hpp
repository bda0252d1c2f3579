#pragma once
// Seeded generators of Lemke benchmark problems, shared by bench_lemke and
// run_lemke_peers (header-only: bench/ builds every bench_*.cpp and run_*.cpp as its own
// program).
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/sparse/types.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace lcprelax::bench {

// A 2-D pile of nc rigid bodies (x, y, θ; mass 0.5…2, inertia m/10) and nc contacts:
// contact c holds body c on body c − 1 − (0…2), or on the static ground when that index
// is negative; its normal is tilted up to ±0.6 rad from vertical, lever arms are ≤ 0.5 m.
// J (2nc × 3nc, rows: normal then tangent per contact) has a 2 × 3 block per body
// touched. Body c is the upper body of contact c only, so J restricted to the (x, y)
// columns of the upper bodies is block lower triangular with orthonormal 2 × 2 diagonal
// blocks: J has full row rank and W = J M⁻¹ Jᵀ (the Delassus operator: 2 × 2 blocks on
// the diagonal and one per pair of contacts sharing a body) is positive definite, so the
// problem has a solution for any q. (With fewer bodies than contacts, ⌈2nc/3⌉, W came
// out singular at 640 contacts and Lemke ended on a ray: no solution for that q.)
// q: normal velocities −U(0.05, 1) (approaching), tangential U(−0.5, 0.5); μ = 0.5.
inline io::Fc2dData make_pile(Index nc, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Index nb = nc;
  Vector inv_mass(3 * nb);
  for (Index b = 0; b < nb; ++b) {
    const double m = 0.5 + 1.5 * U(rng);
    inv_mass.segment<3>(3 * b) << 1 / m, 1 / m, 10 / m;
  }
  std::vector<Triplet> t;
  auto add_body = [&](Index row, Index body, double sign, double dx, double dy, double rx, double ry) {
    t.emplace_back(row, 3 * body, sign * dx);
    t.emplace_back(row, 3 * body + 1, sign * dy);
    t.emplace_back(row, 3 * body + 2, sign * (rx * dy - ry * dx));  // (r × d)
  };
  for (Index c = 0; c < nc; ++c) {
    const Index j = c;
    const Index i = j - 1 - static_cast<Index>(3 * U(rng));  // < 0: the ground
    const double angle = M_PI / 2 + 1.2 * (U(rng) - 0.5);
    const double nx = std::cos(angle), ny = std::sin(angle), tx = ny, ty = -nx;
    const double rjx = U(rng) - 0.5, rjy = -0.5 * U(rng), rix = U(rng) - 0.5, riy = 0.5 * U(rng);
    add_body(2 * c, j, 1.0, nx, ny, rjx, rjy);
    add_body(2 * c + 1, j, 1.0, tx, ty, rjx, rjy);
    if (i >= 0) {
      add_body(2 * c, i, -1.0, nx, ny, rix, riy);
      add_body(2 * c + 1, i, -1.0, tx, ty, rix, riy);
    }
  }
  SparseMatrix J(2 * nc, 3 * nb);
  J.setFromTriplets(t.begin(), t.end());
  io::Fc2dData d;
  d.contacts = nc;
  d.W = J * inv_mass.asDiagonal() * SparseMatrix(J.transpose());
  d.W.makeCompressed();
  d.q.resize(2 * nc);
  for (Index c = 0; c < nc; ++c) d.q.segment<2>(2 * c) << -(0.05 + 0.95 * U(rng)), U(rng) - 0.5;
  d.mu = Vector::Constant(nc, 0.5);
  return d;
}

// Nonsymmetric, strictly row diagonally dominant with positive diagonal (a P-matrix),
// 4 random off-diagonal entries per row; q ~ N(0, 1).
inline void make_random_p(Index n, unsigned seed, SparseMatrix& M, Vector& q) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  std::uniform_int_distribution<Index> col(0, n - 1);
  std::vector<Triplet> t;
  for (Index i = 0; i < n; ++i) {
    double off = 0.0;
    for (int e = 0; e < 4; ++e) {
      const Index j = col(rng);
      if (j == i) continue;
      const double v = N(rng);
      off += std::abs(v);
      t.emplace_back(i, j, v);
    }
    t.emplace_back(i, i, off + 0.1 + 0.9 * std::abs(N(rng)));
  }
  M.resize(n, n);
  M.setFromTriplets(t.begin(), t.end());
  M.makeCompressed();
  q = Vector::NullaryExpr(n, [&] { return N(rng); });
}

}  // namespace lcprelax::bench
