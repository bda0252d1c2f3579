// The Simulator's warm-start state as values (simulator.hpp warm_start_state,
// set_warm_start_state; ContactWarmTable::records / assign). Expected:
// - a simulator built from another's world and warm-start state steps on exactly as the
//   original does (bit for bit, lcp model, a dropping pile), and its first step is warm
//   started like the original's, while a copy without the state starts cold and pivots more;
// - records() lists the table in key order; assign() of records reproduces them, a key
//   listed twice keeping its last record;
// - records that cannot be a contact's entry are refused with an InputError naming the
//   record and what is wrong, and leave the state as it was.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include <string>
#include <vector>

namespace lcprelax {
namespace {

TEST(WarmStartState, ACopyWithTheStateStepsOnAsTheOriginal) {
  Simulator original = test::pile_simulator(30, 4, ContactModel::lcp);
  EXPECT_TRUE(original.warm_start_state().empty());
  for (int k = 0; k < 80; ++k) original.step();
  const std::vector<ContactWarmRecord> state = original.warm_start_state();
  ASSERT_GT(state.size(), 20u);
  Simulator warm(original.world(), original.settings()), cold(original.world(), original.settings());
  warm.set_warm_start_state(state);
  EXPECT_EQ(warm.warm_start_state().size(), state.size());
  const StepStats cold_first = cold.step();
  for (int k = 0; k < 20; ++k) {
    const StepStats a = original.step(), b = warm.step();
    ASSERT_EQ(a.work, b.work) << "step " << k;
    ASSERT_EQ(a.warm_started_islands, b.warm_started_islands) << "step " << k;
    if (k == 0) {
      EXPECT_LT(b.work, cold_first.work);  // the cold copy's first step pivots more
    }
  }
  for (std::size_t i = 0; i < original.world().bodies.size(); ++i) {
    EXPECT_EQ(original.world().bodies[i].pose, warm.world().bodies[i].pose) << "body " << i;
    EXPECT_EQ(original.world().bodies[i].velocity, warm.world().bodies[i].velocity) << "body " << i;
  }
}

TEST(WarmStartState, RecordsRoundTripThroughTheTable) {
  ContactWarmTable table;
  table.assign({{{3, -1, 1, 0, 0}, 1.0, 6.0}, {{0, 2, 0, -1, 1}, 0.0, 1.0}, {{3, -1, 1, 0, 0}, 0.0, 4.0}});
  const std::vector<ContactWarmRecord> r = table.records();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].key, (ContactKey{0, 2, 0, -1, 1}));  // key order
  EXPECT_EQ(r[0].friction, 1.0);
  EXPECT_EQ(r[1].key, (ContactKey{3, -1, 1, 0, 0}));
  EXPECT_EQ(r[1].normal, 0.0);  // the later record of the same key
  EXPECT_EQ(r[1].friction, 4.0);
  ContactWarmTable again;
  again.assign(r);
  const std::vector<ContactWarmRecord> s = again.records();
  ASSERT_EQ(s.size(), r.size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    EXPECT_EQ(s[i].key, r[i].key);
    EXPECT_EQ(s[i].normal, r[i].normal);
    EXPECT_EQ(s[i].friction, r[i].friction);
  }
}

TEST(WarmStartState, BadRecordsAreRefusedNamingTheRecord) {
  Simulator sim = test::pile_simulator(5, 1, ContactModel::lcp);
  const ContactWarmRecord good{{0, -1, 1, 0, 0}, 1.0, 2.0};
  sim.set_warm_start_state({good});
  struct Case {
    ContactWarmRecord record;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{{5, -1, 1, 0, 0}, 1.0, 0.0}, "warm_start[1]: body a = 5 is not a body index"},
      {{{-1, 0, 0, -1, 0}, 1.0, 0.0}, "warm_start[1]: body a = -1"},
      {{{0, 7, 0, -1, 0}, 1.0, 0.0}, "warm_start[1]: body b = 7"},
      {{{0, -1, 3, 0, 0}, 1.0, 0.0}, "warm_start[1]: static kind = 3"},
      {{{0, -1, 1, -2, 0}, 1.0, 0.0}, "warm_start[1]: static index = -2"},
      {{{0, -1, 1, 0, -1}, 1.0, 0.0}, "warm_start[1]: ordinal = -1"},
      {{{0, -1, 1, 0, 0}, 0.5, 0.0}, "warm_start[1]: normal code must be 0 or 1"},
      {{{0, -1, 1, 0, 0}, 1.0, 8.0}, "warm_start[1]: friction code must be an integer in 0..7"},
      {{{0, -1, 1, 0, 0}, 1.0, 2.5}, "warm_start[1]: friction code"},
      {{{0, -1, 1, 0, 0}, std::nan(""), 0.0}, "warm_start[1]: normal code"},
  };
  for (const Case& c : cases) {
    try {
      sim.set_warm_start_state({good, c.record});
      ADD_FAILURE() << "accepted: " << c.message;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
    ASSERT_EQ(sim.warm_start_state().size(), 1u);  // unchanged
    EXPECT_EQ(sim.warm_start_state()[0].friction, 2.0);
  }
}

}  // namespace
}  // namespace lcprelax
