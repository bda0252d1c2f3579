// Matrix Market read/write: exact round trips, symmetric and skew-symmetric expansion,
// pattern/integer/array files, and malformed files that must throw InputError naming
// "path:line:".
#include <lcprelax/core/errors.hpp>
#include <lcprelax/sparse/matrix_market.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using lcprelax::InputError;
using lcprelax::SparseMatrix;
using lcprelax::Triplet;
using lcprelax::Vector;
using lcprelax::sparse::read_matrix_market;
using lcprelax::sparse::read_matrix_market_vector;
using lcprelax::sparse::write_matrix_market;

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "lcprelax_sparse_mm_" + name;
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

// The InputError message of reading `text`, or "" when nothing was thrown.
std::string read_error(const std::string& name, const std::string& text) {
  const std::string path = write_file(name, text);
  try {
    read_matrix_market(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_error_at(const std::string& name, const std::string& text, int line,
                     const std::string& words) {
  const std::string message = read_error(name, text);
  const std::string where = temp_path(name) + ":" + std::to_string(line) + ":";
  EXPECT_EQ(message.rfind(where, 0), 0u) << "message: '" << message << "', expected " << where;
  EXPECT_NE(message.find(words), std::string::npos) << "message: '" << message << "'";
}

TEST(MatrixMarket, RoundTripsExactly) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  std::vector<Triplet> t;
  for (int k = 0; k < 200; ++k) {
    const double v = std::ldexp(mantissa(gen), exponent(gen) / 4) / 3.0;
    t.emplace_back(static_cast<int>(gen() % 37), static_cast<int>(gen() % 23), v);
  }
  t.emplace_back(36, 22, 0.0);  // an explicit zero is part of the pattern
  t.emplace_back(0, 0, std::numeric_limits<double>::denorm_min());
  SparseMatrix A(37, 23);
  A.setFromTriplets(t.begin(), t.end());
  const std::string path = temp_path("roundtrip.mtx");
  write_matrix_market(path, A);
  const SparseMatrix B = read_matrix_market(path);
  ASSERT_EQ(B.rows(), 37);
  ASSERT_EQ(B.cols(), 23);
  ASSERT_EQ(B.nonZeros(), A.nonZeros());
  for (int p = 0; p <= 23; ++p) EXPECT_EQ(B.outerIndexPtr()[p], A.outerIndexPtr()[p]);
  for (int p = 0; p < A.nonZeros(); ++p) {
    EXPECT_EQ(B.innerIndexPtr()[p], A.innerIndexPtr()[p]);
    EXPECT_EQ(B.valuePtr()[p], A.valuePtr()[p]);  // bitwise, thanks to 17 digits
  }
}

TEST(MatrixMarket, RoundTripsVectors) {
  Vector v(4);
  v << 0.1, -2.0 / 3.0, 1e-310, 0.0;
  const std::string path = temp_path("vector.mtx");
  write_matrix_market(path, v);
  const Vector w = read_matrix_market_vector(path);
  ASSERT_EQ(w.size(), 4);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(w[i], v[i]);
  Vector bad = v;
  bad[1] = std::nan("");
  EXPECT_THROW(write_matrix_market(temp_path("nan_vector.mtx"), bad), InputError);
}

TEST(MatrixMarket, ExpandsSymmetricAndSkewSymmetricFiles) {
  const SparseMatrix S = read_matrix_market(write_file("sym.mtx",
      "%%MatrixMarket matrix coordinate real symmetric\n"
      "% lower triangle only\n"
      "3 3 4\n"
      "1 1 2.5\n"
      "3 1 -1\n"
      "2 2 4\n"
      "3 2 0.5\n"));
  Eigen::Matrix3d expected;
  expected << 2.5, 0, -1,
              0, 4, 0.5,
              -1, 0.5, 0;
  EXPECT_EQ(Eigen::Matrix3d(S), expected);
  EXPECT_EQ(S.nonZeros(), 6);

  const SparseMatrix K = read_matrix_market(write_file("skew.mtx",
      "%%MatrixMarket matrix coordinate integer skew-symmetric\n"
      "2 2 1\n"
      "2 1 7\n"));
  Eigen::Matrix2d skew;
  skew << 0, -7,
          7, 0;
  EXPECT_EQ(Eigen::Matrix2d(K), skew);
}

TEST(MatrixMarket, ReadsPatternAndArrayFiles) {
  const SparseMatrix P = read_matrix_market(write_file("pattern.mtx",
      "%%MatrixMarket matrix coordinate pattern general\n"
      "2 3 2\n"
      "1 3\n"
      "2 1\n"
      "\n"));
  EXPECT_EQ(P.coeff(0, 2), 1.0);
  EXPECT_EQ(P.coeff(1, 0), 1.0);
  EXPECT_EQ(P.nonZeros(), 2);

  const SparseMatrix A = read_matrix_market(write_file("array.mtx",
      "%%MatrixMarket matrix array real general\n"
      "2 2\n"
      "1\n"
      "0\n"
      "3\n"
      "4.5e0\n"));
  EXPECT_EQ(A.coeff(0, 0), 1.0);
  EXPECT_EQ(A.coeff(0, 1), 3.0);
  EXPECT_EQ(A.coeff(1, 1), 4.5);
  EXPECT_EQ(A.nonZeros(), 3);  // array zeros are dropped

  const Vector v = read_matrix_market_vector(write_file("coord_vector.mtx",
      "%%MatrixMarket matrix coordinate real general\n"
      "3 1 1\n"
      "2 1 -8\n"));
  EXPECT_EQ(v, Vector::Unit(3, 1) * -8.0);
  EXPECT_THROW(read_matrix_market_vector(write_file("two_columns.mtx",
                   "%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n")),
               InputError);
}

TEST(MatrixMarket, MalformedFilesNameTheLine) {
  const std::string banner = "%%MatrixMarket matrix coordinate real general\n";
  expect_error_at("empty.mtx", "", 1, "banner");
  expect_error_at("bad_banner.mtx", "%%MatrixMarket matrix coordinate complex general\n1 1 0\n",
                  1, "complex");
  expect_error_at("no_banner.mtx", "1 1 1\n1 1 1\n", 1, "banner");
  expect_error_at("bad_size.mtx", banner + "% comment\n\n3 three 1\n", 4, "column count");
  expect_error_at("short_size.mtx", banner + "3 3\n", 2, "size line");
  expect_error_at("no_size.mtx", banner + "% only a comment\n", 3, "size line");
  expect_error_at("out_of_range.mtx", banner + "3 3 2\n1 1 1.0\n4 1 2.0\n", 4, "out of range");
  expect_error_at("zero_index.mtx", banner + "3 3 1\n1 0 1.0\n", 3, "out of range");
  expect_error_at("truncated.mtx", banner + "3 3 3\n1 1 1.0\n2 2 2.0\n", 5, "file ends");
  expect_error_at("too_many.mtx", banner + "3 3 1\n1 1 1.0\n\n2 2 2.0\n", 5, "more entries");
  expect_error_at("nan.mtx", banner + "3 3 2\n1 1 1.0\n2 2 nan\n", 4, "non-finite");
  expect_error_at("inf.mtx", banner + "3 3 1\n1 1 1e999\n", 3, "non-finite");
  expect_error_at("bad_value.mtx", banner + "3 3 1\n1 1 1.0x\n", 3, "bad real value");
  expect_error_at("extra_word.mtx", banner + "3 3 1\n1 1 1.0 2.0\n", 3, "bad entry");
  expect_error_at("upper_in_symmetric.mtx",
                  "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1.0\n", 3,
                  "above the diagonal");
  expect_error_at("rectangular_symmetric.mtx",
                  "%%MatrixMarket matrix coordinate real symmetric\n2 3 0\n", 2, "square");
  expect_error_at("integer_field.mtx",
                  "%%MatrixMarket matrix coordinate integer general\n1 1 1\n1 1 1.5\n", 3,
                  "integer");
  const std::string missing = temp_path("does_not_exist.mtx");
  EXPECT_THROW(read_matrix_market(missing), InputError);
}

}  // namespace
