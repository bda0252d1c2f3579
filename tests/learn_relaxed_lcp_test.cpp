// The relaxed (soft-LCP) loss of learn/relaxed_lcp.hpp:
// - the envelope-theorem gradient equals the adjoint (QpSolver::backward) gradient on random
//   small problems with a PSD symmetric part of M, for every option combination (soft
//   nonnegativity, soft lambdas, l1 softness, max dissipation none/qp/ext), to 1e-6 relative
//   to the largest gradient entry;
// - both equal central finite differences of c in q, p, x̄ and M (step 1e-6, 1e-5 relative);
// - on the 1-D block with m = mg = 1 the cost equals the seeds' formula written out by
//   hand at the QP solution (a1‖Pλ+p−x̄‖² + a2λᵀ(Mλ+q) + ½ε‖λ‖²);
// - an indefinite Hessian is reported as status nonconvex (policy report) or solved after
//   a reported diagonal shift (policy shift); bad data are InputErrors naming the field;
// - a workspace reused over samples (QP values written in place while the pattern repeats,
//   rebuilt on a pattern change) gives bit for bit the result of a fresh workspace.
#include <lcprelax/learn/relaxed_lcp.hpp>
#include <lcprelax/models/block1d.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <random>

namespace lcprelax::learn {
namespace {

SparseMatrix sparse(const DenseMatrix& A) {
  SparseMatrix S = A.sparseView(0.0, 0.0);
  S.makeCompressed();
  return S;
}

// n×n M = AᵀA + K (K skew-symmetric), P k×n, E 1×n: M's symmetric part is PSD.
RelaxedLcpData random_problem(std::mt19937_64& rng, Index n, Index k) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  DenseMatrix A(n, n), K = DenseMatrix::Zero(n, n), P(k, n), E(1, n);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j) A(i, j) = U(rng);
  for (Index i = 0; i < n; ++i)
    for (Index j = i + 1; j < n; ++j) K(i, j) = -(K(j, i) = U(rng));
  for (Index i = 0; i < k; ++i)
    for (Index j = 0; j < n; ++j) P(i, j) = U(rng);
  for (Index j = 0; j < n; ++j) E(0, j) = 1.0 + 0.2 * U(rng);
  RelaxedLcpData d;
  d.M = sparse(0.5 * A.transpose() * A + K);
  d.q = Vector::NullaryExpr(n, [&] { return U(rng); });
  d.P = sparse(P);
  d.p = Vector::NullaryExpr(k, [&] { return U(rng); });
  d.target = Vector::NullaryExpr(k, [&] { return U(rng); });
  d.E = sparse(E);
  d.e = Vector::Constant(1, 0.8);
  return d;
}

double max_abs(const RelaxedLcpGradient& g) {
  double m = 0.0;
  for (const SparseMatrix* S : {&g.dM, &g.dP, &g.dE})
    for (Index k = 0; k < S->outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(*S, k); it; ++it) m = std::max(m, std::abs(it.value()));
  for (const Vector* v : {&g.dq, &g.dp, &g.dtarget, &g.de}) m = std::max(m, v->cwiseAbs().maxCoeff());
  return m;
}

double max_diff(const RelaxedLcpGradient& a, const RelaxedLcpGradient& b) {
  double m = 0.0;
  m = std::max(m, DenseMatrix(a.dM - b.dM).cwiseAbs().maxCoeff());
  m = std::max(m, DenseMatrix(a.dP - b.dP).cwiseAbs().maxCoeff());
  m = std::max(m, (a.dq - b.dq).cwiseAbs().maxCoeff());
  m = std::max(m, (a.dp - b.dp).cwiseAbs().maxCoeff());
  m = std::max(m, (a.dtarget - b.dtarget).cwiseAbs().maxCoeff());
  if (a.de.size() > 0) {
    m = std::max(m, DenseMatrix(a.dE - b.dE).cwiseAbs().maxCoeff());
    m = std::max(m, (a.de - b.de).cwiseAbs().maxCoeff());
  }
  return m;
}

std::vector<RelaxedLcpSettings> all_options() {
  std::vector<RelaxedLcpSettings> out;
  for (int mask = 0; mask < 8; ++mask)
    for (MaxDissipation md : {MaxDissipation::none, MaxDissipation::qp, MaxDissipation::ext}) {
      RelaxedLcpSettings o;
      o.soft_nonnegativity = mask & 1;
      o.soft_lambdas = mask & 2;
      o.l1_softness = mask & 4;
      o.max_dissipation = md;
      out.push_back(o);
    }
  return out;
}

