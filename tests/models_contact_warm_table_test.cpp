// ContactWarmTable (models/contact_warm_table.hpp). Expected:
// - after random writes of either field to 300 keys drawn from 120 (so most keys are written
//   several times, fields in any order), every key's entry equals that of a std::map written
//   with `map[key].field = code` in the same order (last write per field wins, a field never
//   written is 0), and keys never written are not found;
// - an empty table finds nothing; clear() empties it;
// - swap() exchanges two tables' contents.
#include <lcprelax/models/contact_warm_table.hpp>

#include <gtest/gtest.h>

#include <map>
#include <random>

namespace lcprelax {
namespace {

struct Reference {
  double normal = 0.0, friction = 0.0;
};

ContactKey key_of(int k) { return {k % 7, k / 7 - 1, k % 3, k % 5, k % 2}; }

TEST(ContactWarmTable, MatchesMapSemantics) {
  std::mt19937 rng(5);
  std::map<ContactKey, Reference> reference;
  ContactWarmTable table;
  for (int w = 0; w < 300; ++w) {
    const ContactKey key = key_of(static_cast<int>(rng() % 120));
    const double code = static_cast<double>(rng() % 1000) / 7.0;
    if (rng() % 2) {
      table.set_normal(key, code);
      reference[key].normal = code;
    } else {
      table.set_friction(key, code);
      reference[key].friction = code;
    }
  }
  table.finish();
  ASSERT_EQ(table.size(), reference.size());
  for (const auto& [key, ref] : reference) {
    const ContactWarmTable::Entry* e = table.find(key);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->normal, ref.normal);
    EXPECT_EQ(e->friction, ref.friction);
  }
  for (int k = 0; k < 400; ++k) {
    if (!reference.count(key_of(k))) {
      EXPECT_EQ(table.find(key_of(k)), nullptr);
    }
  }
}

TEST(ContactWarmTable, EmptyClearAndSwap) {
  ContactWarmTable a, b;
  a.finish();
  EXPECT_EQ(a.find(key_of(3)), nullptr);
  a.set_normal(key_of(3), 1.0);
  a.finish();
  ASSERT_NE(a.find(key_of(3)), nullptr);
  a.swap(b);
  EXPECT_EQ(a.find(key_of(3)), nullptr);
  ASSERT_NE(b.find(key_of(3)), nullptr);
  EXPECT_EQ(b.find(key_of(3))->normal, 1.0);
  EXPECT_EQ(b.find(key_of(3))->friction, 0.0);
  b.clear();
  EXPECT_EQ(b.size(), 0u);
  EXPECT_EQ(b.find(key_of(3)), nullptr);
}

}  // namespace
}  // namespace lcprelax
