// The nonphysical terms of an island's ContactSystem (models/contact_system.hpp):
// φ_c += gap_offset_a + gap_offset_b, v*_body += W (vx, vy, ω, 1). Their reverse mode
// (accumulate_world_gradient) against central differences of assemble_contact_system on
// every island of a learning pile step, and against the forward mode
// (contact_system_tangent): ⟨ct, tangent(dir)⟩ = ⟨gradient(ct), dir⟩.
#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/models/contact_system_gradient.hpp>
#include <lcprelax/models/simulator.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace lcprelax {
namespace {

// ⟨ct, (φ, v*)⟩ of a system: the only data the structured terms move.
double pairing(const ContactSystemCotangent& ct, const ContactSystem& s) {
  return ct.phi.dot(s.phi) + ct.v_star.dot(s.v_star);
}

TEST(ContactSystemStructured, GapOffsetAndResidualPullBackAndPushForward) {
  World world = learn::make_learning_pile(learn::LearningPileOptions{}).world;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (RigidBody& b : world.bodies) {
    b.gap_offset = 1e-3 * u(rng);
    for (Index k = 0; k < 12; ++k) b.velocity_residual(k / 4, k % 4) = 0.05 * u(rng);
    b.velocity = Vec3(u(rng), u(rng), u(rng));
  }
  const SimulatorSettings settings;
  const StepContacts found = find_step_contacts(world, settings);
  ASSERT_FALSE(found.islands.empty());
  const double dt = settings.dt;
  int compared = 0;
  for (const Island& island : found.islands) {
    const ContactSystem s = assemble_contact_system(world, found.contacts, island, dt);
    ContactSystemCotangent ct;
    ct.set_zero(s);
    for (Index i = 0; i < ct.phi.size(); ++i) ct.phi(i) = u(rng);
    for (Index i = 0; i < ct.v_star.size(); ++i) ct.v_star(i) = u(rng);
    WorldGradient g;
    g.set_zero(world, found.contacts.size());
    accumulate_world_gradient(world, found.contacts, s, dt, {}, ct, g);
    WorldGradient dir;
    dir.set_zero(world, found.contacts.size());
    for (int b : island.bodies) {
      // Central differences of ⟨ct, data⟩ in each body's offset and each W entry.
      const double h = 1e-6;
      auto moved = [&](auto set) {
        World w = world;
        set(w.bodies[static_cast<std::size_t>(b)]);
        return pairing(ct, assemble_contact_system(w, found.contacts, island, dt));
      };
      const double d_gap = (moved([&](RigidBody& r) { r.gap_offset += h; }) -
                            moved([&](RigidBody& r) { r.gap_offset -= h; })) / (2 * h);
      EXPECT_NEAR(g.bodies[b].gap_offset, d_gap, 1e-7 * (1.0 + std::abs(d_gap))) << "body " << b;
      for (Index k = 0; k < 12; ++k) {
        const double d_w = (moved([&](RigidBody& r) { r.velocity_residual(k / 4, k % 4) += h; }) -
                            moved([&](RigidBody& r) { r.velocity_residual(k / 4, k % 4) -= h; })) / (2 * h);
        EXPECT_NEAR(g.bodies[b].velocity_residual(k / 4, k % 4), d_w, 1e-7 * (1.0 + std::abs(d_w)))
            << "body " << b << " entry " << k;
      }
      dir.bodies[b].gap_offset = u(rng);
      for (Index k = 0; k < 12; ++k) dir.bodies[b].velocity_residual(k / 4, k % 4) = u(rng);
      ++compared;
    }
    const ContactSystem t = contact_system_tangent(world, found.contacts, s, dt, {}, dir);
    double reverse = 0.0;
    for (int b : island.bodies)
      reverse += g.bodies[b].gap_offset * dir.bodies[b].gap_offset +
                 (g.bodies[b].velocity_residual.array() * dir.bodies[b].velocity_residual.array()).sum();
    EXPECT_NEAR(pairing(ct, t), reverse, 1e-12 * (1.0 + std::abs(reverse)));
  }
  EXPECT_GT(compared, 5);
}

}  // namespace
}  // namespace lcprelax
