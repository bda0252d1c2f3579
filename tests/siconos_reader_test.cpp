// Siconos .dat readers and errors: every shared LCP and fc2d file parses with the sizes seen
// in the files; hand-written files in each storage (dense, sparse-block, CSparse CSC and
// triplet) give the same matrix; malformed files throw InputError "PATH:LINE: ..." at the
// right line; lcp_error and fc2d_error match hand-computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/core/errors.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace lcprelax::io {
namespace {

const std::string kDir = std::string(LCPRELAX_TEST_DATA_DIR) + "/siconos/";

DenseMatrix dense(const SparseMatrix& m) { return DenseMatrix(m); }

TEST(SiconosReader, EverySharedLcpParsesWithItsSize) {
  const std::vector<std::pair<std::string, Index>> files = {
      {"lcp_CPS_1", 2}, {"lcp_CPS_2", 3},  {"lcp_CPS_3", 4},        {"lcp_CPS_4", 4},
      {"lcp_CPS_5", 2}, {"lcp_deudeu", 2}, {"lcp_deudeu_block", 2}, {"lcp_exp_murty", 6},
      {"lcp_mmc", 26},  {"lcp_ortiz", 4},  {"lcp_tobenna", 40},     {"lcp_trivial", 9}};
  for (const auto& [name, n] : files) {
    SCOPED_TRACE(name);
    const LcpData d = read_siconos_lcp(kDir + "lcp/" + name + ".dat");
    EXPECT_EQ(d.M.rows(), n);
    EXPECT_EQ(d.M.cols(), n);
    EXPECT_EQ(d.q.size(), n);
    EXPECT_TRUE(d.M.isCompressed());
  }
}

TEST(SiconosReader, DenseStorageIsColumnMajor) {
  // lcp_CPS_2 lists "0 2 -1 / -1 0 1 / 2 -2 0": the columns of M (CPS example 4.4.7).
  const LcpData d = read_siconos_lcp(kDir + "lcp/lcp_CPS_2.dat");
  DenseMatrix expected(3, 3);
  expected << 0, -1, 2, 2, 0, -2, -1, 1, 0;
  EXPECT_EQ(dense(d.M), expected);
  EXPECT_EQ(d.q, Vector(Eigen::Vector3d(-3, 6, -1)));
  // Trailing comment lines after q ("Remark 4.1.14 CPS 2009") are ignored.
  EXPECT_NO_THROW(read_siconos_lcp(kDir + "lcp/lcp_CPS_1.dat"));
}

TEST(SiconosReader, DenseAndSparseBlockDeudeuAgree) {
  const LcpData a = read_siconos_lcp(kDir + "lcp/lcp_deudeu.dat");
  const LcpData b = read_siconos_lcp(kDir + "lcp/lcp_deudeu_block.dat");
  EXPECT_EQ(dense(a.M), dense(b.M));
  EXPECT_EQ(a.q, b.q);
  EXPECT_EQ(a.M.coeff(0, 0), 2.0);
  EXPECT_EQ(a.M.coeff(1, 0), 1.0);
  // Its solution z = M⁻¹(5, 6) = (4/3, 7/3) > 0 has Siconos error 0.
  EXPECT_NEAR(lcp_error(a.M, a.q, Vector(Eigen::Vector2d(4.0 / 3, 7.0 / 3))), 0.0, 1e-15);
}

TEST(SiconosReader, EverySharedFc2dParsesWithItsSize) {
  const std::vector<std::pair<std::string, Index>> files = {{"FC2D_SliderCrankLagrangian00000", 2},
                                                            {"FrictionContactProblem00031", 11},
                                                            {"FrictionContactProblem00071", 89},
                                                            {"FrictionContactProblem00374", 28},
                                                            {"fc2d_granularflowonwall_00667_00000", 667}};
  for (const auto& [name, nc] : files) {
    SCOPED_TRACE(name);
    const Fc2dData d = read_siconos_fc2d(kDir + "fc2d/" + name + ".dat");
    EXPECT_EQ(d.contacts, nc);
    EXPECT_EQ(d.W.rows(), 2 * nc);
    EXPECT_EQ(d.W.cols(), 2 * nc);
    EXPECT_EQ(d.q.size(), 2 * nc);
    EXPECT_EQ(d.mu.size(), nc);
    EXPECT_GE(d.mu.minCoeff(), 0.0);
  }
}

TEST(SiconosReader, Fc2dValuesFromEachStorage) {
  const Fc2dData slider = read_siconos_fc2d(kDir + "fc2d/FC2D_SliderCrankLagrangian00000.dat");  // dense
  EXPECT_DOUBLE_EQ(slider.W.coeff(0, 0), 9.365610022253570150496671e+02);
  EXPECT_DOUBLE_EQ(slider.W.coeff(1, 0), -4.642665883420582986218506e+02);  // 2nd value, column 0
  EXPECT_DOUBLE_EQ(slider.W.coeff(0, 1), -4.642662921766745967033785e+02);
  EXPECT_DOUBLE_EQ(slider.mu[1], 1e-2);

  const Fc2dData sbm = read_siconos_fc2d(kDir + "fc2d/FrictionContactProblem00031.dat");  // 15 2×2 blocks
  EXPECT_EQ(sbm.W.nonZeros(), 15 * 4);
  EXPECT_DOUBLE_EQ(sbm.W.coeff(0, 0), 4.435920e-01);
  EXPECT_DOUBLE_EQ(sbm.W.coeff(1, 0), 1.084202e-18);
  EXPECT_DOUBLE_EQ(sbm.W.coeff(1, 1), 1.330776e+00);
  EXPECT_DOUBLE_EQ(sbm.mu[10], 0.9);
  EXPECT_EQ(read_siconos_fc2d(kDir + "fc2d/FrictionContactProblem00071.dat").W.nonZeros(), 287 * 4);

  const Fc2dData csc = read_siconos_fc2d(kDir + "fc2d/fc2d_granularflowonwall_00667_00000.dat");
  EXPECT_EQ(csc.W.nonZeros(), 3822);
  EXPECT_DOUBLE_EQ(csc.W.coeff(0, 0), 856.713);
  EXPECT_DOUBLE_EQ(csc.W.coeff(649, 0), -454.43);
  EXPECT_DOUBLE_EQ(csc.W.coeff(1333, 1333), 2521.06);
  EXPECT_DOUBLE_EQ(csc.mu[666], 0.5);
}

TEST(SiconosReader, HandWrittenStoragesGiveTheSameMatrix) {
  DenseMatrix expected(4, 4);
  expected << 4, 1, 0, 2, -1, 3, 0, 0, 0, 0, 5, 0, 0, 0, 1, 6;
  const Vector q = Vector(Eigen::Vector4d(1, -2, 3, -4));
  for (const char* name : {"lcp_dense", "lcp_sparse_block", "lcp_csparse_csc", "lcp_csparse_triplet"}) {
    SCOPED_TRACE(name);
    const LcpData d = read_siconos_lcp(kDir + "handmade/" + name + ".dat");
    EXPECT_EQ(dense(d.M), expected);
    EXPECT_EQ(d.q, q);
  }
  const Fc2dData fc = read_siconos_fc2d(kDir + "handmade/fc2d_sparse_block.dat");
  EXPECT_EQ(fc.contacts, 2);
  EXPECT_EQ(dense(fc.W), expected);
  EXPECT_EQ(fc.q, q);
  EXPECT_EQ(fc.mu, Vector(Eigen::Vector2d(0.3, 0.5)));
}

TEST(SiconosReader, EmptyBlocksAndColumns) {
  std::istringstream zero("2\n1\n2\n2\n0\n1 2\n");  // nbblocks = 0: the zero matrix
  const LcpData z = parse_siconos_lcp(zero, "zero");
  EXPECT_EQ(z.M.rows(), 2);
  EXPECT_EQ(z.M.nonZeros(), 0);
  EXPECT_EQ(z.q, Vector(Eigen::Vector2d(1, 2)));
  std::istringstream empty_col(
      "2\n2\n2\n2\n2\nCSparse Version 3.1.9\n2-by-2, nzmax: 1 nnz: 1, 1-norm: 7\n"
      "    col 0 : locations 0 to -1\n    col 1 : locations 0 to 0\n      1 : 7\n1 2\n");
  const LcpData e = parse_siconos_lcp(empty_col, "empty_col");
  EXPECT_EQ(e.M.nonZeros(), 1);
  EXPECT_EQ(e.M.coeff(1, 1), 7.0);
}

struct Malformed {
  const char* file;
  long line;
  const char* message;
};

TEST(SiconosReader, MalformedFilesThrowWithLineNumbers) {
  const std::vector<Malformed> cases = {
      {"lcp_truncated", 9, "end of file"},
      {"lcp_nan_entry", 7, "non-finite"},
      {"lcp_inf_q", 9, "non-finite"},
      {"lcp_negative_size", 6, "negative"},
      {"lcp_bad_storage", 2, "unknown matrix storage type"},
      {"lcp_non_numeric", 9, "expected a number"},
      {"lcp_trailing_garbage", 7, "expected a number"},
      {"lcp_zero_size", 1, "must be positive"},
      {"lcp_dimension_mismatch", 5, "dimension mismatch"},
      {"lcp_block_index_out_of_range", 13, "out of range"},
      {"lcp_block_number_mismatch", 14, "block number"},
      {"lcp_csparse_truncated", 10, "end of file"},
      {"lcp_csparse_bad_row", 11, "out of range"},
      {"fc2d_dim3", 1, "only 2-D"},
      {"fc2d_negative_mu", 10, "negative friction"},
      {"fc2d_truncated_mu", 12, "end of file"},
      {"fc2d_negative_contacts", 2, "negative"},
  };
  for (const Malformed& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string path = kDir + "malformed/" + c.file + ".dat";
    try {
      if (std::string(c.file).rfind("fc2d", 0) == 0)
        read_siconos_fc2d(path);
      else
        read_siconos_lcp(path);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path + ":" + std::to_string(c.line) + ": "), std::string::npos) << what;
      EXPECT_NE(what.find(c.message), std::string::npos) << what;
    }
  }
  EXPECT_THROW(read_siconos_lcp(kDir + "malformed/does_not_exist.dat"), InputError);
}

