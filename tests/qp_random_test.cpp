// Seeded random sparse convex QPs and LPs with a known KKT point, solved with every KKT form.
//
// Construction (so every problem is feasible and bounded): draw x0, a sparse P ⪰ 0, A, G,
// the row/bound types and multipliers (y0, z0, zb0) that obey the sign convention of
// qp_problem.hpp (z > 0 only on an active upper side, z < 0 only on an active lower side,
// any sign on an equality row or a fixed variable); then b = A x0, the row bounds are placed
// at or around G x0, and q = −(P x0 + Aᵀ y0 + Gᵀ z0 + zb0). (x0, y0, z0, zb0) then satisfies
// the KKT conditions, so x0 is optimal; with P ≻ 0 (P = BᵀB + 0.1·I) it is the unique optimum.
#include <lcprelax/kkt/qp_solver.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTol = 1e-7;

enum class Family { strict, singular, lp };

struct Options {
  Index n = 50;
  Family family = Family::strict;
  bool equalities = true;  // A (n/4 rows) and l = u rows in G
  bool fixed = true;       // variables with xl = xu
};

struct Generated {
  QpProblem p;
  Vector x0;
};

SparseMatrix random_sparse(std::mt19937& rng, Index rows, Index cols, int per_row, const std::vector<bool>& skip_col) {
  std::uniform_int_distribution<Index> col(0, cols - 1);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  std::vector<Triplet> t;
  for (Index i = 0; i < rows; ++i)
    for (int k = 0; k < per_row; ++k) {
      const Index j = col(rng);
      if (!skip_col[j]) t.emplace_back(i, j, val(rng));
    }
  SparseMatrix M(rows, cols);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

Generated make_problem(unsigned seed, const Options& o) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> sym(-1.0, 1.0), pos(0.1, 1.0);
  std::uniform_int_distribution<int> kind(0, 5);
  const Index n = o.n, me = o.equalities ? n / 4 : 0, mi = n / 2;
  Generated g{QpProblem(n), Vector(n)};
  QpProblem& p = g.p;
  for (Index j = 0; j < n; ++j) g.x0(j) = sym(rng);

  std::vector<bool> zero_col(n, false);
  if (o.family != Family::lp) {
    if (o.family == Family::singular)
      for (Index j = 0; j < n; j += 5) zero_col[j] = true;  // P has zero rows/columns here
    const Index rows = o.family == Family::singular ? n / 2 : n;  // rank(BᵀB) ≤ n/2 if singular
    const SparseMatrix B = random_sparse(rng, rows, n, 3, zero_col);
    SparseMatrix full = SparseMatrix(B.transpose()) * B;
    if (o.family == Family::strict) {
      SparseMatrix I(n, n);
      I.setIdentity();
      full += 0.1 * I;
    }
    p.P = full.triangularView<Eigen::Upper>();
  }
  const std::vector<bool> none(n, false);
  p.A = random_sparse(rng, me, n, 4, none);
  p.b = p.A * g.x0;
  const Vector y0 = Vector::NullaryExpr(me, [&](Index) { return sym(rng); });

  // Rows of G: 0 two-sided inactive, 1 two-sided lower active, 2 two-sided upper active,
  // 3 upper-only (active or not), 4 lower-only (active or not), 5 equality row (l = u).
  p.G = random_sparse(rng, mi, n, 4, none);
  const Vector gx = p.G * g.x0;
  p.l.resize(mi);
  p.u.resize(mi);
  Vector z0 = Vector::Zero(mi);
  for (Index i = 0; i < mi; ++i) {
    int k = kind(rng);
    if (k == 5 && !o.equalities) k = 0;
    const bool active = pos(rng) > 0.5;
    p.l(i) = gx(i) - pos(rng);
    p.u(i) = gx(i) + pos(rng);
    switch (k) {
      case 1: p.l(i) = gx(i); z0(i) = -pos(rng); break;
      case 2: p.u(i) = gx(i); z0(i) = pos(rng); break;
      case 3: p.l(i) = -kInf; if (active) { p.u(i) = gx(i); z0(i) = pos(rng); } break;
      case 4: p.u(i) = kInf; if (active) { p.l(i) = gx(i); z0(i) = -pos(rng); } break;
      case 5: p.l(i) = p.u(i) = gx(i); z0(i) = sym(rng); break;
      default: break;
    }
  }
  // Bounds: 0 free, 1 box inactive, 2 box lower active, 3 upper-only active,
  // 4 lower-only inactive, 5 fixed (or box upper active when fixed variables are off).
  Vector zb0 = Vector::Zero(n);
  for (Index j = 0; j < n; ++j) {
    const double x = g.x0(j);
    switch (kind(rng)) {
      case 0: break;
      case 1: p.xl(j) = x - pos(rng); p.xu(j) = x + pos(rng); break;
      case 2: p.xl(j) = x; p.xu(j) = x + pos(rng); zb0(j) = -pos(rng); break;
      case 3: p.xu(j) = x; zb0(j) = pos(rng); break;
      case 4: p.xl(j) = x - pos(rng); break;
      default:
        if (o.fixed) { p.xl(j) = p.xu(j) = x; zb0(j) = sym(rng); }
        else { p.xl(j) = x - pos(rng); p.xu(j) = x; zb0(j) = pos(rng); }
    }
  }
  const Vector Px0 = p.P.selfadjointView<Eigen::Upper>() * g.x0;
  p.q = -(Px0 + p.A.transpose() * y0 + p.G.transpose() * z0 + zb0);
  return g;
}

