#pragma once
// The wedged box of the lcp model's regularized attempt (models_lcp_regularized_test,
// learn_step_loss_hard_attempts_test): a 0.1 m box (10 kg) in the air, wedged 0.1 mm into
// two walls, whose four wall contacts can push against each other with forces that cancel.
// A per-contact q bias b on the normal rows (world.hpp ContactLcpBlock; enabled when b ≠ 0)
// below zero makes its LCP infeasible.
#include <lcprelax/contact/collision.hpp>
#include <lcprelax/models/contact_system.hpp>

#include "dynamics_support.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace lcprelax::test {

/// The wedge's one island with normal-row bias b (m/s) and friction μ, for time step dt (s).
inline ContactSystem wedged_box_system(double bias, double mu, double dt) {
  World world;
  world.bodies.push_back(box(0.1, 0.1, 10.0, Vec3(0.0, 1.0, 0.0)));
  world.half_planes.push_back(HalfPlane{Vec2(1.0, 0.0), -0.0499, 0});   // solid x < −0.0499
  world.half_planes.push_back(HalfPlane{Vec2(-1.0, 0.0), -0.0499, 0});  // solid x > 0.0499
  world.friction.default_mu = mu;
  world.lcp_block.enabled = bias != 0.0;
  world.lcp_block.q = Vec4(bias, 0.0, 0.0, 0.0);
  const std::vector<Contact> contacts = find_contacts(world, CollisionSettings{1e-2});
  const std::vector<Island> islands = find_islands(world, contacts);
  EXPECT_EQ(islands.size(), 1u);
  return assemble_contact_system(world, contacts, islands.front(), dt);
}

}  // namespace lcprelax::test
