// QpSolver performs no heap allocation once its workspaces exist: after the first solve(),
// a second solve() on the same setup, and update() with new values (same pattern) followed
// by solve(), allocate nothing. Counted by tests/allocation_counter.hpp (malloc & co.
// interposed for this binary), over the whole calls, for
//   - a sparse QP (n = 200, equalities, two-sided and one-sided rows, bounds; KKT dimension
//     well above dense_max_kkt) through CHOLMOD's LDLᵀ of the full quasi-definite form;
//   - a small QP through the dense LDLᵀ backend, both forms (full and eliminated).
// Not covered: CHOLMOD's supernodal LLᵀ of the eliminated form, whose numeric factorization
// allocates inside CHOLMOD (the permuted transpose of the matrix, the dense update
// workspace, an OpenMP team per parallel region); the rest of the loop is the same code.
//   - update() + warm_start() + solve().
// Every counted solve must also be correct: status solved, residuals within eps, and the
// answer after update() equal to that of a fresh solver set up on the new problem.
#include "allocation_counter.hpp"

#include <lcprelax/kkt/qp_solver.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Random sparse convex QP around a feasible point x0: P = BᵀB + 0.1·I restricted to its
// upper triangle, A x0 = b, rows of G two-sided (l < Gx0 < u), lower- or upper-only, bounds
// on a third of the variables (two-sided) and a third (lower only). Every row couples
// variables within a window of 9 (banded data, so that the factors stay sparse).
QpProblem make_qp(unsigned seed, Index n, Index me, Index mi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> sym(-1.0, 1.0), pos(0.2, 1.0);
  std::uniform_int_distribution<Index> offset(-4, 4);
  const auto near = [&](Index center) { return std::clamp<Index>(center + offset(rng), 0, n - 1); };
  QpProblem p(n);
  std::vector<Triplet> tb;
  for (Index i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) tb.emplace_back(i, near(i), sym(rng));
  SparseMatrix B(n, n);
  B.setFromTriplets(tb.begin(), tb.end());
  SparseMatrix I(n, n);
  I.setIdentity();
  const SparseMatrix full = SparseMatrix(B.transpose() * B) + 0.1 * I;
  p.P = full.triangularView<Eigen::Upper>();
  p.P.makeCompressed();
  p.q = Vector::NullaryExpr(n, [&](Index) { return sym(rng); });
  const Vector x0 = Vector::NullaryExpr(n, [&](Index) { return sym(rng); });
  auto random_rows = [&](Index m) {
    std::vector<Triplet> t;
    for (Index i = 0; i < m; ++i)
      for (int k = 0; k < 4; ++k) t.emplace_back(i, near(i * n / m), sym(rng));
    SparseMatrix M(m, n);
    M.setFromTriplets(t.begin(), t.end());
    M.makeCompressed();
    return M;
  };
  p.A = random_rows(me);
  p.b = p.A * x0;
  p.G = random_rows(mi);
  const Vector g0 = p.G * x0;
  p.l.resize(mi);
  p.u.resize(mi);
  for (Index i = 0; i < mi; ++i) {
    p.l(i) = i % 3 == 2 ? -kInf : g0(i) - pos(rng);
    p.u(i) = i % 3 == 1 ? kInf : g0(i) + pos(rng);
  }
  for (Index j = 0; j < n; ++j) {
    if (j % 3 == 0) {
      p.xl(j) = x0(j) - pos(rng);
      p.xu(j) = x0(j) + pos(rng);
    } else if (j % 3 == 1) {
      p.xl(j) = x0(j) - pos(rng);
    }
  }
  return p;
}

// New values, same pattern and the same row classification, still feasible around a new x1.
QpProblem perturb(const QpProblem& p, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> sym(-1.0, 1.0), pos(0.2, 1.0), scale(0.5, 2.0);
  QpProblem r = p;
  r.P *= 1.5;
  for (Index k = 0; k < r.A.nonZeros(); ++k) r.A.valuePtr()[k] *= scale(rng);
  for (Index k = 0; k < r.G.nonZeros(); ++k) r.G.valuePtr()[k] *= scale(rng);
  r.q = Vector::NullaryExpr(p.q.size(), [&](Index) { return sym(rng); });
  const Vector x1 = Vector::NullaryExpr(p.q.size(), [&](Index) { return sym(rng); });
  r.b = r.A * x1;
  const Vector g1 = r.G * x1;
  for (Index i = 0; i < r.l.size(); ++i) {
    if (std::isfinite(r.l(i))) r.l(i) = g1(i) - pos(rng);
    if (std::isfinite(r.u(i))) r.u(i) = g1(i) + pos(rng);
  }
  for (Index j = 0; j < x1.size(); ++j) {
    if (std::isfinite(r.xl(j))) r.xl(j) = x1(j) - pos(rng);
    if (std::isfinite(r.xu(j))) r.xu(j) = x1(j) + pos(rng);
  }
  return r;
}

