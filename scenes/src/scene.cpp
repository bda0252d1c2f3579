// Scene validation and the simulator of a scene (scenes/scene.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/scenes/scene.hpp>

#include <utility>

namespace lcprelax {

void Scene::validate() const {
  if (std::string e = settings.validation_error(); !e.empty()) throw InputError(e);
  if (steps < 0) throw InputError("steps: must be >= 0");
}

Simulator make_simulator(const Scene& scene) { return make_simulator(scene, scene.settings); }

Simulator make_simulator(const Scene& scene, SimulatorSettings solver) {
  solver.dt = scene.settings.dt;
  solver.model = scene.settings.model;
  solver.margin = scene.settings.margin;
  solver.convex_softening = scene.settings.convex_softening;
  Simulator sim(scene.world, std::move(solver));
  if (!scene.warm_start.empty()) sim.set_warm_start_state(scene.warm_start);
  return sim;
}

}  // namespace lcprelax