SparseMatrix identity(Index n) {
  SparseMatrix m(n, n);
  m.setIdentity();
  return m;
}

TEST(SiconosErrors, LcpHandComputed) {
  const SparseMatrix I = identity(2);
  const Vector q = Vector(Eigen::Vector2d(-1, 1));
  EXPECT_EQ(lcp_error(I, q, Vector(Eigen::Vector2d(1, 0))), 0.0);  // w = (0, 1)
  // z = (0, 1): w = (−1, 2), z − max(0, z − w) = (−1, 1): √2 / ‖q‖ = 1.
  EXPECT_DOUBLE_EQ(lcp_error(I, q, Vector(Eigen::Vector2d(0, 1))), 1.0);
  // z = (2, 0): w = (1, 1), residual (1, 0): 1/√2.
  EXPECT_DOUBLE_EQ(lcp_error(I, q, Vector(Eigen::Vector2d(2, 0))), 1.0 / std::sqrt(2.0));
  // q = 0: no normalization (Siconos divides only when ‖q‖ > DBL_EPSILON).
  EXPECT_DOUBLE_EQ(lcp_error(I, Vector::Zero(2), Vector(Eigen::Vector2d(3, 0))), 3.0);
  EXPECT_THROW(lcp_error(I, q, Vector::Zero(3)), InputError);
}

