#pragma once
// Seeded generator of random sparse convex QPs for the benchmarks (header-only: bench/
// builds every bench_*.cpp and run_*.cpp as its own program).
//
// For n variables the problem is
//     minimize    ½ xᵀ P x + qᵀ x
//     subject to  A x = b          (n/4 rows, 3 nonzeros each)
//                 l ≤ G x ≤ u      (n/2 rows, 4 nonzeros each, ~20% one-sided)
//                 xl ≤ x ≤ xu      (~90% of the variables boxed, the rest free)
// with
// - local random structure: every row of M, A and G draws its columns from a window of
//   ±bandwidth columns around an anchor that sweeps 0 … n−1, so the KKT factor's fill
//   grows linearly in n (uniformly random patterns are expanders whose fill grows about
//   quadratically: n = 10⁵ would not fit any direct factorization);
// - P = MᵀM + αI (upper triangle stored), M n×n with 2 or 3 nonzeros per row, so that a
//   column of P holds about 1 + 2.5·1.5 ≈ 5 nonzeros; P is positive definite (α > 0), so
//   the problem is bounded whatever the constraints;
// - a point x0 ∈ [−1, 1]ⁿ with b = A x0, l < G x0 < u and xl < x0 < xu, so that the
//   problem is strictly feasible (b is in A's range because it is built from x0);
// - equality row i always touches its anchor column 4i (a matching of rows to distinct
//   columns), so A has full row rank with probability one;
// - q ~ N(0, σ²) large enough that a fair share of the inequalities and bounds is active
//   at the optimum (the backward pass then sees a nontrivial active set).
// The loss gradient ∂ℓ/∂x is an independent N(0, 1) vector.
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/sparse/types.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace lcprelax::bench {

struct RandomQp {
  QpProblem problem;
  Vector x0;     ///< the strictly feasible point the data were built around
  Vector dl_dx;  ///< random loss gradient for backward()
};

struct RandomQpOptions {
  double alpha = 0.1;            ///< P = MᵀM + αI
  double q_scale = 5.0;          ///< standard deviation of q
  double one_sided_rows = 0.2;   ///< fraction of G rows with l = −∞
  double free_variables = 0.1;   ///< fraction of variables without bounds
  Index bandwidth = 16;          ///< half-width of the column window of each row
};

namespace detail {

/// k distinct random columns in [anchor − w, anchor + w] ∩ [0, n), appended to `cols`
/// (fewer when the window holds fewer than k columns).
inline void sample_columns(std::mt19937_64& rng, Index n, Index anchor, Index w, int k, std::vector<Index>& cols) {
  const Index lo = std::max<Index>(0, anchor - w), hi = std::min<Index>(n - 1, anchor + w);
  std::uniform_int_distribution<Index> pick(lo, hi);
  const std::size_t start = cols.size();
  k = std::min<int>(k, hi - lo + 1 - static_cast<int>(start));
  while (static_cast<int>(cols.size() - start) < k) {
    const Index c = pick(rng);
    if (std::find(cols.begin(), cols.end(), c) == cols.end()) cols.push_back(c);
  }
}

/// rows×n sparse matrix with `per_row` nonzeros of magnitude in [0.1, 1] per row; row i
/// has anchor column a = ⌊i·n/rows⌋, always holds column a, and draws the others from a ± w.
inline SparseMatrix random_rows(std::mt19937_64& rng, Index rows, Index n, int per_row, Index w) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Triplet> triplets;
  triplets.reserve(static_cast<std::size_t>(rows) * static_cast<std::size_t>(per_row));
  std::vector<Index> cols;
  for (Index i = 0; i < rows; ++i) {
    const Index anchor = static_cast<Index>(static_cast<std::int64_t>(i) * n / rows);
    cols.assign(1, anchor);
    sample_columns(rng, n, anchor, w, per_row - 1, cols);
    for (Index c : cols) {
      double v = value(rng);
      if (std::abs(v) < 0.1) v = v < 0.0 ? -0.1 : 0.1;  // keep entries away from zero
      triplets.emplace_back(i, c, v);
    }
  }
  SparseMatrix m(rows, n);
  m.setFromTriplets(triplets.begin(), triplets.end());
  m.makeCompressed();
  return m;
}

}  // namespace detail

/// A random feasible, bounded, sparse convex QP with n ≥ 4 variables (see file comment).
/// The same (n, seed, options) always gives the same problem with the same library build.
inline RandomQp make_random_qp(Index n, std::uint64_t seed, const RandomQpOptions& opt = {}) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(n));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> sym(-1.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);

  RandomQp out;
  QpProblem& p = out.problem;

  // P = upper(MᵀM + αI), M with 2 or 3 nonzeros per row.
  {
    std::vector<Triplet> triplets;
    std::vector<Index> cols;
    for (Index i = 0; i < n; ++i) {
      cols.clear();
      detail::sample_columns(rng, n, i, opt.bandwidth, unit(rng) < 0.5 ? 2 : 3, cols);
      for (Index c : cols) triplets.emplace_back(i, c, sym(rng));
    }
    SparseMatrix m(n, n);
    m.setFromTriplets(triplets.begin(), triplets.end());
    SparseMatrix mtm = SparseMatrix(m.transpose()) * m;
    SparseMatrix identity(n, n);
    identity.setIdentity();
    SparseMatrix full = mtm + opt.alpha * identity;
    p.P = full.triangularView<Eigen::Upper>();
    p.P.makeCompressed();
  }

  out.x0 = Vector::NullaryExpr(n, [&]() { return sym(rng); });
  const Vector& x0 = out.x0;

  p.q = Vector::NullaryExpr(n, [&]() { return opt.q_scale * normal(rng); });

  p.A = detail::random_rows(rng, n / 4, n, 3, opt.bandwidth);
  p.b = p.A * x0;

  p.G = detail::random_rows(rng, n / 2, n, 4, opt.bandwidth);
  const Vector g0 = p.G * x0;
  p.l.resize(p.G.rows());
  p.u.resize(p.G.rows());
  for (Index i = 0; i < p.G.rows(); ++i) {
    p.l[i] = unit(rng) < opt.one_sided_rows ? -inf : g0[i] - 0.1 - 0.9 * unit(rng);
    p.u[i] = g0[i] + 0.1 + 0.9 * unit(rng);
  }

  p.xl.resize(n);
  p.xu.resize(n);
  for (Index j = 0; j < n; ++j) {
    if (unit(rng) < opt.free_variables) {
      p.xl[j] = -inf;
      p.xu[j] = inf;
    } else {
      p.xl[j] = x0[j] - 0.2 - 0.8 * unit(rng);
      p.xu[j] = x0[j] + 0.2 + 0.8 * unit(rng);
    }
  }

  out.dl_dx = Vector::NullaryExpr(n, [&]() { return normal(rng); });
  return out;
}

}  // namespace lcprelax::bench
