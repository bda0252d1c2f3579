// The lcp model's perturbation pattern (contact_step.hpp, step 2; lcp_perturbation_pattern):
// u_i ∈ [½, 1) per LCP row, keyed by the row's contact and kind, so that a contact keeps its
// offsets when the contacts around it are renumbered between time steps. Checked on the
// largest island of a 20-body closed pile after 150 steps: with identities, reversing the contact order
// reverses u exactly (bitwise); without them (keys = indices) it does not; empty identities
// mean the indices; assembly sets distinct identities; bad identities are refused.
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

namespace lcprelax {
namespace {

constexpr double kDt = 1e-2;

ContactSystem pile_island() {
  Simulator sim = make_simulator(test::closed_pile(20, 3, ContactModel::lcp));
  for (int k = 0; k < 150; ++k) sim.step();
  const World& world = sim.world();
  const std::vector<Contact> contacts = find_contacts(world, CollisionSettings{1e-2});
  const std::vector<Island> islands = find_islands(world, contacts);
  const Island& island = *std::max_element(islands.begin(), islands.end(), [](const Island& a, const Island& b) {
    return a.contacts.size() < b.contacts.size();
  });
  return assemble_contact_system(world, contacts, island, kDt);
}

// The same contacts in reverse order (friction rows too); only what the pattern reads.
ContactSystem reversed(const ContactSystem& s) {
  ContactSystem r = s;
  const Index nc = s.num_contacts(), nf = s.num_friction();
  std::reverse(r.contacts.begin(), r.contacts.end());
  for (Index f = 0; f < nf; ++f) r.friction_rows[f] = static_cast<int>(nc - 1 - s.friction_rows[nf - 1 - f]);
  return r;
}

TEST(LcpPerturbation, PatternFollowsContactIdentities) {
  const ContactSystem s = pile_island();
  const Index nc = s.num_contacts(), nf = s.num_friction();
  ASSERT_GE(nc, 10) << "the pile has not come together";
  ASSERT_GE(nf, 1);
  std::mt19937_64 rng(3);
  std::vector<std::uint64_t> ids(static_cast<std::size_t>(nc));
  for (auto& id : ids) id = rng();
  ContactSystem keyed = s, r = reversed(s);
  keyed.ids = ids;
  r.ids.assign(ids.rbegin(), ids.rend());
  for (int seed = 0; seed < kLcpPerturbationSeeds; ++seed) {
    const Vector u = lcp_perturbation_pattern(keyed, seed), ur = lcp_perturbation_pattern(r, seed);
    ASSERT_EQ(u.size(), nc + 3 * nf);
    EXPECT_GE(u.minCoeff(), 0.5);
    EXPECT_LT(u.maxCoeff(), 1.0);
    for (Index c = 0; c < nc; ++c) EXPECT_EQ(ur(nc - 1 - c), u(c)) << "contact " << c;
    for (Index f = 0; f < nf; ++f)
      for (Index block = 0; block < 3; ++block)
        EXPECT_EQ(ur(nc + block * nf + nf - 1 - f), u(nc + block * nf + f)) << "friction row " << f;
  }
  // Keyed by index, the reversal gives every contact other offsets.
  ContactSystem plain = s, plain_r = r;
  plain.ids.clear();
  plain_r.ids.clear();
  const Vector u = lcp_perturbation_pattern(plain, 0), ur = lcp_perturbation_pattern(plain_r, 0);
  Index same = 0;
  for (Index c = 0; c < nc; ++c) same += ur(nc - 1 - c) == u(c);
  EXPECT_LE(same, 1);
}

TEST(LcpPerturbation, EmptyIdentitiesKeyByIndex) {
  ContactSystem plain = pile_island(), indexed = plain;
  plain.ids.clear();
  indexed.ids.resize(static_cast<std::size_t>(plain.num_contacts()));
  std::iota(indexed.ids.begin(), indexed.ids.end(), 0);
  for (int seed = 0; seed < kLcpPerturbationSeeds; ++seed) {
    const Vector a = lcp_perturbation_pattern(plain, seed), b = lcp_perturbation_pattern(indexed, seed);
    EXPECT_EQ((a - b).cwiseAbs().maxCoeff(), 0.0);
  }
  // Patterns differ between seeds.
  EXPECT_GT((lcp_perturbation_pattern(plain, 0) - lcp_perturbation_pattern(plain, 1)).cwiseAbs().minCoeff(), 0.0);
}

TEST(LcpPerturbation, AssemblySetsIdentitiesFromContactKeys) {
  const ContactSystem s = pile_island();
  ASSERT_EQ(static_cast<Index>(s.ids.size()), s.num_contacts());
  // Distinct contacts, distinct identities (a pair's points differ by their ordinal).
  std::vector<std::uint64_t> sorted = s.ids;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
}

TEST(LcpPerturbation, RefusesIdentitiesOfTheWrongSize) {
  ContactSystem s = pile_island();
  s.ids.pop_back();
  EXPECT_THROW(lcp_perturbation_pattern(s, 0), InputError);
  EXPECT_THROW(solve_lcp_model(s, kDt, LemkeSettings{}), InputError);
  s.ids.clear();
  EXPECT_THROW(lcp_perturbation_pattern(s, -1), InputError);
}

}  // namespace
}  // namespace lcprelax
