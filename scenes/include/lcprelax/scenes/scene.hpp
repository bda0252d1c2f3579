#pragma once
// A simulation scene: the world (world/world.hpp) plus what a scene file carries about
// simulating it: the simulator's settings (time step, contact model, margin, solver
// settings; models/simulator.hpp) and the number of steps. SI units: seconds, metres.
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/world/world.hpp>

#include <string>

namespace lcprelax {

struct Scene {
  World world;
  SimulatorSettings settings;  ///< dt, model, softening and margin are read from a scene file
  int steps = 100;             ///< number of steps to simulate, ≥ 0
  std::string name;            ///< free text, may be empty

  /// Throws InputError naming the field ("dt: must be > 0", "steps: must be >= 0") when the
  /// settings or the step count are invalid.
  void validate() const;
};

/// A simulator of the scene's world with the scene's settings (throws as Simulator does).
Simulator make_simulator(const Scene& scene);

/// A simulator of the scene's world with `solver`'s settings, except dt, model, margin and
/// the convex model's softening (convex_softening), which are the scene's (the scene
/// file's time-stepping and model choices with the caller's solver and threading choices).
Simulator make_simulator(const Scene& scene, SimulatorSettings solver);

}  // namespace lcprelax
