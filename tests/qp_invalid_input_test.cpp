// Input errors of the QP solver: setup()/update()/warm_start() and the QpSolver constructor
// throw lcprelax::InputError naming the offending field; backward() without a solution
// throws std::logic_error; the batch API throws InputError naming the problem index.
#include <lcprelax/kkt/qp_batch.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/core/errors.hpp>

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A valid 3-variable problem with every component present:
//   min ½xᵀPx + qᵀx  s.t.  x1 + x2 + x3 = 1,  −1 ≤ x1 − x2 ≤ 1,  −2 ≤ x ≤ 2,
// P = [1 .1 0; .1 1 0; 0 0 1] (diagonally dominant, so ≻ 0), q = (−1, 0, 1); x = (⅓, ⅓, ⅓) is
// strictly feasible, so the problem is solvable (the tests here only need that).
QpProblem valid_problem() {
  QpProblem p(3);
  std::vector<Triplet> t = {{0, 0, 1.0}, {1, 1, 1.0}, {2, 2, 1.0}, {0, 1, 0.1}};
  p.P.setFromTriplets(t.begin(), t.end());
  p.q << -1, 0, 1;
  p.A.resize(1, 3);
  t = {{0, 0, 1.0}, {0, 1, 1.0}, {0, 2, 1.0}};
  p.A.setFromTriplets(t.begin(), t.end());
  p.b = Vector::Ones(1);
  p.G.resize(1, 3);
  t = {{0, 0, 1.0}, {0, 1, -1.0}};
  p.G.setFromTriplets(t.begin(), t.end());
  p.l = Vector::Constant(1, -1.0);
  p.u = Vector::Constant(1, 1.0);
  p.xl = Vector::Constant(3, -2.0);
  p.xu = Vector::Constant(3, 2.0);
  return p;
}

// True when `field` occurs in `msg` as a whole identifier (so "l" does not match "xl").
bool names_field(const std::string& msg, const std::string& field) {
  auto ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (size_t pos = msg.find(field); pos != std::string::npos; pos = msg.find(field, pos + 1)) {
    const bool left = pos == 0 || !ident(msg[pos - 1]);
    const bool right = pos + field.size() == msg.size() || !ident(msg[pos + field.size()]);
    if (left && right) return true;
  }
  return false;
}

// setup() on the valid problem after `corrupt` must throw InputError naming `field`.
void expect_setup_rejects(const std::function<void(QpProblem&)>& corrupt, const std::string& field) {
  SCOPED_TRACE("field " + field);
  QpProblem p = valid_problem();
  corrupt(p);
  EXPECT_FALSE(p.validation_error().empty());
  QpSolver solver;
  try {
    solver.setup(p);
    ADD_FAILURE() << "setup() accepted invalid data";
  } catch (const InputError& e) {
    EXPECT_TRUE(names_field(e.what(), field)) << "message: " << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
  }
}

TEST(QpInvalidInput, ValidProblemIsAccepted) {
  const QpProblem p = valid_problem();
  EXPECT_EQ(p.validation_error(), "");
  QpSolver solver;
  solver.setup(p);
  EXPECT_EQ(solver.solve().info.status, QpStatus::solved);
}

TEST(QpInvalidInput, NonFiniteData) {
  expect_setup_rejects([](QpProblem& p) { p.q(1) = kNaN; }, "q");
  expect_setup_rejects([](QpProblem& p) { p.P.coeffRef(1, 1) = kInf; }, "P");
  expect_setup_rejects([](QpProblem& p) { p.b(0) = kNaN; }, "b");
  expect_setup_rejects([](QpProblem& p) { p.G.coeffRef(0, 0) = kNaN; }, "G");
}

TEST(QpInvalidInput, WrongSizes) {
  expect_setup_rejects([](QpProblem& p) { p.b = Vector::Ones(2); }, "b");
  expect_setup_rejects([](QpProblem& p) { p.l = Vector::Constant(2, -1.0); }, "l");
  expect_setup_rejects([](QpProblem& p) { p.u = Vector::Constant(0, 1.0); }, "u");
  expect_setup_rejects([](QpProblem& p) { p.xl = Vector::Constant(2, -2.0); }, "xl");
  expect_setup_rejects([](QpProblem& p) { p.xu = Vector::Constant(4, 2.0); }, "xu");
  expect_setup_rejects([](QpProblem& p) { p.A.conservativeResize(1, 4); }, "A");
  expect_setup_rejects([](QpProblem& p) { p.G.conservativeResize(1, 2); }, "G");
}

