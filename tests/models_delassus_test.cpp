// delassus(): W = J M⁻¹ Jᵀ formed from J's rows and columns (models/src/delassus.cpp).
// Pinned: bit-for-bit equality with Eigen's (J·M⁻¹)·Jᵀ (pruned) on box stacks and pile
// islands, and of the post-stabilization's normal block with Eigen's unpruned Jn M⁻¹ Jnᵀ
// (explicit zeros kept); the values of a hand-made two-body system; bad sizes.
#include "contact_island_fixtures.hpp"
#include "../bench/lcp_assembly_reference.hpp"
#include "../models/src/delassus.hpp"

#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/contact_system.hpp>

#include <gtest/gtest.h>

#include <cstring>

namespace lcprelax {
namespace {

void expect_bitwise_equal(const SparseMatrix& a, const SparseMatrix& b) {
  ASSERT_TRUE(a.isCompressed());
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.cols(), b.cols());
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  for (Index k = 0; k <= a.cols(); ++k) ASSERT_EQ(a.outerIndexPtr()[k], b.outerIndexPtr()[k]) << "column " << k;
  for (Index k = 0; k < a.nonZeros(); ++k) {
    ASSERT_EQ(a.innerIndexPtr()[k], b.innerIndexPtr()[k]) << "entry " << k;
    ASSERT_EQ(std::memcmp(&a.valuePtr()[k], &b.valuePtr()[k], sizeof(double)), 0)
        << "entry " << k << ": " << a.valuePtr()[k] << " vs " << b.valuePtr()[k];
  }
}

TEST(Delassus, SameBitsAsEigensProductOnStacksAndPiles) {
  expect_bitwise_equal(delassus(testing::box_stack(5, 0.5)), reference::eigen_delassus(testing::box_stack(5, 0.5)));
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const ContactSystem s = testing::settled_pile_island(40, seed, 80);
    ASSERT_GT(s.num_contacts(), 20);
    expect_bitwise_equal(delassus(s), reference::eigen_delassus(s));
  }
}

// The simulator's post-stabilization block (models/src/simulator.cpp): Jn only, every
// entry of the product's pattern kept, zeros included, as Eigen's product without pruned().
TEST(Delassus, NormalBlockKeepsEigensUnprunedPattern) {
  for (const ContactSystem& s : {testing::box_stack(5, 0.5), testing::settled_pile_island(40, 2, 80)}) {
    const SparseMatrix JnMinv = s.Jn * s.minv.asDiagonal();
    SparseMatrix expected = JnMinv * s.Jn.transpose();
    expected.makeCompressed();
    expect_bitwise_equal(detail::stacked_delassus(s.Jn, SparseMatrix(0, s.num_dofs()), s.minv, false), expected);
  }
  // A stored zero of Jn keeps its entries in the unpruned pattern, not in the pruned one.
  ContactSystem s = testing::box_stack(2, 0.5);
  DenseMatrix jn(s.Jn);
  jn(0, 1) = 0.0;
  SparseMatrix with_zero = jn.sparseView(1.0, -1.0);  // every entry stored
  const SparseMatrix kept = detail::stacked_delassus(with_zero, SparseMatrix(0, s.num_dofs()), s.minv, false);
  EXPECT_EQ(kept.nonZeros(), with_zero.rows() * with_zero.rows());
  EXPECT_THROW(detail::stacked_delassus(with_zero, SparseMatrix(0, s.num_dofs() + 3), s.minv, false), InputError);
}

// Two bodies (masses 2 and 4 kg, inertias 0.5 and 1 kg·m²), one contact with one friction
// row between them and one normal-only contact on body 0: W against the dense product.
TEST(Delassus, TwoBodiesMatchTheDenseProduct) {
  ContactSystem s;
  s.bodies = {0, 1};
  s.contacts = {0, 1};
  s.friction_rows = {0};
  s.minv = (Vector(6) << 0.5, 0.5, 2.0, 0.25, 0.25, 1.0).finished();
  DenseMatrix Jn(2, 6), Jt(1, 6);
  Jn << 0, 1, 0.3, 0, -1, 0.2, 0, 1, -0.1, 0, 0, 0;
  Jt << 1, 0, -0.4, -1, 0, 0.5;
  s.Jn = Jn.sparseView();
  s.Jt = Jt.sparseView();
  DenseMatrix J(3, 6);
  J << Jn, Jt;
  const DenseMatrix expected = J * s.minv.asDiagonal() * J.transpose();
  const SparseMatrix W = delassus(s);
  EXPECT_LT((DenseMatrix(W) - expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(W.nonZeros(), 9);  // every pair of rows shares body 0
  EXPECT_TRUE(W.isCompressed());
}

TEST(Delassus, EmptyIslandGivesAnEmptyMatrix) {
  ContactSystem s;
  s.bodies = {0};
  s.minv = Vector::Ones(3);
  s.Jn.resize(0, 3);
  s.Jt.resize(0, 3);
  const SparseMatrix W = delassus(s);
  EXPECT_EQ(W.rows(), 0);
  EXPECT_EQ(W.nonZeros(), 0);
}

TEST(Delassus, InconsistentSizesThrow) {
  ContactSystem s = testing::box_stack(3, 0.5);
  ContactSystem bad = s;
  bad.minv = Vector::Ones(bad.minv.size() - 1);
  EXPECT_THROW(delassus(bad), InputError);
  bad = s;
  bad.friction_rows.pop_back();
  EXPECT_THROW(delassus(bad), InputError);
  bad = s;
  bad.Jn.conservativeResize(bad.Jn.rows(), bad.Jn.cols() + 3);
  EXPECT_THROW(delassus(bad), InputError);
}

}  // namespace
}  // namespace lcprelax
