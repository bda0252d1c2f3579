#pragma once
// Contact islands for the step-loss tests: the largest island of a world (as the simulator
// poses it), a box stack's island, a settled pile's island, and a visitor over every data
// entry of a ContactSystem with its cotangent (for finite differences).
#include <lcprelax/models/contact_system_gradient.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>
#include <lcprelax/scenes/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>

namespace lcprelax::testing {

/// The island of `world` with the most contacts (the simulator's margin and islands).
inline ContactSystem largest_island(const World& world, const SimulatorSettings& settings) {
  const StepContacts sc = find_step_contacts(world, settings);
  std::size_t best = 0;
  for (std::size_t i = 1; i < sc.islands.size(); ++i)
    if (sc.islands[i].contacts.size() > sc.islands[best].contacts.size()) best = i;
  EXPECT_FALSE(sc.islands.empty());
  return assemble_contact_system(world, sc.contacts, sc.islands[best], settings.dt);
}

/// A stack of `boxes` 0.2 m boxes on the ground, friction μ.
inline ContactSystem box_stack(int boxes, double mu) {
  const Scene scene = make_box_stack_scene(boxes, 0.2, mu);
  return largest_island(scene.world, scene.settings);
}

/// The largest island of a pile of `bodies` (seed) after `steps` simulator steps, with
/// one post-stabilization pass (the islands the step-loss tests were measured on; the
/// simulator's default of 5 settles the pile into other islands).
inline ContactSystem settled_pile_island(int bodies, std::uint64_t seed, int steps) {
  PileOptions o;
  o.bodies = bodies;
  o.seed = seed;
  Scene scene = make_pile_scene(o);
  scene.settings.post_stabilization_passes = 1;
  Simulator sim = make_simulator(scene);
  for (int k = 0; k < steps; ++k) sim.step();
  return largest_island(sim.world(), sim.settings());
}

/// Visits every data entry: fn(value reference, cotangent value, kind name).
inline void for_each_entry(ContactSystem& s, const ContactSystemCotangent& g,
                           const std::function<void(double&, double, const std::string&)>& fn) {
  for (Index k = 0; k < s.Jn.nonZeros(); ++k) {
    const Index col = std::upper_bound(s.Jn.outerIndexPtr(), s.Jn.outerIndexPtr() + s.Jn.cols() + 1, k) -
                      s.Jn.outerIndexPtr() - 1;
    fn(s.Jn.valuePtr()[k], g.Jn.coeff(s.Jn.innerIndexPtr()[k], col), "Jn");
  }
  for (Index k = 0; k < s.Jt.nonZeros(); ++k) {
    const Index col = std::upper_bound(s.Jt.outerIndexPtr(), s.Jt.outerIndexPtr() + s.Jt.cols() + 1, k) -
                      s.Jt.outerIndexPtr() - 1;
    fn(s.Jt.valuePtr()[k], g.Jt.coeff(s.Jt.innerIndexPtr()[k], col), "Jt");
  }
  for (Index c = 0; c < s.phi.size(); ++c) fn(s.phi(c), g.phi(c), "phi");
  for (Index f = 0; f < s.mu.size(); ++f) fn(s.mu(f), g.mu(f), "mu");
  for (Index k = 0; k < s.minv.size(); ++k) fn(s.minv(k), g.minv(k), "minv");
  for (Index k = 0; k < s.v_star.size(); ++k) fn(s.v_star(k), g.v_star(k), "v_star");
}

}  // namespace lcprelax::testing