TEST(QpInvalidInput, LowerTriangleOfP) {
  // P(1,0) is below the diagonal: P must be given as its upper triangle only.
  expect_setup_rejects([](QpProblem& p) { p.P.coeffRef(1, 0) = 0.1; }, "P");
}

TEST(QpInvalidInput, InconsistentBounds) {
  expect_setup_rejects([](QpProblem& p) { p.l(0) = 2.0; }, "l");   // l = 2 > u = 1
  expect_setup_rejects([](QpProblem& p) { p.xl(2) = 3.0; }, "xl");  // xl = 3 > xu = 2
  expect_setup_rejects([](QpProblem& p) { p.l(0) = kInf; p.u(0) = kInf; }, "l");  // +∞ lower bound
  expect_setup_rejects([](QpProblem& p) { p.u(0) = -kInf; p.l(0) = -kInf; }, "u");  // −∞ upper bound
}

TEST(QpInvalidInput, Settings) {
  QpSettings s;
  s.eps_abs = -1;
  try {
    QpSolver solver(s);
    ADD_FAILURE() << "eps_abs = -1 accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(names_field(e.what(), "eps_abs")) << e.what();
  }
  s = QpSettings{};
  s.max_iter = 0;
  try {
    QpSolver solver(s);
    ADD_FAILURE() << "max_iter = 0 accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(names_field(e.what(), "max_iter")) << e.what();
  }
  // set_settings validates too and leaves the old settings in place.
  QpSolver solver;
  EXPECT_THROW(solver.set_settings(s), InputError);
  EXPECT_EQ(solver.settings().max_iter, QpSettings{}.max_iter);
}

TEST(QpInvalidInput, UpdateWithAnotherPattern) {
  QpSolver solver;
  solver.setup(valid_problem());
  ASSERT_EQ(solver.solve().info.status, QpStatus::solved);
  QpProblem p = valid_problem();
  p.P.coeffRef(1, 2) = 0.2;  // new structural entry in P
  EXPECT_THROW(solver.update(p), InputError);
  p = valid_problem();
  p.G.coeffRef(0, 2) = 1.0;  // new structural entry in G
  EXPECT_THROW(solver.update(p), InputError);
  p = valid_problem();
  p.q(0) = kNaN;  // same pattern, invalid values
  EXPECT_THROW(solver.update(p), InputError);
  // The solver still holds the original problem and solves it.
  EXPECT_EQ(solver.solve().info.status, QpStatus::solved);
}

TEST(QpInvalidInput, BackwardBeforeSuccessfulSolve) {
  const Vector dl = Vector::Ones(3);
  QpSolver fresh;
  EXPECT_THROW(fresh.backward(dl), std::logic_error);
  QpSolver solver;
  solver.setup(valid_problem());
  EXPECT_THROW(solver.backward(dl), std::logic_error);  // set up but not solved
  // Primal infeasible (x1 + x2 + x3 = 1 with x ≤ 0): backward must still refuse.
  QpProblem p = valid_problem();
  p.xu = Vector::Zero(3);
  QpSolver infeasible;
  infeasible.setup(p);
  ASSERT_EQ(infeasible.solve().info.status, QpStatus::primal_infeasible);
  EXPECT_THROW(infeasible.backward(dl), std::logic_error);
}

TEST(QpInvalidInput, BatchThrowsNamingTheInvalidProblem) {
  std::vector<QpProblem> problems(4, valid_problem());
  problems[2].q(0) = kNaN;
  for (int threads : {1, 2}) {
    SCOPED_TRACE("threads " + std::to_string(threads));
    try {
      solve_qp_batch(problems, QpSettings{}, threads);
      FAIL() << "no exception";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("problems[2]: ", 0), 0u) << what;
      EXPECT_TRUE(names_field(what, "q")) << what;
    }
  }
  problems[2] = valid_problem();
  const std::vector<QpResult> r = solve_qp_batch(problems, QpSettings{}, 2);
  for (const QpResult& x : r) EXPECT_EQ(x.info.status, QpStatus::solved) << x.info.message;
}

}  // namespace
}  // namespace lcprelax