double dist_to_box(double v, double lo, double hi) { return std::max({lo - v, v - hi, 0.0}); }

// Complementarity with the sign convention: z > 0 must sit on an active upper side, z < 0
// on an active lower side. min(|z|, |v − side(z)|) is small iff z ≈ 0 or that side is active.
double complementarity(double z, double v, double lo, double hi) {
  const double side = z > 0 ? hi : lo;
  const double d = std::isfinite(side) ? std::fabs(v - side) : kInf;
  return std::min(std::fabs(z), d);
}

// Independent KKT check (qp_problem.hpp): stationarity P x + q + Aᵀy + Gᵀz + zb = 0,
// primal feasibility A x = b, l ≤ G x ≤ u, xl ≤ x ≤ xu, and complementarity per row/bound.
void expect_kkt(const QpProblem& p, const QpResult& r, double tol) {
  ASSERT_EQ(r.info.status, QpStatus::solved) << r.info.message;
  const Vector Px = p.P.selfadjointView<Eigen::Upper>() * r.x;
  const Vector stat = Px + p.q + p.A.transpose() * r.y + p.G.transpose() * r.z + r.z_bounds;
  EXPECT_LE(stat.lpNorm<Eigen::Infinity>(), tol) << "stationarity";
  if (p.num_equalities()) {
    EXPECT_LE((p.A * r.x - p.b).lpNorm<Eigen::Infinity>(), tol) << "Ax = b";
  }
  const Vector Gx = p.G * r.x;
  double prim = 0, comp = 0;
  for (Index i = 0; i < Gx.size(); ++i) {
    prim = std::max(prim, dist_to_box(Gx(i), p.l(i), p.u(i)));
    comp = std::max(comp, complementarity(r.z(i), Gx(i), p.l(i), p.u(i)));
  }
  for (Index j = 0; j < r.x.size(); ++j) {
    prim = std::max(prim, dist_to_box(r.x(j), p.xl(j), p.xu(j)));
    comp = std::max(comp, complementarity(r.z_bounds(j), r.x(j), p.xl(j), p.xu(j)));
  }
  EXPECT_LE(prim, tol) << "row/bound feasibility";
  EXPECT_LE(comp, tol) << "complementarity / multiplier signs";
}

QpResult solve_with(const QpProblem& p, KktForm form) {
  QpSettings s;
  s.kkt_form = form;
  QpSolver solver(s);
  solver.setup(p);
  return solver.solve();
}

using Param = std::tuple<Index, Family>;

std::string param_name(const ::testing::TestParamInfo<Param>& i) {
  const Family f = std::get<1>(i.param);
  return std::string(f == Family::strict ? "Strict" : f == Family::singular ? "Singular" : "Lp") + "N" +
         std::to_string(std::get<0>(i.param));
}

class RandomQp : public ::testing::TestWithParam<Param> {};

// Full problems (equalities, fixed and free variables): automatic and full forms.
TEST_P(RandomQp, AutomaticAndFullFormsSatisfyKkt) {
  const auto [n, family] = GetParam();
  for (unsigned seed = 1; seed <= 3; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Generated g = make_problem(1000 * n + seed, {n, family, true, true});
    const QpResult a = solve_with(g.p, KktForm::automatic);
    const QpResult f = solve_with(g.p, KktForm::full);
    expect_kkt(g.p, a, kTol);
    expect_kkt(g.p, f, kTol);
    EXPECT_EQ(f.info.kkt_form, KktForm::full);
    // Optimal values agree; with P ≻ 0 the optimum x0 is unique, so x agrees too.
    EXPECT_NEAR(a.info.objective, f.info.objective, 1e-7 * std::max(1.0, std::fabs(f.info.objective)));
    if (family == Family::strict) {
      EXPECT_LE((a.x - g.x0).lpNorm<Eigen::Infinity>(), 1e-6);
      EXPECT_LE((f.x - g.x0).lpNorm<Eigen::Infinity>(), 1e-6);
    }
  }
}

// Without equality rows and fixed variables the eliminated (Schur complement) form applies.
TEST_P(RandomQp, FullAndEliminatedFormsAgree) {
  const auto [n, family] = GetParam();
  for (unsigned seed = 11; seed <= 13; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Generated g = make_problem(1000 * n + seed, {n, family, false, false});
    ASSERT_EQ(g.p.num_equalities(), 0);
    const QpResult f = solve_with(g.p, KktForm::full);
    const QpResult e = solve_with(g.p, KktForm::eliminated);
    expect_kkt(g.p, f, kTol);
    expect_kkt(g.p, e, kTol);
    EXPECT_EQ(f.info.kkt_form, KktForm::full);
    EXPECT_EQ(e.info.kkt_form, KktForm::eliminated);
    EXPECT_NEAR(e.info.objective, f.info.objective, 1e-7 * std::max(1.0, std::fabs(f.info.objective)));
    if (family == Family::strict) {
      EXPECT_LE((f.x - e.x).lpNorm<Eigen::Infinity>(), 1e-6);
      EXPECT_LE((e.x - g.x0).lpNorm<Eigen::Infinity>(), 1e-6);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(All, RandomQp,
                         ::testing::Combine(::testing::Values(10, 50, 200),
                                            ::testing::Values(Family::strict, Family::singular, Family::lp)),
                         param_name);

}  // namespace
}  // namespace lcprelax