// Independent check of a solution against the problem (unscaled, ∞-norms).
void expect_optimal(const QpProblem& p, const QpResult& r, const QpSettings& s, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(r.info.status, QpStatus::solved) << r.info.message;
  EXPECT_LE(r.info.primal_residual, s.eps_abs);
  EXPECT_LE(r.info.dual_residual, s.eps_abs);
  EXPECT_LE(r.info.duality_gap, s.eps_abs);
  const Vector& x = r.x;
  double primal = p.num_equalities() ? (p.A * x - p.b).lpNorm<Eigen::Infinity>() : 0.0;
  const Vector gx = p.G * x;
  for (Index i = 0; i < gx.size(); ++i) primal = std::max({primal, p.l(i) - gx(i), gx(i) - p.u(i)});
  for (Index j = 0; j < x.size(); ++j) primal = std::max({primal, p.xl(j) - x(j), x(j) - p.xu(j)});
  const Vector dual = Vector(p.P.selfadjointView<Eigen::Upper>() * x) + p.q + p.A.transpose() * r.y +
                      p.G.transpose() * r.z + r.z_bounds;
  EXPECT_LE(primal, 1e-8);
  EXPECT_LE(dual.lpNorm<Eigen::Infinity>(), 1e-8);
}

struct Case {
  const char* name;
  Index n, me, mi;
  KktBackend backend;
  KktForm form;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class QpAllocation : public ::testing::TestWithParam<Case> {};

TEST_P(QpAllocation, SecondSolveAndUpdateAllocateNothing) {
  const Case c = GetParam();
  QpSettings s;
  s.kkt_backend = c.backend;
  s.kkt_form = c.form;
  const QpProblem p1 = make_qp(3, c.n, c.me, c.mi);
  const QpProblem p2 = perturb(p1, 4);
  ASSERT_TRUE(p1.same_pattern(p2));

  QpSolver solver(s);
  solver.setup(p1);
  const QpResult first = solver.solve();  // creates the factorization's workspaces
  expect_optimal(p1, first, s, "first solve");
  ASSERT_EQ(first.info.kkt_backend, c.backend);
  ASSERT_EQ(first.info.kkt_form, c.form);
  if (c.backend == KktBackend::cholmod) {
    ASSERT_GT(c.n + c.me + c.mi, s.dense_max_kkt);
  }

  // Second solve() on the same setup: whole call counted.
  long second_allocations = 0;
  {
    lcprelax::test::AllocationCounter counter;
    solver.solve();
    second_allocations = counter.stop();
  }
  EXPECT_EQ(second_allocations, 0);
  expect_optimal(p1, solver.result(), s, "second solve");
  EXPECT_EQ(solver.result().x, first.x);  // same setup, same cold start: same iterates

  // update() with new values (same pattern) + solve(): both calls counted.
  long update_allocations = 0;
  {
    lcprelax::test::AllocationCounter counter;
    solver.update(p2);
    solver.solve();
    update_allocations = counter.stop();
  }
  EXPECT_EQ(update_allocations, 0);
  const QpResult updated = solver.result();
  expect_optimal(p2, updated, s, "update + solve");
  QpSolver fresh(s);
  fresh.setup(p2);
  const QpResult& reference = fresh.solve();
  ASSERT_EQ(reference.info.status, QpStatus::solved);
  EXPECT_EQ(updated.info.iterations, reference.info.iterations);
  EXPECT_LE((updated.x - reference.x).lpNorm<Eigen::Infinity>(), 1e-12);

  // Back to p1 with a warm start at its solution: update() + warm_start() + solve().
  long warm_allocations = 0;
  {
    lcprelax::test::AllocationCounter counter;
    solver.update(p1);
    solver.warm_start(first.x, first.y, first.z, first.z_bounds);
    solver.solve();
    warm_allocations = counter.stop();
  }
  EXPECT_EQ(warm_allocations, 0);
  expect_optimal(p1, solver.result(), s, "update + warm start + solve");
}

INSTANTIATE_TEST_SUITE_P(
    Backends, QpAllocation,
    ::testing::Values(Case{"cholmod_full", 200, 20, 120, KktBackend::cholmod, KktForm::full},
                      Case{"dense_full", 10, 2, 8, KktBackend::dense, KktForm::full},
                      Case{"dense_eliminated", 10, 0, 8, KktBackend::dense, KktForm::eliminated}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace lcprelax
