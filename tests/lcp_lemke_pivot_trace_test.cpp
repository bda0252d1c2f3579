// LemkeSolver::set_pivot_trace with a bound (lemke.hpp): the first max_pivots pivots are
// recorded, exactly the start of the unbounded trace, appended to what the vector held,
// without allocating beyond a reserve of 2·max_pivots; the bound does not change the path.
// On the LCP of a generated 186-contact pile step (tests/data/generated, cold path of
// several hundred pivots).
#include <lcprelax/io/siconos_reader.hpp>
#include <lcprelax/lcp/fc2d_lcp.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace lcprelax {
namespace {

struct Traced {
  LcpResult result;
  std::vector<Index> trace;
  std::size_t reserved = 0;  // the trace's capacity before the solve
};

Traced solve(const Fc2dLcp& lcp, long max_pivots, std::vector<Index> prefix = {}) {
  LemkeSettings s;
  s.covering_retries = 0;
  s.regularization_retries = 0;
  LemkeSolver solver(s);
  Traced t;
  t.trace = std::move(prefix);
  if (max_pivots >= 0) t.trace.reserve(t.trace.size() + static_cast<std::size_t>(2 * max_pivots));
  t.reserved = t.trace.capacity();
  solver.set_pivot_trace(&t.trace, max_pivots);
  solver.setup(lcp.M, lcp.q);
  t.result = solver.solve();
  return t;
}

TEST(LemkePivotTrace, BoundedTraceIsTheStartOfTheFullOne) {
  const io::Fc2dData d =
      io::read_siconos_fc2d(std::string(LCPRELAX_TEST_DATA_DIR) + "/generated/fc2d_pile_00186_b60_s150.dat");
  const Fc2dLcp lcp = fc2d_to_lcp(d.W, d.q, d.mu);
  const Traced full = solve(lcp, -1);
  ASSERT_GE(full.result.info.pivots, 50) << full.result.info.message;
  EXPECT_EQ(static_cast<long>(full.trace.size()), 2 * full.result.info.pivots);
  EXPECT_EQ(full.trace.front(), 2 * lcp.q.size()) << "z0 enters first";

  const Traced bounded = solve(lcp, 20, {-7});
  EXPECT_EQ(bounded.result.info.pivots, full.result.info.pivots);
  EXPECT_EQ(bounded.result.info.status, full.result.info.status);
  ASSERT_EQ(bounded.trace.size(), 41u);
  EXPECT_EQ(bounded.trace.front(), -7) << "appended, not cleared";
  EXPECT_EQ(bounded.trace.capacity(), bounded.reserved) << "no allocation beyond the reserve";
  EXPECT_TRUE(std::equal(bounded.trace.begin() + 1, bounded.trace.end(), full.trace.begin()));

  EXPECT_TRUE(solve(lcp, 0).trace.empty());
}

}  // namespace
}  // namespace lcprelax