TEST(RelaxedLcp, EnvelopeEqualsAdjointOnRandomProblems) {
  std::mt19937_64 rng(7);
  int checked = 0;
  double worst = 0.0;
  for (const RelaxedLcpSettings& o : all_options())
    for (int trial = 0; trial < 4; ++trial) {
      const RelaxedLcpData d = random_problem(rng, 3 + trial, 2);
      QpSettings qp;
      qp.eps_abs = 1e-12;
      RelaxedLcpSolver solver(o, qp);
      const RelaxedLcpResult& r = solver.solve(d);
      ASSERT_EQ(r.status, RelaxedLcpStatus::solved) << r.message;
      const RelaxedLcpGradient envelope = r.gradient;
      const RelaxedLcpGradient adjoint = solver.gradient_adjoint();
      const double scale = std::max(1.0, max_abs(envelope));
      worst = std::max(worst, max_diff(envelope, adjoint) / scale);
      EXPECT_LE(max_diff(envelope, adjoint), 1e-6 * scale)
          << "soft_nonneg " << o.soft_nonnegativity << " soft_lambdas " << o.soft_lambdas << " l1 "
          << o.l1_softness << " md " << to_string(o.max_dissipation) << " trial " << trial;
      ++checked;
    }
  EXPECT_EQ(checked, 96);
  std::printf("worst |envelope - adjoint| / max(1, |gradient|): %.3g over %d problems\n", worst, checked);
}

TEST(RelaxedLcp, EnvelopeEqualsFiniteDifferences) {
  std::mt19937_64 rng(11);
  for (const RelaxedLcpSettings& o : all_options()) {
    const RelaxedLcpData d = random_problem(rng, 4, 2);
    RelaxedLcpSolver solver(o);
    const RelaxedLcpGradient g = solver.solve(d).gradient;
    auto cost = [&](const RelaxedLcpData& x) { return solver.solve(x, false).cost; };
    const double h = 1e-6;
    auto fd = [&](auto&& perturb) {
      RelaxedLcpData a = d, b = d;
      perturb(a, h);
      perturb(b, -h);
      return (cost(a) - cost(b)) / (2 * h);
    };
    auto near = [](double a, double b) { return std::abs(a - b) <= 1e-5 * std::max(1.0, std::abs(b)); };
    for (Index i = 0; i < 4; ++i) EXPECT_PRED2(near, fd([&](RelaxedLcpData& x, double s) { x.q(i) += s; }), g.dq(i));
    for (Index i = 0; i < 2; ++i) {
      EXPECT_PRED2(near, fd([&](RelaxedLcpData& x, double s) { x.p(i) += s; }), g.dp(i));
      EXPECT_PRED2(near, fd([&](RelaxedLcpData& x, double s) { x.target(i) += s; }), g.dtarget(i));
    }
    EXPECT_PRED2(near, fd([&](RelaxedLcpData& x, double s) { x.M.coeffRef(1, 2) += s; }), g.dM.coeff(1, 2));
    EXPECT_PRED2(near, fd([&](RelaxedLcpData& x, double s) { x.P.coeffRef(0, 3) += s; }), g.dP.coeff(0, 3));
    if (o.max_dissipation != MaxDissipation::none) {
      EXPECT_PRED2(near, fd([&](RelaxedLcpData& x, double s) { x.e(0) += s; }), g.de(0));
    }
  }
}

TEST(RelaxedLcp, BlockCostMatchesTheSeedsFormula) {
  const Block1dLcp lcp = block1d_lcp(Block1d{1.0, 1.0, 0.3}, 0.2, 0.5);
  RelaxedLcpData d;
  d.M = lcp.M;
  d.q = lcp.q;
  d.P = sparse((DenseMatrix(1, 3) << 1, -1, 0).finished());
  d.p = Vector::Constant(1, 0.7);
  d.target = Vector::Constant(1, 0.1);
  const RelaxedLcpResult r = relaxed_lcp(d);
  ASSERT_EQ(r.status, RelaxedLcpStatus::solved);
  const Vector& l = r.lambda;
  const double pred = l(0) - l(1) + 0.7 - 0.1;
  const double expected = pred * pred + l.dot(DenseMatrix(d.M) * l + d.q) + 0.5e-3 * l.squaredNorm();
  EXPECT_NEAR(r.cost, expected, 1e-9);
  EXPECT_GE(l.minCoeff(), -1e-9);
}

TEST(RelaxedLcp, IndefiniteHessianIsReportedOrShifted) {
  RelaxedLcpData d;
  d.M = sparse((DenseMatrix(2, 2) << 0, 3, 3, 0).finished());  // sym(M) indefinite, P small
  d.q = Vector::Constant(2, 1.0);
  d.P = sparse((DenseMatrix(1, 2) << 0.1, 0).finished());
  d.p = Vector::Zero(1);
  d.target = Vector::Constant(1, 1.0);
  RelaxedLcpResult r = relaxed_lcp(d);
  EXPECT_EQ(r.status, RelaxedLcpStatus::nonconvex);
  EXPECT_TRUE(std::isnan(r.cost));
  RelaxedLcpSettings o;
  o.nonconvex = NonconvexPolicy::shift;
  r = relaxed_lcp(d, o);
  EXPECT_EQ(r.status, RelaxedLcpStatus::solved) << r.message;
  EXPECT_GT(r.shift, 0.0);
}