Fc2dData one_contact(double mu, const Vector& r, const Vector& u) {
  Fc2dData d;
  d.contacts = 1;
  d.W = identity(2);
  d.q = u - r;  // u = W r + q with W = I
  d.mu = Vector::Constant(1, mu);
  return d;
}

TEST(SiconosErrors, Fc2dZeroOnExactSolutions) {
  const double mu = 0.5;
  const std::vector<std::pair<Vector, Vector>> cases = {
      {Eigen::Vector2d(1, 0.2), Eigen::Vector2d(0, 0)},   // sticking: |r_T| < μ r_N, u = 0
      {Eigen::Vector2d(1, 0.5), Eigen::Vector2d(0, -2)},  // sliding: r_T = −μ r_N sgn(u_T)
      {Eigen::Vector2d(2, -1), Eigen::Vector2d(0, 3)},    // sliding the other way
      {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 3)},     // separation: r = 0, u_N > 0
  };
  for (const auto& [r, u] : cases) {
    const Fc2dData d = one_contact(mu, r, u);
    EXPECT_NEAR(fc2d_error(d, r, u), 0.0, 1e-15) << r.transpose() << " / " << u.transpose();
    EXPECT_NEAR(fc2d_error(d, r), 0.0, 1e-15);
  }
}

TEST(SiconosErrors, Fc2dPositiveOtherwise) {
  const double mu = 0.5;
  // Sticking force with a sliding velocity: v = (1 − 0 − 0.5, 0.2 − 1) = (0.5, −0.8) lies
  // outside K and K°; P_K(v) = (a, −μ a), a = (0.4 + 0.5)/1.25 = 0.72; e = (0.28, 0.56);
  // scale = max(‖r‖, ‖u‖, ‖q‖) = ‖(−1, 0.8)‖.
  const Vector r = Eigen::Vector2d(1, 0.2), u = Eigen::Vector2d(0, 1);
  const Fc2dData d = one_contact(mu, r, u);
  EXPECT_NEAR(fc2d_error(d, r, u), std::sqrt(0.28 * 0.28 + 0.56 * 0.56) / std::sqrt(1.64), 1e-15);
  // Outside the cone (|r_T| > μ r_N), penetrating velocity, and a wrong separation.
  EXPECT_GT(
      fc2d_error(one_contact(mu, Eigen::Vector2d(1, 0.8), Eigen::Vector2d(0, 0)), Eigen::Vector2d(1, 0.8)),
      0.1);
  EXPECT_GT(fc2d_error(one_contact(mu, Eigen::Vector2d(0, 0), Eigen::Vector2d(-1, 0)), Eigen::Vector2d(0, 0)),
            0.1);
  EXPECT_GT(fc2d_error(one_contact(mu, Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 0)), Eigen::Vector2d(1, 0)),
            0.1);
}

TEST(SiconosErrors, Fc2dOnSharedProblemUsesWrPlusQ) {
  const Fc2dData d = read_siconos_fc2d(kDir + "fc2d/fc2d_granularflowonwall_00667_00000.dat");
  Vector r = Vector::Zero(2 * d.contacts);
  for (Index c = 0; c < d.contacts; ++c) r[2 * c] = 0.01 * (c % 7);
  const Vector u = d.W * r + d.q;
  const double e = fc2d_error(d, r);
  EXPECT_DOUBLE_EQ(e, fc2d_error(d, r, u));
  EXPECT_GT(e, 0.0);
  EXPECT_THROW(fc2d_error(d, Vector::Zero(3)), InputError);
}

}  // namespace
}  // namespace lcprelax::io
