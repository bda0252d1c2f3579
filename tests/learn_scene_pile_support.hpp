#pragma once
// The learning piles of the scene-learning tests: a make_learning_pile scene of a few bodies
// and classes, simulated by generate_scene_dataset, of which the last transitions (the
// settled, many-contact end of the drop) are kept.
#include <lcprelax/learn/scene_dataset.hpp>

#include <cstddef>

namespace lcprelax::learn::test {

/// make_learning_pile's options for `bodies` bodies of `classes` shape classes, data by `model`.
inline LearningPileOptions learning_pile_options(int bodies, int classes, ContactModel model) {
  LearningPileOptions po;
  po.bodies = bodies;
  po.classes = classes;
  po.model = model;
  return po;
}

/// The last `keep` transitions (all, when there are fewer) of `scene` simulated for `steps`
/// steps with `ds`'s other settings.
inline SceneDataset last_transitions(const Scene& scene, int steps, std::size_t keep, SceneDatasetSettings ds = {}) {
  ds.steps = steps;
  SceneDataset data = generate_scene_dataset(scene, ds);
  if (data.transitions.size() > keep)
    data.transitions.erase(data.transitions.begin(),
                           data.transitions.end() - static_cast<std::ptrdiff_t>(keep));
  return data;
}

}  // namespace lcprelax::learn::test
