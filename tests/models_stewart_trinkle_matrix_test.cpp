// stewart_trinkle_lcp()'s matrix, written column by column (models/src/lcp_model.cpp), against
// a triplet assembly (bench/lcp_assembly_reference.hpp): the same pattern (explicit zeros included) and the same
// values bit for bit, on box stacks and pile islands, with normal compliance (also where W
// has no diagonal entry) and with the per-contact block; bad sizes throw.
#include "contact_island_fixtures.hpp"
#include "../bench/lcp_assembly_reference.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/contact_step.hpp>

#include <gtest/gtest.h>

#include <cstring>

namespace lcprelax {
namespace {

void expect_same(const ContactSystem& s, const SparseMatrix& W) {
  const SparseMatrix a = stewart_trinkle_lcp(s, W, 0.01).M, b = reference::triplet_stewart_trinkle_matrix(s, W);
  ASSERT_TRUE(a.isCompressed());
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  for (Index k = 0; k <= a.cols(); ++k) ASSERT_EQ(a.outerIndexPtr()[k], b.outerIndexPtr()[k]) << "column " << k;
  for (Index k = 0; k < a.nonZeros(); ++k) {
    ASSERT_EQ(a.innerIndexPtr()[k], b.innerIndexPtr()[k]) << "entry " << k;
    ASSERT_EQ(std::memcmp(&a.valuePtr()[k], &b.valuePtr()[k], sizeof(double)), 0) << "entry " << k;
  }
}

std::vector<ContactSystem> islands() {
  std::vector<ContactSystem> out{testing::box_stack(4, 0.5)};
  for (std::uint64_t seed : {1u, 2u}) out.push_back(testing::settled_pile_island(40, seed, 80));
  return out;
}

TEST(StewartTrinkleMatrix, SameAsTheTripletAssembly) {
  for (const ContactSystem& s : islands()) {
    ASSERT_GT(s.num_friction(), 0);
    expect_same(s, delassus(s));
  }
}

TEST(StewartTrinkleMatrix, ComplianceOnTheDiagonalAlsoWithoutAWEntry) {
  for (ContactSystem s : islands()) {
    s.compliance = Vector::Zero(s.num_contacts());
    for (Index c = 0; c < s.num_contacts(); c += 3) s.compliance(c) = 1e-4 * (1 + c);
    const SparseMatrix W = delassus(s);
    expect_same(s, W);
    // A caller's W without the first contact's diagonal entry: the compliance is inserted.
    SparseMatrix W0 = W;
    W0.prune([](Index i, Index j, double) { return !(i == 0 && j == 0); });
    W0.makeCompressed();
    ASSERT_EQ(W0.nonZeros(), W.nonZeros() - 1);
    expect_same(s, W0);
  }
}

TEST(StewartTrinkleMatrix, ContactBlockAddedWithItsZeros) {
  for (ContactSystem s : islands()) {
    s.lcp_block.enabled = true;
    s.lcp_block.M << 0.1, 0, 0.2, 0, 0, -0.3, 0, 0, 0.4, 0, 0.5, 0, 0, 0, 0, 0.6;
    expect_same(s, delassus(s));
  }
}

TEST(StewartTrinkleMatrix, BadSizesThrow) {
  const ContactSystem s = testing::box_stack(3, 0.5);
  const SparseMatrix W = delassus(s);
  SparseMatrix small = W.topLeftCorner(W.rows() - 1, W.cols() - 1);
  EXPECT_THROW(stewart_trinkle_lcp(s, small, 0.01), InputError);
  ContactSystem bad = s;
  bad.mu = Vector::Ones(s.num_friction() + 1);
  EXPECT_THROW(stewart_trinkle_lcp(bad, W, 0.01), InputError);
  bad = s;
  bad.friction_rows[0] = static_cast<int>(s.num_contacts());
  EXPECT_THROW(stewart_trinkle_lcp(bad, W, 0.01), InputError);
}

}  // namespace
}  // namespace lcprelax
