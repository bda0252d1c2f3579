// A Stewart–Trinkle basis survives its per-contact codes (lcp_basis_codes.hpp), which the
// Simulator's warm start and the hard scene loss's stored bases both use.
#include <lcprelax/models/lcp_basis_codes.hpp>

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

TEST(LcpBasisCodes, RoundTripOfEveryFrictionRowPattern) {
  // nc = 3 contacts, nf = 8 friction rows: row f takes the 3-bit pattern f (β⁺, β⁻, γ).
  const Index nc = 3, nf = 8;
  std::vector<bool> basis(static_cast<std::size_t>(nc + 3 * nf), false);
  basis[1] = true;
  for (Index f = 0; f < nf; ++f) {
    basis[static_cast<std::size_t>(nc + f)] = (f & 1) != 0;
    basis[static_cast<std::size_t>(nc + nf + f)] = (f & 2) != 0;
    basis[static_cast<std::size_t>(nc + 2 * nf + f)] = (f & 4) != 0;
  }
  Vector code;
  encode_lcp_basis(basis, nc, nf, code);
  ASSERT_EQ(code.size(), nc + nf);
  EXPECT_EQ(code(0), 0.0);
  EXPECT_EQ(code(1), 1.0);
  for (Index f = 0; f < nf; ++f) {
    EXPECT_EQ(code(nc + f), static_cast<double>(f)) << "row " << f;
    EXPECT_EQ(friction_basis_bits(code(nc + f)), f);
  }
  std::vector<bool> back;
  decode_lcp_basis(code, nc, nf, back);
  EXPECT_EQ(back, basis);
}

TEST(LcpBasisCodes, RandomBasesRoundTrip) {
  std::mt19937 rng(7);
  std::bernoulli_distribution coin(0.4);
  for (int trial = 0; trial < 50; ++trial) {
    const Index nc = 1 + trial % 9, nf = trial % 5 == 0 ? 0 : nc - trial % 2 * (nc / 2);
    std::vector<bool> basis(static_cast<std::size_t>(nc + 3 * nf));
    for (std::size_t i = 0; i < basis.size(); ++i) basis[i] = coin(rng);
    Vector code;
    std::vector<bool> back;
    encode_lcp_basis(basis, nc, nf, code);
    decode_lcp_basis(code, nc, nf, back);
    EXPECT_EQ(back, basis) << "trial " << trial;
  }
}

TEST(LcpBasisCodes, ValuesThatAreNotCodesGiveSomeBasis) {
  // A relaxed centre (any real) or a NaN decodes without throwing: a friction code is
  // rounded, and one that is not finite or outside [0, 7] has nothing basic.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Vector code(4);
  code << 0.7, nan, nan, 2.9;  // nc = 2, nf = 2
  std::vector<bool> basis;
  decode_lcp_basis(code, 2, 2, basis);
  ASSERT_EQ(basis.size(), 8u);
  EXPECT_TRUE(basis[0]);
  EXPECT_FALSE(basis[1]);
  EXPECT_FALSE(basis[2] || basis[4] || basis[6]);  // friction row 0: NaN
  EXPECT_TRUE(basis[3] && basis[5] && !basis[7]);  // friction row 1: round(2.9) = 3 = β⁺ + β⁻
  EXPECT_EQ(friction_basis_bits(-1.0), 0);
  EXPECT_EQ(friction_basis_bits(8.0), 0);
  EXPECT_EQ(friction_basis_bits(7.2), 7);
}

TEST(LcpBasisCodes, SizeMismatchThrowsWithTheSizes) {
  Vector code;
  EXPECT_THROW(encode_lcp_basis(std::vector<bool>(5, false), 2, 2, code), std::invalid_argument);
  std::vector<bool> basis;
  std::string message;
  try {
    decode_lcp_basis(Vector::Zero(3), 2, 2, basis);
  } catch (const std::invalid_argument& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("size 3 for nc = 2, nf = 2 (expected 4)"), std::string::npos) << message;
}

}  // namespace
}  // namespace lcprelax
