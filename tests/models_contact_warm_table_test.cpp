// ContactWarmTable (models/contact_warm_table.hpp). Expected:
// - after random writes of any field (normal, friction, regularized) to 300 keys drawn from
//   120 (so most keys are written several times, fields in any order), every key's entry
//   equals that of a std::map written with `map[key].field = code` in the same order (last
//   write per field wins, a field never written is 0 or false), keys never written are not
//   found, and records() / assign() carry every field;
// - an empty table finds nothing; clear() empties it;
// - swap() exchanges two tables' contents;
// - find_sorted() gives find()'s entry for every key, for keys in increasing order (the
//   merge pass) and in any other order (repeated keys too), and writes made in key order
//   give the same table as the same writes shuffled (finish() skips its sort for them).
#include <lcprelax/models/contact_warm_table.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace lcprelax {
namespace {

struct Reference {
  double normal = 0.0, friction = 0.0;
  bool regularized = false;
};

ContactKey key_of(int k) { return {k % 7, k / 7 - 1, k % 3, k % 5, k % 2}; }

TEST(ContactWarmTable, MatchesMapSemantics) {
  std::mt19937 rng(5);
  std::map<ContactKey, Reference> reference;
  ContactWarmTable table;
  for (int w = 0; w < 300; ++w) {
    const ContactKey key = key_of(static_cast<int>(rng() % 120));
    const double code = static_cast<double>(rng() % 1000) / 7.0;
    const unsigned field = rng() % 3;
    if (field == 0) {
      table.set_normal(key, code);
      reference[key].normal = code;
    } else if (field == 1) {
      table.set_friction(key, code);
      reference[key].friction = code;
    } else {
      const bool flag = rng() % 2;
      table.set_regularized(key, flag);
      reference[key].regularized = flag;
    }
  }
  table.finish();
  ASSERT_EQ(table.size(), reference.size());
  for (const auto& [key, ref] : reference) {
    const ContactWarmTable::Entry* e = table.find(key);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->normal, ref.normal);
    EXPECT_EQ(e->friction, ref.friction);
    EXPECT_EQ(e->regularized, ref.regularized);
  }
  int flagged = 0;
  for (const auto& [key, ref] : reference) flagged += ref.regularized;
  ASSERT_GT(flagged, 0);
  ASSERT_LT(flagged, static_cast<int>(reference.size()));
  ContactWarmTable copy;
  copy.assign(table.records());
  ASSERT_EQ(copy.size(), table.size());
  for (const auto& [key, ref] : reference) {
    const ContactWarmTable::Entry* e = copy.find(key);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->normal, ref.normal);
    EXPECT_EQ(e->friction, ref.friction);
    EXPECT_EQ(e->regularized, ref.regularized);
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

TEST(ContactWarmTable, FindSortedIsFindForEveryKey) {
  std::mt19937 rng(8);
  ContactWarmTable table;
  for (int k = 0; k < 400; k += 1 + static_cast<int>(rng() % 3)) table.set_normal(key_of(k), k);
  table.finish();
  std::vector<ContactKey> keys;
  for (int k = 0; k < 420; ++k) keys.push_back(key_of(k));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<const ContactWarmTable::Entry*> out;
  for (int order = 0; order < 3; ++order) {
    if (order == 1) std::shuffle(keys.begin(), keys.end(), rng);
    if (order == 2) keys.push_back(keys.front());  // a repeated key
    table.find_sorted(keys, out);
    ASSERT_EQ(out.size(), keys.size());
    int found = 0;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      EXPECT_EQ(out[i], table.find(keys[i])) << "order " << order << " key " << i;
      found += out[i] != nullptr;
    }
    EXPECT_GT(found, 50);
    EXPECT_LT(found, static_cast<int>(keys.size()));
  }
}

TEST(ContactWarmTable, WritesInKeyOrderGiveTheShuffledWritesTable) {
  std::vector<std::pair<ContactKey, double>> writes;
  for (int k = 0; k < 300; ++k) writes.emplace_back(key_of(k), 0.5 * k);
  std::sort(writes.begin(), writes.end());
  writes.erase(std::unique(writes.begin(), writes.end(),
                           [](const auto& a, const auto& b) { return a.first == b.first; }),
               writes.end());
  ContactWarmTable sorted, shuffled;
  for (const auto& [key, code] : writes) {
    sorted.set_normal(key, code);
    sorted.set_friction(key, code + 1);
  }
  std::mt19937 rng(2);
  std::shuffle(writes.begin(), writes.end(), rng);
  for (const auto& [key, code] : writes) {
    shuffled.set_friction(key, code + 1);
    shuffled.set_normal(key, code);
  }
  sorted.finish();
  shuffled.finish();
  const std::vector<ContactWarmRecord> a = sorted.records(), b = shuffled.records();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].key, b[i].key);
    EXPECT_EQ(a[i].normal, b[i].normal);
    EXPECT_EQ(a[i].friction, b[i].friction);
  }
}

}  // namespace
}  // namespace lcprelax
