// Redundant contacts: rank-deficient contact Jacobians. A 1 m, 1 kg box lies flat on the
// ground at rest (gap 0). Its contact system is built by hand from find_contacts with
// (a) every contact listed twice, (b) a third point in the middle of the bottom face, and
// (c) both; with μ = 0.5 the rows [Jn; Jt] then have rank 3 for up to 6 + 6 rows.
// Expected: solve_lcp_model and solve_convex_model both succeed and return v⁺ = 0 (the
// box stays at rest: |v⁺| < 1e-9 for the LCP, < 1e-7 for the convex model, whose ρ term
// and interior-point tolerance 1e-8 leave a small residual), and the normal impulses sum
// to the weight impulse m·g·Δt (to 1e-9 relative; 1e-6 for the convex model).
// Through the simulator: a box whose bottom face has a nearly collinear middle vertex
// (1e-6 m below the corners: strictly convex, a valid polygon; the narrow phase reports
// the two deepest vertices, so the contact set switches as the box tilts by ±4e-6 rad)
// stays: over 200 steps no failed island and drift < 1e-6 m with both models; the LCP
// model brings it to rest (|v| < 1e-9), the convex model (default ρ = 1e-3, whose term
// makes contact slightly soft) keeps it rocking in a limit cycle of |ω| ≈ 5e-4 rad/s
// (measured; asserted < 1e-3).
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/contact/polygon.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/simulator.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <numeric>

namespace lcprelax {
namespace {

constexpr double kDt = 1e-2;

struct Redundancy {
  bool duplicate = false;  // every contact twice
  bool middle = false;     // a third point at the middle of the bottom face
};

ContactSystem redundant_system(const Redundancy& r) {
  const Scene scene = test::scene_with({test::box(1.0, 1.0, 1.0, Vec3(0.0, 0.5, 0.0))}, 0.5, kDt);
  std::vector<Contact> found = find_contacts(scene.world, CollisionSettings{1e-2});
  EXPECT_EQ(found.size(), 2u);
  std::vector<Contact> contacts;
  for (const Contact& c : found) {
    contacts.push_back(c);
    if (r.duplicate) contacts.push_back(c);
  }
  if (r.middle) {
    Contact c = found.front();
    c.point = 0.5 * (found[0].point + found[1].point);
    contacts.push_back(c);
  }
  Island island;
  island.bodies = {0};
  island.contacts.resize(contacts.size());
  std::iota(island.contacts.begin(), island.contacts.end(), 0);
  return assemble_contact_system(scene.world, contacts, island, kDt);
}

class Redundant : public ::testing::TestWithParam<Redundancy> {};

TEST_P(Redundant, BothModelsKeepTheBoxAtRest) {
  const ContactSystem s = redundant_system(GetParam());
  ASSERT_GE(s.num_contacts(), 3);
  const double weight = 1.0 * 9.81 * kDt;

  const ContactSolution lcp = solve_lcp_model(s, kDt, LemkeSettings{});
  ASSERT_TRUE(has_solution(lcp.status)) << lcp.message;
  EXPECT_LT(lcp.v_next.norm(), 1e-9);
  EXPECT_NEAR(lcp.lambda_n.sum(), weight, 1e-9 * weight);
  EXPECT_TRUE((lcp.lambda_n.array() >= 0).all());

  QpSettings qp;
  qp.eps_abs = 1e-8;
  const ContactSolution convex = solve_convex_model(s, kDt, qp);
  ASSERT_TRUE(has_solution(convex.status)) << convex.message;
  EXPECT_LT(convex.v_next.norm(), 1e-7);
  EXPECT_NEAR(convex.lambda_n.sum(), weight, 1e-6 * weight);
}

INSTANTIATE_TEST_SUITE_P(Cases, Redundant,
                         ::testing::Values(Redundancy{true, false}, Redundancy{false, true}, Redundancy{true, true}));

class CollinearVertex : public ::testing::TestWithParam<ContactModel> {};

TEST_P(CollinearVertex, BoxWithNearlyCollinearBottomVertexRests) {
  const double dip = 1e-6;  // the middle vertex lies this far below the bottom corners
  Polygon p{{Vec2(-0.5, -0.5), Vec2(0.0, -0.5 - dip), Vec2(0.5, -0.5), Vec2(0.5, 0.5), Vec2(-0.5, 0.5)}};
  ASSERT_EQ(polygon_validation_error(p), "");
  RigidBody body = make_body(p, 1.0, Vec3::Zero());
  // Rest the middle vertex on the ground (the centroid is slightly below the box centre).
  body.pose = Vec3(0.0, -world_vertices(body)[1].y(), 0.0);
  Simulator sim = make_simulator(test::scene_with({body}, 0.5, kDt, GetParam()));
  const std::vector<Vec3> start = test::poses(sim.world());
  for (int k = 0; k < 200; ++k) {
    const StepStats st = sim.step();
    ASSERT_EQ(st.failed_islands, 0) << "step " << k << ": " << st.first_failure;
  }
  EXPECT_LT(test::max_drift(sim.world(), start), 1e-6);
  EXPECT_LT(sim.world().bodies[0].velocity.norm(), GetParam() == ContactModel::lcp ? 1e-9 : 1e-3);
}

INSTANTIATE_TEST_SUITE_P(LcpAndConvex, CollinearVertex, ::testing::Values(ContactModel::lcp, ContactModel::convex));

}  // namespace
}  // namespace lcprelax
