// Scene learning on a resting two-box stack (scenes/pile_scene.hpp make_box_stack_scene):
// ∂ℓ/∂θ of μ, the class's mass and its inertia for the hard, relaxed and convex losses
// against central differences of the whole pipeline, on every transition. A stack of
// axis-aligned boxes is the case where the inertia enters only through the contacts'
// lever arms in W = J M⁻¹ Jᵀ (no body rotates), so its derivative is small beside μ's and
// mass's; tolerances are relative to each parameter's own derivative (floor 1e-3 of the
// largest), as learn_scene_fd_support.hpp states. The losses' QPs are solved to 1e-12/1e-14
// (test::fd_loss_settings): at the default 1e-8 the convex loss's inertia derivative here
// is 27% off its central difference (−1.01e-5 against −7.93e-6), an interior-point
// tolerance effect on a derivative 100× smaller than μ's, not a wrong formula.
#include "learn_scene_fd_support.hpp"

#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/learn/scene_objective.hpp>
#include <lcprelax/scenes/pile_scene.hpp>

#include <gtest/gtest.h>

namespace lcprelax::learn {
namespace {

void check_stack(LossMethod method, const std::vector<Index>& samples) {
  SceneDatasetSettings ds;
  ds.steps = 30;
  const SceneDataset data = generate_scene_dataset(make_box_stack_scene(2, 0.1, 0.5), ds);
  const SceneParameterMap map(data.scene.world, SceneParameterSettings{});
  const ParameterSet theta = perturb_scene_parameters(map.parameters(data.scene.world), map, 0.2, 1);
  SceneObjective objective(data, map, test::fd_loss_settings(method));
  // μ, the mass and the inertia (the vertices sit on kinks here: box corners on the ground).
  std::vector<Index> all;
  for (Index k = 0; k < theta.size(); ++k)
    if (theta[k].name == "mu" || theta[k].name == "class0.mass" || theta[k].name == "class0.inertia") all.push_back(k);
  ASSERT_EQ(all.size(), 3u);
  for (Index sample : samples) {
    const test::FdReport report = test::compare_with_central_differences(
        objective, map, theta, sample, all, std::string(to_string(method)) + ", sample " + std::to_string(sample));
    EXPECT_EQ(report.kinks, 0);
  }
}

TEST(SceneBoxStackGradient, Convex) { check_stack(LossMethod::convex, {0, 10, 29}); }
TEST(SceneBoxStackGradient, Relaxed) { check_stack(LossMethod::relaxed, {0, 10, 29}); }
// Transition 0 (the stack at rest before any push) has a hard loss of ~1e-24: only roundoff.
TEST(SceneBoxStackGradient, Hard) { check_stack(LossMethod::hard, {10, 29}); }

}  // namespace
}  // namespace lcprelax::learn