bool same_bits(const SparseMatrix& a, const SparseMatrix& b) {
  return a.nonZeros() == b.nonZeros() &&
         std::equal(a.valuePtr(), a.valuePtr() + a.nonZeros(), b.valuePtr(),
                    [](double x, double y) { return std::memcmp(&x, &y, sizeof(double)) == 0; });
}

bool same_bits(const Vector& a, const Vector& b) {
  // (memcmp's pointers must not be null, even for 0 bytes: empty vectors have none)
  return a.size() == b.size() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
}

void expect_same_bits(const RelaxedLcpResult& a, const RelaxedLcpResult& b, const std::string& what) {
  ASSERT_EQ(a.status, b.status) << what;
  EXPECT_EQ(std::memcmp(&a.cost, &b.cost, sizeof(double)), 0) << what << ": cost " << a.cost << " vs " << b.cost;
  EXPECT_EQ(a.shift, b.shift) << what;
  EXPECT_EQ(a.iterations, b.iterations) << what;
  EXPECT_TRUE(same_bits(a.qp_x, b.qp_x)) << what;
  EXPECT_TRUE(same_bits(a.qp_z, b.qp_z)) << what;
  EXPECT_TRUE(same_bits(a.gradient.dM, b.gradient.dM)) << what;
  EXPECT_TRUE(same_bits(a.gradient.dP, b.gradient.dP)) << what;
  EXPECT_TRUE(same_bits(a.gradient.dE, b.gradient.dE)) << what;
  EXPECT_TRUE(same_bits(a.gradient.dq, b.gradient.dq)) << what;
  EXPECT_TRUE(same_bits(a.gradient.dp, b.gradient.dp)) << what;
  EXPECT_TRUE(same_bits(a.gradient.de, b.gradient.de)) << what;
}

TEST(RelaxedLcp, ReusedWorkspaceGivesTheFreshResultBitwise) {
  std::mt19937_64 rng(5);
  // Sizes 4, 4 (same pattern: values written in place), 5 (pattern change), 4 (again).
  for (const RelaxedLcpSettings& o : all_options()) {
    RelaxedLcpSolver reused(o);
    for (Index n : {4, 4, 5, 4}) {
      const RelaxedLcpData d = random_problem(rng, n, 2);
      RelaxedLcpSolver fresh(o);
      const RelaxedLcpResult expected = fresh.solve(d);
      ASSERT_EQ(expected.status, RelaxedLcpStatus::solved) << expected.message;
      expect_same_bits(reused.solve(d), expected,
                       "soft_nonneg " + std::to_string(o.soft_nonnegativity) + " soft_lambdas " +
                           std::to_string(o.soft_lambdas) + " l1 " + std::to_string(o.l1_softness) + " md " +
                           to_string(o.max_dissipation) + " n " + std::to_string(n));
    }
  }
  // Policy shift: the QP is assembled again for every tried δ.
  RelaxedLcpSettings o;
  o.nonconvex = NonconvexPolicy::shift;
  RelaxedLcpSolver reused(o);
  for (double m : {3.0, 2.0, 5.0}) {
    RelaxedLcpData d;
    d.M = sparse((DenseMatrix(2, 2) << 0, m, m, 0).finished());
    d.q = Vector::Constant(2, 1.0);
    d.P = sparse((DenseMatrix(1, 2) << 0.1, 0.2).finished());
    d.p = Vector::Zero(1);
    d.target = Vector::Constant(1, m);
    RelaxedLcpSolver fresh(o);
    const RelaxedLcpResult expected = fresh.solve(d);
    ASSERT_EQ(expected.status, RelaxedLcpStatus::solved) << expected.message;
    EXPECT_GT(expected.shift, 0.0);
    expect_same_bits(reused.solve(d), expected, "shift, M offdiagonal " + std::to_string(m));
  }
}

TEST(RelaxedLcp, BadDataNameTheField) {
  RelaxedLcpData d;
  d.M = sparse(DenseMatrix::Identity(2, 2));
  d.q = Vector::Zero(3);
  d.P = sparse(DenseMatrix::Identity(1, 2));
  d.p = Vector::Zero(1);
  d.target = Vector::Zero(1);
  try {
    relaxed_lcp(d);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("q has length"), std::string::npos) << e.what();
  }
  d.q = Vector::Zero(2);
  d.target(0) = std::nan("");
  EXPECT_THROW(relaxed_lcp(d), InputError);
  RelaxedLcpSettings o;
  o.a3 = -1.0;
  EXPECT_THROW(RelaxedLcpSolver solver(o), InputError);
  EXPECT_THROW(parse_max_dissipation("maybe"), InputError);
}

}  // namespace
}  // namespace lcprelax::learn
