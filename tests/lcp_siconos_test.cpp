// Lemke, dense and sparse, on the Siconos numerics test problems (tests/data/siconos,
// copied from the project's shared data), with errors computed as Siconos defines them
// (io/siconos_errors). The 667-contact granular fc2d problem is solved by the sparse path
// only: the dense one needs minutes on it (2,668 unknowns, O(n²) per pivot). The sparse path
// runs with both of KLU's column orderings (LemkeSettings::lu_ordering: COLAMD, the default,
// and AMD), which must give the same statuses and accuracies.
#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <ostream>
#include <string>
#include <tuple>

namespace lcprelax {
namespace {

const std::string kDir = std::string(LCPRELAX_TEST_DATA_DIR) + "/siconos/";

// The Lemke variants run on every file: dense, sparse (KLU with COLAMD), sparse with AMD.
enum class Path { dense, sparse, sparse_amd };

const char* to_string(Path p) {
  return p == Path::dense ? "dense" : p == Path::sparse ? "sparse" : "sparse_amd";
}
void PrintTo(Path p, std::ostream* os) { *os << to_string(p); }

LemkeSettings with_path(Path path) {
  LemkeSettings s;
  s.method = path == Path::dense ? LemkeMethod::dense : LemkeMethod::sparse;
  s.lu_ordering = path == Path::sparse_amd ? LuOrdering::amd : LuOrdering::colamd;
  return s;
}

using NameAndPath = std::tuple<std::string, Path>;
std::string name_and_path(const ::testing::TestParamInfo<NameAndPath>& info) {
  return std::get<0>(info.param) + "_" + to_string(std::get<1>(info.param));
}

class SiconosLcp : public ::testing::TestWithParam<NameAndPath> {};

TEST_P(SiconosLcp, SolvedToSiconosErrorOrRightStatus) {
  const auto& [name, path] = GetParam();
  const io::LcpData d = io::read_siconos_lcp(kDir + "lcp/" + name + ".dat");
  const LemkeSettings settings = with_path(path);
  LemkeSolver solver(settings);
  solver.setup(d.M, d.q);
  const LcpResult& r = solver.solve();
  std::printf("%s (%s): n = %ld, %s, %ld pivots\n", name.c_str(), to_string(path),
              static_cast<long>(d.q.size()), to_string(r.info.status), r.info.pivots);
  EXPECT_EQ(r.info.method, settings.method);
  if (name == "lcp_CPS_3") {
    // Bimatrix game (Cottle, Pang & Stone, example 4.4.23): M ≥ 0 with zero diagonal
    // blocks is copositive but not copositive-plus, so Lemke's method with the standard
    // covering vector may end on a ray, and does here.
    EXPECT_EQ(r.info.status, LcpStatus::ray_termination);
    return;
  }
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  EXPECT_LE(io::lcp_error(d.M, d.q, r.z), 1e-10);
}

const auto kPaths = ::testing::Values(Path::dense, Path::sparse, Path::sparse_amd);

INSTANTIATE_TEST_SUITE_P(All, SiconosLcp,
                         ::testing::Combine(::testing::Values("lcp_CPS_1", "lcp_CPS_2", "lcp_CPS_3", "lcp_CPS_4",
                                                              "lcp_CPS_5", "lcp_deudeu", "lcp_deudeu_block",
                                                              "lcp_exp_murty", "lcp_mmc", "lcp_ortiz",
                                                              "lcp_tobenna", "lcp_trivial"),
                                            kPaths),
                         name_and_path);

class SiconosFc2d : public ::testing::TestWithParam<NameAndPath> {};

TEST_P(SiconosFc2d, SolvedAsAnLcpToSiconosError) {
  const auto& [name, path] = GetParam();
  const io::Fc2dData d = io::read_siconos_fc2d(kDir + "fc2d/" + name + ".dat");
  const Fc2dLcp lcp = fc2d_to_lcp(d.W, d.q, d.mu);
  const LemkeSettings settings = with_path(path);
  LemkeSolver solver(settings);
  solver.setup(lcp.M, lcp.q);
  const LcpResult& r = solver.solve();
  std::printf("%s (%s): %ld contacts, %s, %ld pivots, %ld refactorizations, %.3f s\n", name.c_str(),
              to_string(path), static_cast<long>(d.contacts), to_string(r.info.status), r.info.pivots,
              r.info.refactorizations, r.info.seconds);
  ASSERT_EQ(r.info.status, LcpStatus::solved) << r.info.message;
  Vector reactions, velocities;
  fc2d_from_lcp(r.z, d.W, d.q, reactions, velocities);
  EXPECT_LE(io::fc2d_error(d, reactions), 1e-10);
  // The same on the problem scaled to ‖q‖₂ = 1 (r and u scale with q): Siconos does not
  // normalize its error when ‖q‖ is below machine epsilon (granular file: ‖q‖₂ = 4e-18,
  // where r = 0 already scores 2e-18), so the unscaled check alone proves nothing there.
  const double qn = d.q.norm();
  io::Fc2dData scaled = d;
  scaled.q /= qn;
  const Vector r_scaled = reactions / qn, u_scaled = velocities / qn;
  EXPECT_LE(io::fc2d_error(scaled, r_scaled), 1e-10);
  EXPECT_GT(io::fc2d_error(scaled, Vector::Zero(r_scaled.size())), 1e-3) << "r = 0 must not pass";
  // Coulomb's law directly on the scaled problem: r_n ≥ 0, u_n ≥ 0, |r_t| ≤ μ r_n.
  for (Index c = 0; c < d.contacts; ++c) {
    EXPECT_GE(r_scaled(2 * c), 0.0);
    EXPECT_GE(u_scaled(2 * c), -1e-9);
    EXPECT_LE(std::abs(r_scaled(2 * c + 1)), d.mu(c) * r_scaled(2 * c) * (1 + 1e-9) + 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(All, SiconosFc2d,
                         ::testing::Combine(::testing::Values("FC2D_SliderCrankLagrangian00000",
                                                              "FrictionContactProblem00031",
                                                              "FrictionContactProblem00071",
                                                              "FrictionContactProblem00374"),
                                            kPaths),
                         name_and_path);
INSTANTIATE_TEST_SUITE_P(Granular, SiconosFc2d,
                         ::testing::Combine(::testing::Values("fc2d_granularflowonwall_00667_00000"),
                                            ::testing::Values(Path::sparse, Path::sparse_amd)),
                         name_and_path);

// The LCP formulation of fc2d: a 1-contact problem whose LCP is the seeds' block LCP up to
// the normal row: W = I, q = (−1, v), μ = 0.5 → r_n = 1, friction −sign(v)·min(|v|, 0.5).
TEST(Fc2dLcp, OneContactClosedForm) {
  SparseMatrix W(2, 2);
  W.setIdentity();
  for (double v : {-2.0, -0.3, 0.0, 0.4, 1.5}) {
    const Vector q = (Vector(2) << -1.0, v).finished();
    const Vector mu = Vector::Constant(1, 0.5);
    const Fc2dLcp lcp = fc2d_to_lcp(W, q, mu);
    LemkeSolver solver;
    solver.setup(lcp.M, lcp.q);
    const LcpResult& r = solver.solve();
    ASSERT_EQ(r.info.status, LcpStatus::solved);
    Vector reactions, velocities;
    fc2d_from_lcp(r.z, W, q, reactions, velocities);
    EXPECT_NEAR(reactions(0), 1.0, 1e-12);
    EXPECT_NEAR(reactions(1), -std::copysign(std::min(std::abs(v), 0.5), v), 1e-12) << "v = " << v;
  }
}

}  // namespace
}  // namespace lcprelax
