#pragma once
// A simulation scene: the world (world/world.hpp) plus what a scene file carries about
// simulating it: the simulator's settings (time step, contact model, margin, solver
// settings; models/simulator.hpp) and the number of steps. SI units: seconds, metres.
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/world/world.hpp>

#include <string>
#include <vector>

namespace lcprelax {

struct Scene {
  World world;
  SimulatorSettings settings;  ///< dt, model, softening and margin are read from a scene file
  int steps = 100;             ///< number of steps to simulate, ≥ 0
  std::string name;            ///< free text, may be empty
  /// The simulator's warm-start state to start from (Simulator::warm_start_state: each
  /// contact's part of the last step's basis or active set), e.g. saved with the scene by
  /// `lcprelax pile --save-scene`; empty: the first step starts cold.
  std::vector<ContactWarmRecord> warm_start;

  /// Throws InputError naming the field ("dt: must be > 0", "steps: must be >= 0") when the
  /// settings or the step count are invalid.
  void validate() const;
};

/// A simulator of the scene's world with the scene's settings and warm-start state (throws
/// as Simulator and Simulator::set_warm_start_state do).
Simulator make_simulator(const Scene& scene);

/// A simulator of the scene's world with `solver`'s settings, except dt, model, margin and
/// the convex model's softening (convex_softening), which are the scene's (the scene
/// file's time-stepping and model choices with the caller's solver and threading choices),
/// and the scene's warm-start state.
Simulator make_simulator(const Scene& scene, SimulatorSettings solver);

}  // namespace lcprelax
